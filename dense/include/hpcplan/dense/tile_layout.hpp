#pragma once
// The lattice [0, extent)^d as 64-bit tiles: the dense engine's unit of work, one bit per
// lattice state. Axis 0, and axis 1 from 2D up, lie inside the word: 8 x 8 cells (bit
// x0' + 8 x1'), or a row of 64 cells along axis 0 (1D, and 2D/3D lattices so wide that the
// 8 x 8 window table would not fit; see free_windows.hpp). Every further axis has one cell per
// tile, so a move along it changes the word, not the bit. Tiles are numbered with axis 0
// fastest; padding cells past the extent exist in the last tile of an in-tile axis and are
// never free.
//
// Why square tiles and not rows along one axis: a BFS wavefront crosses a row of 64 cells over
// about 32 levels, two cells at a time, so every word is touched ~32 times for 64 states; an
// 8 x 8 tile is crossed in ~5 levels, 12 states a time (4D, extent 40: 12.7 against 5.4 visits
// of each tile, measured in the prototype). Axes beyond the second stay one cell wide because a
// step along them is then a word offset, with no shift and no mask.
//
// A layer is the tiles sharing their last tile coordinate; a slab, a run of layers. From 3D up
// (and in 2D rows) a layer is one lattice layer of the last axis; in 2D with 8 x 8 tiles it is 8.
//
// Threads: immutable once built.
#include <array>
#include <cstdint>
#include <span>

#include "hpcplan/graph/packed_key.hpp"

namespace hpcplan::dense {

using Word = std::uint64_t;

class TileLayout {
 public:
  // Tile indices stay below this (2^50 tiles, 2^56 states: 8 PiB of bits, beyond any machine's
  // memory, and far below 2^53, where tile_coords' double reciprocal stays exact).
  static constexpr std::uint64_t kMaxTiles = std::uint64_t{1} << 50;
  // Whether the lattice has at most kMaxTiles tiles (the constructor's precondition).
  static bool fits(int dims, int extent, int in_tile_axes);
  // in_tile_axes: 1 (rows of 64 along axis 0) or 2 (8 x 8 on axes 0 and 1, dims >= 2).
  TileLayout(int dims, int extent, int in_tile_axes);

  int dims() const { return dims_; }
  int extent() const { return extent_; }
  int in_tile_axes() const { return in_tile_; }
  int side(int axis) const { return side_[axis]; }    // cells per tile along the axis
  int tiles(int axis) const { return tiles_[axis]; }  // tiles along the axis
  std::int64_t stride(int axis) const { return stride_[axis]; }
  std::uint64_t tile_count() const { return tile_count_; }
  int layers() const { return tiles_[dims_ - 1]; }
  std::uint64_t layer_tiles() const { return static_cast<std::uint64_t>(stride_[dims_ - 1]); }
  int cells_per_layer_step() const { return side_[dims_ - 1]; }  // lattice layers per tile layer

  // A lattice state's tile and bit.
  std::uint64_t tile_of(std::span<const int> c) const;
  int bit_of(std::span<const int> c) const;
  // Tile coordinates of a tile index (division by invariant divisors through a double
  // reciprocal and one correction: tile indices stay far below 2^53).
  void tile_coords(std::uint64_t tile, int* t) const {
    std::uint64_t rest = tile;
    for (int a = 0; a + 1 < dims_; ++a) {
      const auto n = static_cast<std::uint64_t>(tiles_[a]);
      auto q = static_cast<std::uint64_t>(static_cast<double>(rest) * inverse_[a]);
      if (q * n > rest)
        --q;
      else if ((q + 1) * n <= rest)
        ++q;
      t[a] = static_cast<int>(rest - q * n);
      rest = q;
    }
    t[dims_ - 1] = static_cast<int>(rest);
  }
  // The lattice coordinates of bit `bit` of tile `tile` (may lie in the padding).
  void cell(std::uint64_t tile, int bit, int* c) const;
  // The layer (last tile coordinate) holding a lattice state.
  int layer_of(std::span<const int> c) const { return c[dims_ - 1] / side_[dims_ - 1]; }

 private:
  int dims_;
  int extent_;
  int in_tile_;
  std::array<int, kMaxDims> side_{};
  std::array<int, kMaxDims> tiles_{};
  std::array<std::int64_t, kMaxDims> stride_{};
  std::array<double, kMaxDims> inverse_{};
  std::uint64_t tile_count_ = 0;
};

// Bits of a tile with in-tile coordinate 0 (lo) or side - 1 (hi) along axis 0 of an 8-wide tile.
inline constexpr Word kColumn0 = 0x0101010101010101ULL;
inline constexpr Word kColumn7 = 0x8080808080808080ULL;

}  // namespace hpcplan::dense
