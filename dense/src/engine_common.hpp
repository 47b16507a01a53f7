#pragma once
// Pieces both dense searches share: the slab this rank and its threads own, frontier entries,
// outboxes to neighbours, the walk back from the goal, and the moves in one fixed order.
#include <omp.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <optional>
#include <vector>

#include "hpcplan/core/progress.hpp"
#include "hpcplan/core/stopwatch.hpp"
#include "hpcplan/dense/dense_search.hpp"
#include "hpcplan/dense/free_windows.hpp"
#include "hpcplan/dense/slab_plan.hpp"
#include "hpcplan/dense/tile_layout.hpp"
#include "hpcplan/dense/tile_moves.hpp"
#include "hpcplan/graph/lattice_cost.hpp"

namespace hpcplan::dense::detail {

// One tile of a frontier or an outbox: its index and a word of states.
struct Entry {
  std::uint64_t tile;
  Word bits;
};

// Sorts entries by tile and ORs the words of equal tiles together.
inline void sort_and_merge(std::vector<Entry>& v) {
  std::sort(v.begin(), v.end(), [](const Entry& a, const Entry& b) { return a.tile < b.tile; });
  std::size_t w = 0;
  for (std::size_t i = 0; i < v.size(); ++i) {
    if (w > 0 && v[w - 1].tile == v[i].tile)
      v[w - 1].bits |= v[i].bits;
    else
      v[w++] = v[i];
  }
  v.resize(w);
}

template <class T>
std::span<const std::byte> as_bytes_of(const std::vector<T>& v) {
  return std::as_bytes(std::span<const T>(v.data(), v.size()));
}
template <class T>
void from_bytes(const std::vector<std::byte>& b, std::vector<T>& out) {
  out.resize(b.size() / sizeof(T));
  if (!b.empty()) std::memcpy(out.data(), b.data(), out.size() * sizeof(T));
}

// The layers of this rank and of each of its threads, and the neighbouring ranks.
struct Slabs {
  std::vector<int> rank_layers;             // ranks + 1 bounds
  int z0 = 0, z1 = 0;                       // this rank's layers
  std::uint64_t b0 = 0, b1 = 0;             // this rank's tiles
  std::vector<std::uint64_t> thread_tiles;  // threads + 1 tile bounds, inside [b0, b1)
  int threads = 1;
  int below = -1, above = -1;  // nearest ranks with layers below / above (-1: none)
  bool empty() const { return z1 == z0; }
};

inline Slabs plan_slabs(const GogField& field, const TileLayout& layout, int rank, int ranks,
                        int threads) {
  Slabs s;
  const std::vector<double> weights = free_states_per_layer(field, layout);
  s.rank_layers = balanced_slabs(weights, ranks);
  s.z0 = s.rank_layers[rank];
  s.z1 = s.rank_layers[rank + 1];
  const std::uint64_t lt = layout.layer_tiles();
  s.b0 = static_cast<std::uint64_t>(s.z0) * lt;
  s.b1 = static_cast<std::uint64_t>(s.z1) * lt;
  // Threads own whole layers too: at most one per layer of the slab.
  s.threads = std::max(1, std::min(threads, s.z1 - s.z0));
  const std::vector<double> mine(weights.begin() + s.z0, weights.begin() + s.z1);
  const std::vector<int> tb =
      mine.empty() ? std::vector<int>(s.threads + 1, 0) : balanced_slabs(mine, s.threads);
  for (int b : tb) s.thread_tiles.push_back(s.b0 + static_cast<std::uint64_t>(b) * lt);
  if (!s.empty()) {
    for (int r = rank - 1; r >= 0 && s.below < 0; --r)
      if (s.rank_layers[r + 1] > s.rank_layers[r]) s.below = r;
    for (int r = rank + 1; r < ranks && s.above < 0; ++r)
      if (s.rank_layers[r + 1] > s.rank_layers[r]) s.above = r;
  }
  return s;
}

// The lattice moves as coordinate offsets, in one fixed order (the walk back picks the first
// legal predecessor in it, so paths do not depend on ranks or threads): one-axis steps, then
// two-axis steps (the seed rule), or every offset in {-1,0,1}^d but 0 (full connectivity).
inline std::vector<std::array<int, kMaxDims>> move_offsets(int dims, Connectivity c) {
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

// Whether from -> from + offset is a legal move, from the field formula alone (every corner of
// the spanned unit cube free, inside the box); its axis count, or 0.
inline int legal_move(const GogField& field, const int* from, const std::array<int, kMaxDims>& o) {
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

// Progress on stderr for runs over 2 s: the level or class, states reached of the lattice's
// free states, the rate and the time left at that rate.
class DenseProgress {
 public:
  DenseProgress(std::string label, double after_s, std::uint64_t free_states)
      : label_(std::move(label)), after_s_(after_s), free_(free_states) {}
  void update(const char* unit, double at, std::uint64_t reached) {
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

 private:
  std::string label_;
  double after_s_;
  std::uint64_t free_;
  double last_ = -1.0;
  Stopwatch clock_;
  ProgressLine line_;
};

// The exact cost of a lattice path of unit cubes' diagonals.
inline LatticeCost path_cost(const std::vector<std::vector<int>>& path) {
  LatticeCost c;
  for (std::size_t i = 1; i < path.size(); ++i) {
    int k = 0;
    for (std::size_t a = 0; a < path[i].size(); ++a) k += path[i][a] != path[i - 1][a];
    c = c + LatticeCost::for_axes(k);
  }
  return c;
}

}  // namespace hpcplan::dense::detail
