// The dense engine's shared pieces that are not templates (engine_common.hpp).
#include "engine_common.hpp"

namespace hpcplan::dense::detail {

int cut_axis_for(const TileLayout& layout, int workers) {
  const std::uint64_t wanted = static_cast<std::uint64_t>(kSectionsPerWorker) *
                               static_cast<std::uint64_t>(std::max(1, workers));
  int cut = layout.dims() - 1;
  if (workers <= 1) return cut;
  std::uint64_t sections = static_cast<std::uint64_t>(layout.tiles(cut));
  // Down through the axes of one cell per tile, while the sections stay few enough to list
  // (one int each) and there are too few of them, and over kMaxCutAxes axes at most (a
  // section has 3^k - 1 neighbours to look through for peers over k axes).
  const int lowest = std::max(layout.in_tile_axes(), layout.dims() - kMaxCutAxes);
  while (sections < wanted && cut - 1 >= lowest &&
         sections * static_cast<std::uint64_t>(layout.tiles(cut - 1)) <= (std::uint64_t{1} << 30))
    sections *= static_cast<std::uint64_t>(layout.tiles(--cut));
  return cut;
}

SlabMap plan_slabs(const ObstacleSource& field, const TileLayout& layout, int rank, int ranks,
                   int threads, int block_sections) {
  SlabMap s;
  s.rank = rank;
  s.ranks = ranks;
  const int workers = ranks * std::max(1, threads);
  const int dims = layout.dims();
  s.cut_axis = cut_axis_for(layout, workers);
  s.section_tiles = static_cast<std::uint64_t>(layout.stride(s.cut_axis));
  s.section_inverse = 1.0 / static_cast<double>(s.section_tiles);
  int sections = 1;
  for (int a = s.cut_axis; a < dims; ++a) sections *= layout.tiles(a);
  if (block_sections < 0)
    block_sections = workers == 1 ? sections : std::max(4, sections / (kBlocksPerWorker * workers));
  s.block_sections = block_sections;
  if (block_sections == 0) {
    const std::vector<double> weights = free_states_per_section(field, layout, s.cut_axis);
    const std::vector<int> rb = balanced_slabs(weights, ranks);
    for (int r = 0; r < ranks; ++r) {
      const int n = rb[r + 1] - rb[r];
      const int t = std::max(1, std::min(threads, n));
      if (n == 0) continue;
      const std::vector<double> part(weights.begin() + rb[r], weights.begin() + rb[r + 1]);
      const std::vector<int> tb = balanced_slabs(part, t);
      for (int k = 0; k < t; ++k)
        if (tb[k + 1] > tb[k]) s.blocks.push_back({rb[r] + tb[k], rb[r] + tb[k + 1], r, k});
    }
  } else {
    std::vector<int> count(ranks, 0);
    for (int z = 0, j = 0; z < sections; z += block_sections, ++j) {
      const int r = j % ranks;
      s.blocks.push_back({z, std::min(sections, z + block_sections), r, count[r]++});
    }
    // Each rank's k-th block to thread k mod (its threads).
    for (Block& b : s.blocks) b.thread %= std::max(1, std::min(threads, count[b.rank]));
  }
  s.threads = 1;
  for (const Block& b : s.blocks)
    if (b.rank == rank) s.threads = std::max(s.threads, b.thread + 1);
  s.thread_tiles.assign(s.threads, 0);
  s.rank_sections.assign(ranks, 0);
  s.section_block.assign(sections, 0);
  for (std::size_t j = 0; j < s.blocks.size(); ++j) {
    Block& b = s.blocks[j];
    b.lo = static_cast<std::uint64_t>(b.s0) * s.section_tiles;
    b.hi = static_cast<std::uint64_t>(b.s1) * s.section_tiles;
    for (int z = b.s0; z < b.s1; ++z) s.section_block[z] = static_cast<int>(j);
    s.rank_sections[b.rank] += b.s1 - b.s0;
    if (b.rank != rank) continue;
    b.store = s.store_tiles;
    s.store_tiles += b.hi - b.lo;
    b.mark = s.thread_tiles[b.thread];
    s.thread_tiles[b.thread] += b.hi - b.lo;
  }
  // The peers: owners of the sections next to this rank's own, over every axis of the cut.
  int k = dims - s.cut_axis, around = 1;
  for (int a = 0; a < k; ++a) around *= 3;
  std::vector<char> peer(ranks, 0), ghost(ranks > 1 ? sections : 0, 0);
  for (const Block& b : s.blocks) {
    if (b.rank != rank || ranks == 1) continue;
    for (int z = b.s0; z < b.s1; ++z) {
      int c[kMaxDims];
      for (int a = s.cut_axis, rest = z; a < dims; ++a) {
        c[a] = rest % layout.tiles(a);
        rest /= layout.tiles(a);
      }
      for (int code = 0; code < around; ++code) {
        int n = 0, scale = 1;
        bool inside = true;
        for (int a = s.cut_axis, q = code; a < dims; ++a, q /= 3) {
          const int x = c[a] + q % 3 - 1;
          inside = inside && x >= 0 && x < layout.tiles(a);
          n += x * scale;
          scale *= layout.tiles(a);
        }
        if (!inside) continue;
        const int owner = s.blocks[s.section_block[n]].rank;
        peer[owner] = 1;
        if (owner != rank && !ghost[n]) {
          ghost[n] = 1;
          ++s.ghost_sections;
        }
      }
    }
  }
  s.peer_slot.assign(ranks, -1);
  for (int r = 0; r < ranks; ++r)
    if (peer[r] && r != rank) {
      s.peer_slot[r] = static_cast<int>(s.peers.size());
      s.peers.push_back(r);
    }
  return s;
}

std::vector<std::array<int, kMaxDims>> move_offsets(int dims, Connectivity c) {
  std::vector<std::array<int, kMaxDims>> out;
  if (c == Connectivity::seed_pairs) {
    for (int i = 0; i < dims; ++i)
      for (int s = -1; s <= 1; s += 2) {
        std::array<int, kMaxDims> o{};
        o[i] = s;
        out.push_back(o);
      }
    for (int i = 0; i < dims; ++i)
      for (int k = i + 1; k < dims; ++k)
        for (int si = -1; si <= 1; si += 2)
          for (int sk = -1; sk <= 1; sk += 2) {
            std::array<int, kMaxDims> o{};
            o[i] = si;
            o[k] = sk;
            out.push_back(o);
          }
  } else {
    int count = 1;
    for (int a = 0; a < dims; ++a) count *= 3;
    for (int code = 0; code < count; ++code) {
      std::array<int, kMaxDims> o{};
      bool any = false;
      for (int a = 0, q = code; a < dims; ++a, q /= 3) {
        o[a] = q % 3 - 1;
        any = any || o[a] != 0;
      }
      if (any) out.push_back(o);
    }
  }
  return out;
}

int legal_move(const ObstacleSource& field, const int* from, const std::array<int, kMaxDims>& o) {
  const int dims = field.dims();
  int axes[kMaxDims], k = 0;
  for (int a = 0; a < dims; ++a)
    if (o[a] != 0) axes[k++] = a;
  for (unsigned subset = 0; subset < (1u << k); ++subset) {
    int corner[kMaxDims];
    std::copy(from, from + dims, corner);
    for (int j = 0; j < k; ++j)
      if (subset & (1u << j)) corner[axes[j]] += o[axes[j]];
    if (!field.is_free(std::span<const int>(corner, dims))) return 0;
  }
  return k;
}

void DenseProgress::update(const char* unit, double at, std::uint64_t reached) {
  if (label_.empty() || !line_.enabled()) return;
  const double t = clock_.seconds();
  if (t < after_s_ || (last_ >= 0 && t < last_ + 1.0)) return;
  last_ = t;
  const double rate = reached / t;
  const double left = rate > 0 && free_ > reached ? (free_ - reached) / rate : 0.0;
  line_.show(
      "%s: %s %.6g, %.4g of %.4g free states reached (%.1f%%), %.3g states/s, %.0f s, "
      "at most ~%.0f s left",
      label_.c_str(), unit, at, static_cast<double>(reached), static_cast<double>(free_),
      free_ ? 100.0 * reached / free_ : 0.0, rate, t, left);
}

LatticeCost path_cost(const std::vector<std::vector<int>>& path) {
  LatticeCost c;
  for (std::size_t i = 1; i < path.size(); ++i) {
    int k = 0;
    for (std::size_t a = 0; a < path[i].size(); ++a) k += path[i][a] != path[i - 1][a];
    c = c + LatticeCost::for_axes(k);
  }
  return c;
}

}  // namespace hpcplan::dense::detail
