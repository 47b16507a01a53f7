#pragma once
// Uniform grids, written once for everything that cuts space into equal cells: the continuous
// worlds' search lattice, the dense 2D grid, the box maps' broad phase, and next the SPH
// neighbour grid and the fluid's occupancy grid.
//   GridShape<D>   cells per axis, strides, index <-> coordinates, box iteration, the 3^D - 1
//                  neighbour offsets;
//   UniformGrid<D> a shape placed in space (origin, cell size): the cell of a point, the cells
//                  a closed box touches;
//   CsrBuckets     items listed per cell in one flat array, built by counting sort (two passes,
//                  no per-cell vectors).
//
// Threads: all three are values; const use from several threads is safe.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <span>
#include <type_traits>
#include <vector>

namespace hpcplan {

template <int D>
class GridShape {
 public:
  using Coords = std::array<std::int64_t, D>;

  GridShape() = default;
  explicit GridShape(const Coords& counts) : counts_(counts) {
    stride_[0] = 1;
    for (int k = 1; k < D; ++k)
      stride_[k] = stride_[k - 1] * static_cast<std::uint64_t>(counts_[k - 1]);
  }

  std::int64_t count(int k) const { return counts_[k]; }
  const Coords& counts() const { return counts_; }
  std::uint64_t stride(int k) const { return stride_[k]; }
  std::uint64_t size() const { return stride_[D - 1] * static_cast<std::uint64_t>(counts_[D - 1]); }

  std::uint64_t index(const Coords& c) const {
    std::uint64_t i = 0;
    for (int k = 0; k < D; ++k) i += static_cast<std::uint64_t>(c[k]) * stride_[k];
    return i;
  }
  Coords coords(std::uint64_t i) const {
    Coords c;
    for (int k = 0; k < D; ++k)
      c[k] = static_cast<std::int64_t>((i / stride_[k]) % static_cast<std::uint64_t>(counts_[k]));
    return c;
  }
  bool contains(const Coords& c) const {
    for (int k = 0; k < D; ++k)
      if (c[k] < 0 || c[k] >= counts_[k]) return false;
    return true;
  }

  // fn(c) for every c with lo <= c <= hi on each axis, axis 0 fastest. A fn that returns bool
  // ends the walk by returning false.
  template <class Fn>
  static void for_each_in(const Coords& lo, const Coords& hi, Fn&& fn) {
    for (int k = 0; k < D; ++k)
      if (lo[k] > hi[k]) return;
    Coords c = lo;
    for (;;) {
      if constexpr (std::is_same_v<decltype(fn(c)), bool>) {
        if (!fn(c)) return;
      } else {
        fn(c);
      }
      int k = 0;
      while (k < D && c[k] == hi[k]) c[k] = lo[k], ++k;
      if (k == D) return;
      ++c[k];
    }
  }

  // The 3^D - 1 offsets to the neighbouring cells (each axis -1, 0 or +1, not all 0), in
  // base-3 order of (d_0 + 1) + 3 (d_1 + 1) + ...
  static std::vector<std::array<int, D>> neighbour_offsets() {
    std::vector<std::array<int, D>> out;
    int pow3 = 1;
    for (int k = 0; k < D; ++k) pow3 *= 3;
    for (int code = 0; code < pow3; ++code) {
      std::array<int, D> d;
      int c = code;
      bool any = false;
      for (int k = 0; k < D; ++k) {
        d[k] = c % 3 - 1;
        c /= 3;
        any = any || d[k] != 0;
      }
      if (any) out.push_back(d);
    }
    return out;
  }

 private:
  Coords counts_{};
  std::array<std::uint64_t, D> stride_{};
};

template <int D>
struct UniformGrid {
  using Coords = typename GridShape<D>::Coords;
  using Point = std::array<double, D>;

  Point origin{};
  Point cell{};  // cell size per axis
  GridShape<D> shape;

  // The cell holding p, clamped into the grid (points outside map to the border cells).
  Coords cell_of(const Point& p) const {
    Coords c;
    for (int k = 0; k < D; ++k) c[k] = clamp_cell(std::floor((p[k] - origin[k]) / cell[k]), k);
    return c;
  }

  // The cells a closed box [lo, hi] touches: a face lying on a cell boundary touches the cells
  // on both sides. False when the box misses the grid altogether.
  bool cells_touching(const Point& lo, const Point& hi, Coords& first, Coords& last) const {
    for (int k = 0; k < D; ++k)
      if ((hi[k] - origin[k]) / cell[k] < 0 ||
          (lo[k] - origin[k]) / cell[k] > static_cast<double>(shape.count(k)))
        return false;
    cells_touching_clamped(lo, hi, first, last);
    return true;
  }
  // The same range, clamped into the grid whether or not the box meets it.
  void cells_touching_clamped(const Point& lo, const Point& hi, Coords& first, Coords& last) const {
    for (int k = 0; k < D; ++k) {
      first[k] = clamp_cell(std::ceil((lo[k] - origin[k]) / cell[k]) - 1, k);
      last[k] = clamp_cell(std::floor((hi[k] - origin[k]) / cell[k]), k);
    }
  }

 private:
  std::int64_t clamp_cell(double x, int k) const {
    const double top = static_cast<double>(shape.count(k) - 1);
    return static_cast<std::int64_t>(std::isfinite(x) ? std::clamp(x, 0.0, top) : 0.0);
  }
};

class CsrBuckets {
 public:
  // cells_of(i, add) calls add(cell) once for every cell item i belongs to; items are
  // 0 .. items-1 and come out of each bucket in increasing order (the sort is stable).
  template <class CellsOf>
  void build(std::size_t cells, std::size_t items, CellsOf&& cells_of) {
    start_.assign(cells + 1, 0);
    for (std::size_t i = 0; i < items; ++i) cells_of(i, [&](std::size_t c) { ++start_[c + 1]; });
    for (std::size_t c = 0; c < cells; ++c) start_[c + 1] += start_[c];
    items_.resize(start_.back());
    // Scatter with start_[c] as bucket c's write cursor (it ends at bucket c + 1's start),
    // then shift the starts back: no second array of cursors.
    for (std::size_t i = 0; i < items; ++i)
      cells_of(i, [&](std::size_t c) { items_[start_[c]++] = static_cast<std::uint32_t>(i); });
    for (std::size_t c = cells; c > 0; --c) start_[c] = start_[c - 1];
    start_[0] = 0;
  }

  // Items 0 .. keys.size()-1, item i in bucket keys[i] (< cells): for callers that compute
  // the keys once (in parallel) and rebuild every step (the fluid's neighbour grid); no array
  // is reallocated once it has grown.
  void build_from_keys(std::size_t cells, std::span<const std::uint32_t> keys) {
    build(cells, keys.size(), [&](std::size_t i, auto&& add) { add(keys[i]); });
  }

  std::span<const std::uint32_t> items_in(std::size_t cell) const {
    return {items_.data() + start_[cell], items_.data() + start_[cell + 1]};
  }
  // The items of the consecutive buckets first .. last, as one run.
  std::span<const std::uint32_t> items_in(std::size_t first, std::size_t last) const {
    return {items_.data() + start_[first], items_.data() + start_[last + 1]};
  }
  // Every item, bucket after bucket.
  std::span<const std::uint32_t> all_items() const { return items_; }
  // After the caller renumbered its items in bucket order (item all_items()[k] is now item
  // k), the lists say so: bucket c holds items start .. end-1.
  void renumber_in_bucket_order() {
    for (std::size_t k = 0; k < items_.size(); ++k) items_[k] = static_cast<std::uint32_t>(k);
  }
  std::size_t cells() const { return start_.empty() ? 0 : start_.size() - 1; }
  std::size_t entries() const { return items_.size(); }

 private:
  std::vector<std::uint32_t> start_;  // bucket c holds items_[start_[c] .. start_[c + 1])
  std::vector<std::uint32_t> items_;
};

}  // namespace hpcplan
