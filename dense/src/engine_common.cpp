// The dense engine's shared pieces that are not templates (engine_common.hpp).
#include "engine_common.hpp"

namespace hpcplan::dense::detail {

SlabMap plan_slabs(const ObstacleSource& field, const TileLayout& layout, int rank, int ranks,
                   int threads, int block_layers) {
  SlabMap s;
  s.rank = rank;
  s.ranks = ranks;
  s.layer_tiles = layout.layer_tiles();
  const int layers = layout.layers();
  const std::vector<double> weights = free_states_per_layer(field, layout);
  if (block_layers < 0) {
    const int workers = ranks * std::max(1, threads);
    block_layers = workers == 1 ? layers : std::max(4, layers / (kBlocksPerWorker * workers));
  }
  s.block_layers = block_layers;
  if (block_layers == 0) {
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
    for (int z = 0, j = 0; z < layers; z += block_layers, ++j) {
      const int r = j % ranks;
      s.blocks.push_back({z, std::min(layers, z + block_layers), r, count[r]++});
    }
    // Each rank's k-th block to thread k mod (its threads).
    for (Block& b : s.blocks) b.thread %= std::max(1, std::min(threads, count[b.rank]));
  }
  s.threads = 1;
  for (const Block& b : s.blocks)
    if (b.rank == rank) s.threads = std::max(s.threads, b.thread + 1);
  s.thread_tiles.assign(s.threads, 0);
  s.rank_layers.assign(ranks, 0);
  s.layer_block.assign(layers, 0);
  for (std::size_t j = 0; j < s.blocks.size(); ++j) {
    Block& b = s.blocks[j];
    b.lo = static_cast<std::uint64_t>(b.z0) * s.layer_tiles;
    b.hi = static_cast<std::uint64_t>(b.z1) * s.layer_tiles;
    for (int z = b.z0; z < b.z1; ++z) s.layer_block[z] = static_cast<int>(j);
    s.rank_layers[b.rank] += b.z1 - b.z0;
    if (b.rank != rank) continue;
    b.store = s.store_tiles;
    s.store_tiles += b.hi - b.lo;
    b.mark = s.thread_tiles[b.thread];
    s.thread_tiles[b.thread] += b.hi - b.lo;
  }
  for (std::size_t j = 0; j < s.blocks.size(); ++j) {
    if (s.blocks[j].rank != rank) continue;
    if (j > 0 && s.blocks[j - 1].rank != rank) s.below = s.blocks[j - 1].rank;
    if (j + 1 < s.blocks.size() && s.blocks[j + 1].rank != rank) s.above = s.blocks[j + 1].rank;
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
