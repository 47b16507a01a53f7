#include "engine_checkpoint.hpp"

#include <sstream>

#include "hpcplan/core/atomic_file.hpp"

namespace hpcplan::dense {

std::string rank_file(const std::string& file, int rank, int ranks) {
  return ranks <= 1 ? file : file + ".r" + std::to_string(rank);
}

namespace detail {
namespace {

constexpr std::string_view kMagic = "hpcplan dense lattice checkpoint\n";
// 2: the BFS saves its store of three words a tile and active bitmaps (was: codes and lists).
constexpr std::uint32_t kFormat = 2;
constexpr std::string_view kKind =
    "an hpcplan dense lattice checkpoint (hpcplan grid --checkpoint)";

std::string coords(const std::vector<int>& c) {
  std::string s;
  for (std::size_t i = 0; i < c.size(); ++i) {
    if (i) s += ',';
    s += std::to_string(c[i]);
  }
  return s;
}

// The first line of `a` that differs from `b`'s, and `b`'s.
std::pair<std::string, std::string> first_difference(const std::string& a, const std::string& b) {
  std::istringstream ia(a), ib(b);
  std::string la, lb;
  while (true) {
    const bool ga = static_cast<bool>(std::getline(ia, la));
    const bool gb = static_cast<bool>(std::getline(ib, lb));
    if (!ga && !gb) return {};
    if (!ga) la.clear();
    if (!gb) lb.clear();
    if (la != lb) return {la, lb};
  }
}

}  // namespace

std::string run_identity(const ObstacleSource& field, const Query& q, const SlabMap& slabs) {
  std::ostringstream o;
  o << "engine = " << (q.algorithm == Algorithm::bfs ? "bfs" : "dijkstra") << "\n"
    << "dims = " << field.dims() << "\n"
    << "extent = " << field.extent() << "\n";
  if (field.is_gog()) {
    const GogParams& g = field.gog().params();
    o << "seed = " << g.seed << "\n"
      << "threshold = " << field.gog().threshold() << "\n"
      << "gog shifts = " << g.shift_p << "," << g.shift_v << "\n";
  } else {
    // The grid's shape and bits: a restart on another map (or an edited one) is refused.
    const OccupancyGrid& grid = field.occupancy();
    o << "occupancy = " << coords(grid.shape()) << "\n"
      << "occupancy checksum = " << grid.checksum() << "\n";
  }
  o << "connectivity = " << (q.connectivity == Connectivity::full ? "full" : "seed") << "\n"
    << "start = " << coords(q.start) << "\n"
    << "goal = " << coords(q.goal) << "\n";
  // BFS always keeps what its walk back needs; Dijkstra's --path adds each state's class.
  if (q.algorithm == Algorithm::dijkstra) o << "path = " << (q.keep_path ? "yes" : "no") << "\n";
  o << "ranks = " << slabs.ranks << "\n"
    << "rank = " << slabs.rank << "\n"
    << "threads = " << slabs.threads << "\n"
    << "layers per block = " << slabs.block_sections << "\n";
  // (Added with cuts below the last axis; absent where the cut is the last axis, so that
  // checkpoints written before it still open.)
  if (slabs.cut_axis != field.dims() - 1) o << "cut axis = " << slabs.cut_axis << "\n";
  o << "tiles held = " << slabs.store_tiles << "\n";
  return o.str();
}

void write_checkpoint(const std::string& path, const std::string& identity,
                      const std::string& payload) {
  checkpoint::Writer w;
  w.put_string(identity);
  w.bytes() += payload;
  write_file_atomically(path, checkpoint::seal(kMagic, kFormat, w.bytes()));
}

std::string read_checkpoint_file(const std::string& path) {
  return checkpoint::read_regular_file(path, kMagic, kKind);
}

std::string_view open_checkpoint(std::string_view bytes, const std::string& name,
                                 const std::string& identity) {
  const std::string_view payload = checkpoint::open(bytes, kMagic, kFormat, kKind, name);
  checkpoint::Reader r(payload, name);
  const std::string saved = r.get_string();
  if (saved != identity) {
    const auto [was, now] = first_difference(saved, identity);
    r.fail("was written for another run (" + (was.empty() ? "nothing" : was) + "; this run has " +
           (now.empty() ? "nothing" : now) + ")");
  }
  return payload.substr(payload.size() - r.left());
}

}  // namespace detail
}  // namespace hpcplan::dense
