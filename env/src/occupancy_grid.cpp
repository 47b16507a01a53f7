#include "hpcplan/env/occupancy_grid.hpp"

#include <algorithm>
#include <bit>
#include <utility>

#include "hpcplan/core/error.hpp"
#include "hpcplan/core/memory.hpp"

namespace hpcplan {
namespace {

constexpr int kMaxGridDims = 16;     // as the lattice engines (packed_key.hpp's kMaxDims)
constexpr int kMaxGridSide = 65535;  // as the lattice engines (kMaxExtent)

}  // namespace

OccupancyGrid::OccupancyGrid(std::vector<int> shape) : shape_(std::move(shape)) {
  if (shape_.empty() || static_cast<int>(shape_.size()) > kMaxGridDims)
    throw InputError("an occupancy grid has 1 to 16 dimensions, not " +
                     std::to_string(shape_.size()));
  for (int s : shape_)
    if (s < 1 || s > kMaxGridSide)
      throw InputError("an occupancy grid's sides are 1 to 65535 cells, not " + std::to_string(s));
  extent_ = std::max(2, *std::max_element(shape_.begin(), shape_.end()));
  // Rows along axis 0 padded to whole words; the other axes as they are.
  stride_.assign(shape_.size(), 1);
  const auto width = static_cast<std::uint64_t>(shape_[0]);
  unsigned __int128 bits = width >= 32 ? (width + 63) / 64 * 64 : width;
  cells_ = static_cast<std::uint64_t>(shape_[0]);
  for (std::size_t a = 1; a < shape_.size(); ++a) {
    stride_[a] = static_cast<std::int64_t>(bits);
    bits *= static_cast<unsigned>(shape_[a]);
    // 2^46 bits is 8 TiB: beyond that no machine holds the grid, and products stay exact.
    if (bits > (static_cast<unsigned __int128>(1) << 46))
      throw InputError("an occupancy grid of this shape needs more than 8 TiB");
    cells_ *= static_cast<std::uint64_t>(shape_[a]);
  }
  const std::uint64_t bytes = static_cast<std::uint64_t>(bits) / 8;
  if (const std::uint64_t avail = available_memory_bytes(); avail && bytes > avail)
    throw InputError("an occupancy grid of this shape needs " + std::to_string(bytes >> 20) +
                     " MiB, more than the " + std::to_string(avail >> 20) +
                     " MiB this machine has available");
  const auto total = static_cast<std::uint64_t>(bits);
  words_.assign(static_cast<std::size_t>((total + 63) / 64), 0);
  // Free every in-shape cell, the row padding (if any) left blocked.
  const std::uint64_t row_bits = shape_.size() > 1 ? static_cast<std::uint64_t>(stride_[1]) : total;
  for (std::uint64_t row = 0; row < total; row += row_bits)
    for (std::uint64_t x = 0; x < width;) {
      const std::uint64_t bit = row + x;
      const std::uint64_t n = std::min<std::uint64_t>(width - x, 64 - (bit & 63));
      words_[bit >> 6] |= (n == 64 ? ~std::uint64_t{0} : ((std::uint64_t{1} << n) - 1))
                          << (bit & 63);
      x += n;
    }
}

std::uint64_t OccupancyGrid::count_free(std::uint64_t begin, std::uint64_t end) const {
  std::uint64_t n = 0;
  while (begin < end) {
    const int take = static_cast<int>(std::min<std::uint64_t>(end - begin, 64 - (begin & 63)));
    n += static_cast<std::uint64_t>(std::popcount(bits(begin, take)));
    begin += static_cast<std::uint64_t>(take);
  }
  return n;
}

bool OccupancyGrid::inside(std::span<const int> c) const {
  if (static_cast<int>(c.size()) != dims()) return false;
  for (int a = 0; a < dims(); ++a)
    if (c[a] < 0 || c[a] >= shape_[a]) return false;
  return true;
}

bool OccupancyGrid::is_free(std::span<const int> c) const {
  return inside(c) && free_at(index(c.data()));
}

void OccupancyGrid::set_free(std::span<const int> c, bool free) {
  if (!inside(c)) throw std::out_of_range("OccupancyGrid::set_free: cell outside the shape");
  const std::uint64_t bit = index(c.data());
  const std::uint64_t mask = std::uint64_t{1} << (bit & 63);
  if (sealed_) unseal();
  if (free)
    words_[bit >> 6] |= mask;
  else
    words_[bit >> 6] &= ~mask;
}

void OccupancyGrid::seal() {
  unseal();
  free_cells_ = free_cells();
  checksum_ = compute_checksum();
  if (dims() == 2) {
    const auto width = static_cast<std::uint64_t>(shape_[0]);
    const auto height = static_cast<std::uint64_t>(shape_[1]);
    column_bits_ = (height + 63) / 64 * 64;
    transposed_.assign(width * column_bits_ / 64, 0);
    const auto row = static_cast<std::uint64_t>(stride_[1]);
    for (std::uint64_t y = 0; y < height; ++y)
      for (std::uint64_t x = 0; x < width; ++x)
        if (free_at(y * row + x)) {
          const std::uint64_t bit = x * column_bits_ + y;
          transposed_[bit >> 6] |= std::uint64_t{1} << (bit & 63);
        }
  }
  sealed_ = true;
}

void OccupancyGrid::unseal() {
  sealed_ = false;
  transposed_.clear();
  transposed_.shrink_to_fit();
  column_bits_ = 0;
}

std::uint64_t OccupancyGrid::compute_checksum() const {
  std::uint64_t h = 0xcbf29ce484222325ULL;
  auto mix = [&h](std::uint64_t v) {
    for (int i = 0; i < 8; ++i) {
      h ^= (v >> (8 * i)) & 0xFF;
      h *= 0x100000001b3ULL;
    }
  };
  for (int s : shape_) mix(static_cast<std::uint64_t>(s));
  for (std::uint64_t w : words_) mix(w);
  return h;
}

OccupancyGrid occupancy_from_bytes(const std::uint8_t* data,
                                   std::span<const std::int64_t> array_shape) {
  const std::size_t d = array_shape.size();
  if (d < 1 || d > static_cast<std::size_t>(kMaxGridDims))
    throw InputError("an occupancy array has 1 to 16 dimensions, not " + std::to_string(d));
  std::vector<int> shape(d);
  for (std::size_t a = 0; a < d; ++a) {
    const std::int64_t s = array_shape[d - 1 - a];
    if (s < 1 || s > kMaxGridSide)
      throw InputError("an occupancy array's sides are 1 to 65535 cells, not " + std::to_string(s));
    shape[a] = static_cast<int>(s);
  }
  OccupancyGrid grid(std::move(shape));
  // The array's rows along its last axis are the grid's rows along axis 0, in the same order.
  const std::uint64_t width = static_cast<std::uint64_t>(grid.size(0));
  const std::uint64_t rows = grid.cells() / width;
  const std::uint64_t row_bits = grid.dims() > 1 ? static_cast<std::uint64_t>(grid.stride(1)) : 0;
  for (std::uint64_t r = 0; r < rows; ++r) {
    const std::uint8_t* src = data + r * width;
    const std::uint64_t base = r * row_bits;
    for (std::uint64_t x = 0; x < width; ++x)
      if (src[x]) grid.block_at(base + x);
  }
  grid.seal();
  return grid;
}

}  // namespace hpcplan
