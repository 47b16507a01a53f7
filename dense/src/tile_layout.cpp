#include "hpcplan/dense/tile_layout.hpp"

#include <stdexcept>

namespace hpcplan::dense {

TileLayout::TileLayout(int dims, int extent, int in_tile_axes)
    : dims_(dims), extent_(extent), in_tile_(in_tile_axes) {
  if (dims < 1 || dims > kMaxDims || extent < 2)
    throw std::logic_error("TileLayout: dims or extent out of range");
  if (in_tile_axes != 1 && in_tile_axes != 2)
    throw std::logic_error("TileLayout: 1 or 2 in-tile axes");
  if (in_tile_axes == 2 && dims < 2) throw std::logic_error("TileLayout: 8 x 8 tiles need 2D");
  if (!fits(dims, extent, in_tile_axes))
    throw std::logic_error("TileLayout: more than kMaxTiles tiles (check fits() first)");
  std::int64_t stride = 1;
  for (int a = 0; a < dims; ++a) {
    side_[a] = in_tile_axes == 1 ? (a == 0 ? 64 : 1) : (a < 2 ? 8 : 1);
    tiles_[a] = (extent + side_[a] - 1) / side_[a];
    stride_[a] = stride;
    inverse_[a] = 1.0 / tiles_[a];
    stride *= tiles_[a];
  }
  tile_count_ = static_cast<std::uint64_t>(stride);
}

bool TileLayout::fits(int dims, int extent, int in_tile_axes) {
  // Multiplied in double: 16 axes of 65,535 tiles would overflow any integer type.
  double tiles = 1.0;
  for (int a = 0; a < dims; ++a) {
    const int side = in_tile_axes == 1 ? (a == 0 ? 64 : 1) : (a < 2 ? 8 : 1);
    tiles *= static_cast<double>((extent + side - 1) / side);
  }
  return tiles <= static_cast<double>(kMaxTiles);
}

std::uint64_t TileLayout::tile_of(std::span<const int> c) const {
  std::uint64_t tile = 0;
  for (int a = 0; a < dims_; ++a)
    tile += static_cast<std::uint64_t>(c[a] / side_[a]) * static_cast<std::uint64_t>(stride_[a]);
  return tile;
}

int TileLayout::bit_of(std::span<const int> c) const {
  if (in_tile_ == 1) return c[0] % 64;
  return c[0] % 8 + 8 * (c[1] % 8);
}

void TileLayout::cell(std::uint64_t tile, int bit, int* c) const {
  tile_coords(tile, c);
  for (int a = 0; a < dims_; ++a) c[a] *= side_[a];
  if (in_tile_ == 1) {
    c[0] += bit;
  } else {
    c[0] += bit % 8;
    c[1] += bit / 8;
  }
}

}  // namespace hpcplan::dense
