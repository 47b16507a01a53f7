#pragma once
// The free masks the dense kernels read, built once from the GOG field's per-axis level
// tables. GOG is separable: a state is free when its per-axis levels sum below the threshold.
// So a tile's free mask depends only on its in-tile coordinates (the 64 cells' levels along
// axes 0 and 1) and on tau = threshold - the sum of its word axes' levels (one cell per tile
// along those). Every mask a move needs is that of a "window": the tile shifted by -1, 0 or +1
// cell along each in-tile axis, whose bit p says whether cell p + offset is free; a step along
// a word axis only changes tau by that axis's level change. The table holds every window at
// every in-tile position for every tau a move can reach, so each corner check of a move is one
// read (no shifts, no per-state formula).
//
// Cells outside the box are never free: in-tile neighbours past an edge read padded table rows
// of zero masks, and a word-axis step out of the box moves tau to a value whose masks are zero.
//
// An occupancy grid is not separable, so its table holds the nine windows of every tile itself,
// over the tile grid padded by one zero tile on each side of every axis: 9 words per tile.
// The kernels read it through the same At: the row is the table's start, the stride 1, tau the
// tile's padded position times 9, and a step along a word axis adds that axis's padded tile
// stride times 9, landing on the neighbour tile's windows (zero past the box's edge). So the
// kernels are the same code for both sources.
//
// Threads: immutable once built.
#include <array>
#include <cstdint>
#include <vector>

#include "hpcplan/dense/tile_layout.hpp"
#include "hpcplan/env/obstacle_source.hpp"

namespace hpcplan::dense {

class FreeWindows {
 public:
  // max_word_steps: the most word axes one move's corner may step along (2 for the seed rule,
  // up to dims for full connectivity): it sets the range of tau the table covers.
  FreeWindows(const ObstacleSource& field, const TileLayout& layout, int max_word_steps);

  // The table's size for a layout, without building it (the engine picks rows over 8 x 8 tiles
  // when it would be too large).
  // An occupancy grid's table fits only while its padded positions times 9 fit an int (the
  // kernels' tau): the most a table may be is then about 17 GB.
  static std::uint64_t table_bytes(const ObstacleSource& field, const TileLayout& layout,
                                   int max_word_steps);

  // Windows: in-tile offsets (o0, o1) in {-1, 0, 1}; rows (one in-tile axis) fill only o1 = 0.
  static constexpr int window(int o0, int o1 = 0) { return (o0 + 1) + 3 * (o1 + 1); }
  static constexpr int kWindows = 9;

  // Where one tile's masks are read.
  struct At {
    const Word* row;  // mask(w, tau') = row[w * stride + tau']
    int tau;          // threshold minus the word axes' levels of this tile
    std::array<int, kMaxDims> minus{}, plus{};  // tau change of a step -1 / +1 along a word axis
  };
  [[gnu::always_inline]] void locate(const int* t, At& at) const {
    if (occupancy_) return locate_occupancy(t, at);
    const int k = in_tile_axes_;
    const std::size_t pos = k == 2 ? static_cast<std::size_t>(t[0] + 1) * (tiles1_ + 2) + (t[1] + 1)
                                   : static_cast<std::size_t>(t[0] + 1);
    at.row = table_.data() + pos * kWindows * range_ + tau_offset_;
    int tau = threshold_;
    for (int b = k; b < dims_; ++b) {
      const int* lv = levels_[b].data() + 1;  // lv[c] for c in -1 .. extent
      const int here = lv[t[b]];
      tau -= here;
      at.minus[b] = t[b] > 0 ? here - lv[t[b] - 1] : out_of_box_;
      at.plus[b] = t[b] + 1 < extent_ ? here - lv[t[b] + 1] : out_of_box_;
    }
    at.tau = tau;
  }
  int stride() const { return range_; }
  Word mask(const At& at, int window, int tau) const { return at.row[window * range_ + tau]; }
  // The free mask of the tile itself.
  Word free_mask(const int* tile_coords) const {
    At at;
    locate(tile_coords, at);
    return mask(at, window(0, 0), at.tau);
  }
  std::uint64_t bytes() const { return table_.size() * sizeof(Word); }

 private:
  void build_gog(const GogField& field, const TileLayout& layout);
  void build_occupancy(const OccupancyGrid& grid, const TileLayout& layout);
  void locate_occupancy(const int* t, At& at) const {
    std::int64_t pos = 0;
    for (int b = 0; b < dims_; ++b) pos += (t[b] + 1) * padded_stride_[b];
    at.row = table_.data();
    at.tau = static_cast<int>(pos * kWindows);
    for (int b = in_tile_axes_; b < dims_; ++b) {
      at.minus[b] = -static_cast<int>(padded_stride_[b] * kWindows);
      at.plus[b] = static_cast<int>(padded_stride_[b] * kWindows);
    }
  }

  bool occupancy_ = false;
  std::array<std::int64_t, kMaxDims> padded_stride_{};  // occupancy: tiles, padded grid
  int dims_, extent_, in_tile_axes_, tiles1_;
  int threshold_;
  int out_of_box_;  // tau change of a step out of the box: drives every mask to zero
  int tau_offset_;  // table index of tau = 0
  int range_;       // taus covered per window
  std::vector<Word> table_;
  std::vector<std::vector<int>> levels_;  // per axis, coordinate -1 .. extent (shifted by one)
};

}  // namespace hpcplan::dense
