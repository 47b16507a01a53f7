#pragma once
// An occupancy array a user brings: a MovingAI map, a voxel map, an N-dimensional NumPy array,
// a configuration-space bitmap computed elsewhere. One bit per cell (1 = free), so a grid costs
// an eighth of the bytes of the array it came from.
//
// Axes: axis 0 is x, the array's last (fastest-varying) axis; axis 1 is y, the one before it,
// and so on. A C-contiguous array indexed [z][y][x] therefore lies in memory in the grid's own
// order, and a MovingAI map's x (its column) is axis 0, as in its scenario files. Rows along
// axis 0 of 32 cells or more are padded to whole 64-bit words (padding bits are blocked), so a
// row is a run of words a scanning search can read directly; narrower rows are packed end to
// end (padding them would cost up to 64 times the cells).
//
// The lattice the engines index is the bounding hypercube [0, extent)^d with extent the
// largest side: cells outside the array's shape are blocked, like cells outside a GOG box.
//
// Threads: immutable once built (the set_* calls are for the loaders); safe for any number
// of concurrent readers.
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace hpcplan {

class OccupancyGrid {
 public:
  // Sides per axis (axis 0 = x); every cell starts free. InputError if the dimension is not
  // 1..16, a side is not 1..65535, or the bits would not fit this machine's memory.
  explicit OccupancyGrid(std::vector<int> shape);

  int dims() const { return static_cast<int>(shape_.size()); }
  const std::vector<int>& shape() const { return shape_; }
  int size(int axis) const { return shape_[axis]; }
  // The lattice's side: the largest of the sides (at least 2, the engines' smallest lattice).
  int extent() const { return extent_; }
  std::uint64_t cells() const { return cells_; }  // product of the sides

  // Bit index of an in-shape cell: sum of coords[a] * stride(a).
  std::int64_t stride(int axis) const { return stride_[axis]; }
  std::uint64_t index(const int* coords) const {
    std::uint64_t i = 0;
    for (int a = 0; a < dims(); ++a) i += static_cast<std::uint64_t>(coords[a]) * stride_[a];
    return i;
  }
  bool free_at(std::uint64_t bit) const { return (words_[bit >> 6] >> (bit & 63)) & 1; }
  // `count` (1..64) bits from bit index `bit` on, low bit first (bits past the end read 0).
  std::uint64_t bits(std::uint64_t bit, int count) const {
    const std::uint64_t w = bit >> 6;
    const int shift = static_cast<int>(bit & 63);
    std::uint64_t v = words_[w] >> shift;
    if (shift != 0 && w + 1 < words_.size()) v |= words_[w + 1] << (64 - shift);
    return count == 64 ? v : v & ((std::uint64_t{1} << count) - 1);
  }
  // Free cells among bit indices [begin, end).
  std::uint64_t count_free(std::uint64_t begin, std::uint64_t end) const;
  // Whether rows along axis 0 start on word boundaries (stride(1) is a multiple of 64).
  bool rows_aligned() const { return dims() == 1 || stride_[1] % 64 == 0; }
  // Whether a cell is inside the shape and free (false for any coordinate outside).
  bool is_free(std::span<const int> coords) const;
  bool inside(std::span<const int> coords) const;

  void set_free(std::span<const int> coords, bool free);
  // Marks the cell of bit index `bit` (in shape) blocked; loaders write whole rows this way.
  void block_at(std::uint64_t bit) {
    words_[bit >> 6] &= ~(std::uint64_t{1} << (bit & 63));
    if (sealed_) unseal();
  }

  const std::uint64_t* words() const { return words_.data(); }
  std::uint64_t word_count() const { return words_.size(); }
  // Free cells, and FNV-1a over the shape and the bits (a checkpoint's identity and a report's
  // fingerprint): computed by seal(), which loaders call once the grid is written, so every
  // query reads them for free; on a grid changed since, computed afresh on each call.
  std::uint64_t free_cells() const {
    return sealed_ ? free_cells_ : count_free(0, words_.size() * 64);
  }
  std::uint64_t checksum() const { return sealed_ ? checksum_ : compute_checksum(); }
  // Also builds a 2D grid's columns as rows of their own (transposed(), below).
  void seal();

  // A sealed 2D grid's cells column by column: bit y of column x at x * column_bits() + y
  // (columns padded to whole words), so a search can scan along y a word at a time as it does
  // along x. Empty for other grids (1 bit more per cell, for 2D maps only).
  const std::vector<std::uint64_t>& transposed() const { return transposed_; }
  std::uint64_t column_bits() const { return column_bits_; }
  std::uint64_t bytes() const { return words_.size() * sizeof(std::uint64_t); }

  // Where the grid came from, for reports and errors: the file's name (or "array") and its
  // format ("movingai", "voxel", "npy", "array").
  std::string name = "array";
  std::string format = "array";

 private:
  std::uint64_t compute_checksum() const;
  void unseal();

  std::vector<int> shape_;
  bool sealed_ = false;
  std::vector<std::uint64_t> transposed_;
  std::uint64_t column_bits_ = 0;
  std::uint64_t free_cells_ = 0, checksum_ = 0;
  int extent_ = 2;
  std::uint64_t cells_ = 0;
  std::vector<std::int64_t> stride_;
  std::vector<std::uint64_t> words_;
};

// A grid from a C-contiguous array of bytes (nonzero = blocked) whose NumPy shape is
// `array_shape` (first axis slowest): the grid's axis 0 is the array's last axis. Reads the
// bytes in place; InputError on an empty or over-large shape.
OccupancyGrid occupancy_from_bytes(const std::uint8_t* data,
                                   std::span<const std::int64_t> array_shape);

}  // namespace hpcplan
