// libFuzzer target for the dense engine's checkpoint (hpcplan grid --restart,
// dense/dense_checkpoint.hpp): any byte string, restarted from, must either continue the search
// or be refused with an InputError; a crafted file that passes every check but holds a state
// no search reaches may end in a RunError (the walk back finds no predecessor). Any other
// exception, a crash, a sanitizer report or a hang is a bug.
//
// Each input is tried twice on a small lattice (3D, extent 12): as a whole file (the envelope
// first, whose checksum a mutation almost never passes), and, after its first byte (which picks
// BFS or Dijkstra, on one or two threads; Dijkstra on two with --path), as the engine's payload
// sealed into a sound file with the identity of that run, so that mutations reach the payload's
// checks (the frontier's and the pending classes' tiles, the counts, the store's size). The
// identities and the file's kind come from genuine checkpoints written when the target starts; with
// HPCPLAN_FUZZ_WRITE_SEEDS=DIR it also writes those as seeds (tests/fuzz/corpus).
#include <unistd.h>

#include <array>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <memory>
#include <string>
#include <string_view>

#include "hpcplan/core/checkpoint_file.hpp"
#include "hpcplan/core/error.hpp"
#include "hpcplan/dense/dense_search.hpp"

namespace {

using namespace hpcplan;

struct Run {
  dense::Query query;
  std::string magic, identity;
  std::uint32_t format = 0;
};

const GogField& field() {
  static const GogField f(3, 12, [] {
    GogParams p;
    p.seed = 3;
    return p;
  }());
  return f;
}

// One file per process, removed at its exit.
std::string temp_file() {
  struct File {
    std::string path = "/tmp/hpcplan-fuzz-grid-" + std::to_string(::getpid());
    ~File() { std::remove(path.c_str()); }
  };
  static const File file;
  return file.path;
}

void write(const std::string& path, std::string_view bytes) {
  std::ofstream(path, std::ios::binary | std::ios::trunc).write(bytes.data(), bytes.size());
}

std::string read(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

// The four runs an input's first byte picks, each with a genuine checkpoint's identity.
const std::array<Run, 4>& runs() {
  static const std::array<Run, 4> all = [] {
    std::array<Run, 4> r;
    const char* seeds = std::getenv("HPCPLAN_FUZZ_WRITE_SEEDS");
    for (int i = 0; i < 4; ++i) {
      dense::Query& q = r[i].query;
      q.start = {0, 0, 0};
      q.goal = {11, 11, 11};
      for (long s = 0; !field().is_free(q.start); ++s) ++q.start[s % 3];
      for (long s = 0; !field().is_free(q.goal); ++s) --q.goal[s % 3];
      q.algorithm = i % 2 ? dense::Algorithm::dijkstra : dense::Algorithm::bfs;
      q.keep_path = i == 3;  // each state's class (8 bytes a state) in one run only
      q.threads = i < 2 ? 1 : 2;
      dense::Query first = q;
      first.checkpointing.path = temp_file();
      auto calls = std::make_shared<int>(0);
      first.checkpointing.interrupted = [calls] { return ++*calls == 4; };
      dense::LocalTransport local;
      if (dense::search(field(), first, local).status != Status::interrupted) std::abort();
      const std::string file = read(temp_file());
      r[i].magic = file.substr(0, file.find('\n') + 1);
      checkpoint::Reader head(std::string_view(file).substr(r[i].magic.size()), "seed");
      r[i].format = head.get<std::uint32_t>();
      const std::string_view payload =
          checkpoint::open(file, r[i].magic, r[i].format, "a grid checkpoint", "seed");
      checkpoint::Reader p(payload, "seed");
      r[i].identity = p.get_string();
      if (seeds) {
        const std::string dir = seeds;
        write(dir + "/file_" + std::to_string(i), file);
        std::string mine(1, static_cast<char>(i));
        mine += payload.substr(payload.size() - p.left());
        write(dir + "/payload_" + std::to_string(i), mine);
      }
    }
    return r;
  }();
  return all;
}

void restart(dense::Query q) {
  q.checkpointing = {};
  q.checkpointing.restart = temp_file();
  dense::LocalTransport local;
  try {
    (void)dense::search(field(), q, local);
  } catch (const InputError&) {
  } catch (const RunError&) {
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  const auto& all = runs();
  // The whole file, restarted by each run.
  write(temp_file(), bytes);
  restart(all[0].query);
  restart(all[3].query);
  // The payload behind a sound envelope and identity.
  if (size == 0) return 0;
  const Run& run = all[data[0] % 4];
  checkpoint::Writer w;
  w.put_string(run.identity);
  w.bytes().append(bytes.substr(1));
  write(temp_file(), checkpoint::seal(run.magic, run.format, w.bytes()));
  restart(run.query);
  return 0;
}
