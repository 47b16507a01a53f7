// Runs a fuzz target without libFuzzer (any compiler): every file of the corpus named on the
// command line (files, or directories of them), then deterministic mutations of each (byte
// changes, inserted tokens, 8-byte integers written over the bytes, truncations, erased and
// repeated stretches), so that the suite exercises the parsers on malformed input even where
// clang is absent.
// Usage: fuzz_<target>_replay [--mutations N] CORPUS... (N mutations per corpus file, 3000 by
// default). A named file or directory that gives no input fails the run: a corpus moved or
// emptied would otherwise replay nothing and pass.
#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "hpcplan/core/splitmix64.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);

namespace {

bool read_file(const std::filesystem::path& path, std::vector<std::string>& corpus) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  if (!in || s.str().empty()) {
    std::fprintf(stderr, "fuzz replay: cannot read corpus file '%s' (or it is empty)\n",
                 path.c_str());
    return false;
  }
  corpus.push_back(s.str());
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  long mutations = 3000;
  std::vector<std::string> corpus;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--mutations") == 0 && i + 1 < argc) {
      mutations = std::strtol(argv[++i], nullptr, 10);
      continue;
    }
    const std::size_t before = corpus.size();
    std::error_code ec;
    if (std::filesystem::is_directory(argv[i], ec)) {
      for (const auto& e : std::filesystem::directory_iterator(argv[i], ec))
        if (e.is_regular_file() && !read_file(e.path(), corpus)) return 1;
    } else if (!read_file(argv[i], corpus)) {
      return 1;
    }
    if (corpus.size() == before) {
      std::fprintf(stderr, "fuzz replay: '%s' holds no corpus file\n", argv[i]);
      return 1;
    }
  }
  if (corpus.empty()) {
    std::fprintf(stderr, "usage: %s [--mutations N] CORPUS...\n", argv[0]);
    return 1;
  }
  // Tokens of the text formats (maps, option values, file names) and numbers at the edges,
  // inserted; 8-byte integers at the edges, written over the bytes (the checkpoints' counts).
  const std::string_view words = "boundary block start goal sphere fluid_ .vtu nan inf";
  const std::string_view numbers = "010 0x1p3 1e308 1e-400 4294967296 18446744073709551616";
  std::vector<std::string> tokens = {"#", "\r\n", "\t", " ", "/", ",", "[", "]", "+", "-", "."};
  for (const std::string_view list : {words, numbers})
    for (std::size_t at = 0; at < list.size();) {
      const std::size_t end = std::min(list.find(' ', at), list.size());
      tokens.emplace_back(list.substr(at, end - at));
      at = end + 1;
    }
  const std::uint64_t integers[] = {
      0, 1, 2, 7, 0xff, 0x7fffffff, 0xffffffff, 1ull << 32, 1ull << 62, ~0ull >> 1, ~0ull};
  hpcplan::SplitMix64 rng(2026);
  std::size_t runs = 0;
  for (const std::string& seed : corpus) {
    LLVMFuzzerTestOneInput(reinterpret_cast<const std::uint8_t*>(seed.data()), seed.size());
    for (long i = 0; i < mutations; ++i) {
      std::string s = seed;
      for (int m = 0, n = 1 + static_cast<int>(rng.next_below(4)); m < n && !s.empty(); ++m) {
        const std::size_t at = rng.next_below(s.size());
        switch (rng.next_below(6)) {
          case 0:
            s[at] = static_cast<char>(rng.next_below(256));
            break;
          case 1:
            s.insert(at, tokens[rng.next_below(tokens.size())]);
            break;
          case 2:
            s.resize(at);
            break;
          case 3: {
            const std::uint64_t v = integers[rng.next_below(std::size(integers))];
            s.replace(at, sizeof v, reinterpret_cast<const char*>(&v), sizeof v);
            break;
          }
          case 4:
            s.insert(at, s.substr(rng.next_below(s.size()), rng.next_below(16)));
            break;
          default:
            s.erase(at, rng.next_below(16));
            break;
        }
      }
      LLVMFuzzerTestOneInput(reinterpret_cast<const std::uint8_t*>(s.data()), s.size());
      ++runs;
    }
  }
  std::printf("replayed %zu corpus files and %zu mutations\n", corpus.size(), runs);
  return 0;
}
