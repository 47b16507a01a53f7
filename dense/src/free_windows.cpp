#include "hpcplan/dense/free_windows.hpp"

#include <climits>
#include <limits>
#include <stdexcept>

#include "hpcplan/core/error.hpp"

namespace hpcplan::dense {
namespace {

// A level no sum of real levels can stay below: cells outside the box.
constexpr int kOutside = 1 << 12;

struct Range {
  int tau_min, tau_max, out_of_box;
};

// Every tau a lookup can use: the tile's own tau (threshold minus 0..3 per word axis), changed
// by up to max_word_steps steps of -3..3, or by the out-of-box change, which is chosen so that
// any lookup including it lands at or below 0 (empty masks).
Range tau_range(const TileLayout& layout, int threshold, int max_word_steps) {
  const int word_axes = layout.dims() - layout.in_tile_axes();
  const int steps = std::min(max_word_steps, word_axes);
  Range r;
  r.out_of_box = -(threshold + 3 * steps);
  r.tau_min = threshold - 3 * word_axes + steps * r.out_of_box;
  r.tau_max = threshold + 3 * steps;
  return r;
}

std::uint64_t positions(const TileLayout& layout) {
  const std::uint64_t p0 = static_cast<std::uint64_t>(layout.tiles(0)) + 2;
  return layout.in_tile_axes() == 2 ? p0 * (static_cast<std::uint64_t>(layout.tiles(1)) + 2) : p0;
}

// An occupancy table's padded tile positions (every axis padded by one tile each side), or 0
// when 9 words per position would pass the kernels' int tau.
std::uint64_t padded_positions(const TileLayout& layout) {
  std::uint64_t n = 1;
  for (int a = 0; a < layout.dims(); ++a) {
    n *= static_cast<std::uint64_t>(layout.tiles(a)) + 2;
    if (n * FreeWindows::kWindows > static_cast<std::uint64_t>(INT_MAX)) return 0;
  }
  return n;
}

}  // namespace

std::uint64_t FreeWindows::table_bytes(const ObstacleSource& field, const TileLayout& layout,
                                       int max_word_steps) {
  if (field.is_occupancy()) {
    const std::uint64_t n = padded_positions(layout);
    return n == 0 ? std::numeric_limits<std::uint64_t>::max() : n * kWindows * sizeof(Word);
  }
  const Range r = tau_range(layout, field.gog().threshold(), max_word_steps);
  return positions(layout) * kWindows * static_cast<std::uint64_t>(r.tau_max - r.tau_min + 1) *
         sizeof(Word);
}

FreeWindows::FreeWindows(const ObstacleSource& field, const TileLayout& layout, int max_word_steps)
    : dims_(layout.dims()),
      extent_(layout.extent()),
      in_tile_axes_(layout.in_tile_axes()),
      tiles1_(layout.in_tile_axes() == 2 ? layout.tiles(1) : 1),
      threshold_(field.is_gog() ? field.gog().threshold() : 0) {
  if (field.is_occupancy()) {
    build_occupancy(field.occupancy(), layout);
    return;
  }
  const Range r = tau_range(layout, threshold_, max_word_steps);
  out_of_box_ = r.out_of_box;
  tau_offset_ = -r.tau_min;
  range_ = r.tau_max - r.tau_min + 1;
  build_gog(field.gog(), layout);
}

void FreeWindows::build_gog(const GogField& field, const TileLayout& layout) {
  const int dims = layout.dims(), extent = layout.extent();
  levels_.assign(dims, {});
  for (int a = 0; a < dims; ++a) {
    const std::uint8_t* table = field.level_table(a);
    levels_[a].resize(static_cast<std::size_t>(extent) + 2);
    for (int c = -1; c <= extent; ++c)
      levels_[a][c + 1] = c >= 0 && c < extent ? table[c] : kOutside;
  }
  // Level of axis a at coordinate c, for any c (padding and beyond: outside).
  auto level = [&](int a, int c) { return c >= -1 && c <= extent ? levels_[a][c + 1] : kOutside; };

  const bool square = layout.in_tile_axes() == 2;
  const int windows = kWindows;  // rows use the three with o1 = 0
  const int t0n = layout.tiles(0), t1n = square ? layout.tiles(1) : 1;
  table_.assign(positions(layout) * windows * static_cast<std::size_t>(range_), 0);
  for (int t0 = -1; t0 <= t0n; ++t0)
    for (int t1 = square ? -1 : 0; t1 <= (square ? t1n : 0); ++t1) {
      const std::size_t pos = square ? static_cast<std::size_t>(t0 + 1) * (t1n + 2) + (t1 + 1)
                                     : static_cast<std::size_t>(t0 + 1);
      // Tiles wholly outside the grid keep zero masks (every cell outside the box).
      if (t0 < 0 || t0 >= t0n || t1 < 0 || t1 >= t1n) continue;
      for (int w = 0; w < windows; ++w) {
        const int o0 = w % 3 - 1, o1 = w / 3 - 1;
        if (!square && o1 != 0) continue;
        Word* out = table_.data() + (pos * windows + w) * range_;
        if (square) {
          int a[8], b[8];
          for (int x = 0; x < 8; ++x) {
            a[x] = level(0, 8 * t0 + x + o0);
            b[x] = level(1, 8 * t1 + x + o1);
          }
          for (int i = 0; i < range_; ++i) {
            const int u = i - tau_offset_;
            Word m = 0;
            for (int y = 0; y < 8; ++y) {
              const int v = u - b[y];
              for (int x = 0; x < 8; ++x)
                if (a[x] < v) m |= Word{1} << (x + 8 * y);
            }
            out[i] = m;
          }
        } else {
          int a[64];
          for (int x = 0; x < 64; ++x) a[x] = level(0, 64 * t0 + x + o0);
          for (int i = 0; i < range_; ++i) {
            const int u = i - tau_offset_;
            Word m = 0;
            for (int x = 0; x < 64; ++x)
              if (a[x] < u) m |= Word{1} << x;
            out[i] = m;
          }
        }
      }
    }
}

namespace {

// Window masks from a tile's own mask and its neighbours' (bit x + 8y of an 8 x 8 tile, or bit
// x of a row): cell p + offset, for an offset of -1, 0 or +1 along one in-tile axis.
Word shift_x(Word centre, Word next, int o, int in_tile_axes) {
  if (o == 0) return centre;
  if (in_tile_axes == 1) return o > 0 ? (centre >> 1) | (next << 63) : (centre << 1) | (next >> 63);
  return o > 0 ? ((centre >> 1) & ~kColumn7) | ((next & kColumn0) << 7)
               : ((centre << 1) & ~kColumn0) | ((next & kColumn7) >> 7);
}
Word shift_y(Word centre, Word next, int o) {
  if (o == 0) return centre;
  return o > 0 ? (centre >> 8) | (next << 56) : (centre << 8) | (next >> 56);
}

}  // namespace

void FreeWindows::build_occupancy(const OccupancyGrid& grid, const TileLayout& layout) {
  occupancy_ = true;
  range_ = 1;
  tau_offset_ = 0;
  const int dims = layout.dims(), k = layout.in_tile_axes();
  const std::uint64_t n = padded_positions(layout);
  if (n == 0)
    throw InputError(
        "the occupancy grid is too large for the dense engine's window table; use "
        "--engine sparse");
  for (int a = 0; a < dims; ++a)
    padded_stride_[a] = a == 0 ? 1 : padded_stride_[a - 1] * (layout.tiles(a - 1) + 2);
  // Each tile's own free mask, over the padded grid (zero outside).
  std::vector<Word> own(n, 0);
  std::array<int, kMaxDims> t{};
  const std::uint64_t tiles = layout.tile_count();
  const int row_bits = k == 2 ? 8 : 64;
  for (std::uint64_t i = 0; i < tiles; ++i) {
    layout.tile_coords(i, t.data());
    // The tile's first cell; a tile past the shape along a word axis stays blocked.
    int c[kMaxDims];
    bool outside = false;
    for (int a = 0; a < dims; ++a) {
      c[a] = t[a] * layout.side(a);
      outside = outside || c[a] >= grid.size(a);
    }
    if (outside) continue;
    Word m = 0;
    const int rows = k == 2 ? 8 : 1;
    for (int y = 0; y < rows; ++y) {
      if (k == 2 && c[1] + y >= grid.size(1)) break;
      int cy[kMaxDims];
      std::copy(c, c + dims, cy);
      if (k == 2) cy[1] += y;
      // The tile's cells of this row that lie inside the grid's width.
      const int cells = std::min(row_bits, grid.size(0) - c[0]);
      m |= grid.bits(grid.index(cy), cells) << (row_bits * y);
    }
    std::int64_t pos = 0;
    for (int a = 0; a < dims; ++a) pos += (t[a] + 1) * padded_stride_[a];
    own[static_cast<std::size_t>(pos)] = m;
  }
  table_.assign(n * kWindows, 0);
  for (std::uint64_t i = 0; i < tiles; ++i) {
    layout.tile_coords(i, t.data());
    std::int64_t pos = 0;
    for (int a = 0; a < dims; ++a) pos += (t[a] + 1) * padded_stride_[a];
    const std::int64_t s0 = padded_stride_[0], s1 = k == 2 ? padded_stride_[1] : 0;
    Word* out = table_.data() + pos * kWindows;
    for (int w = 0; w < kWindows; ++w) {
      const int o0 = w % 3 - 1, o1 = w / 3 - 1;
      if (k == 1 && o1 != 0) continue;
      const Word near = shift_x(own[pos], own[pos + o0 * s0], o0, k);
      const Word far =
          o1 == 0 ? 0 : shift_x(own[pos + o1 * s1], own[pos + o0 * s0 + o1 * s1], o0, k);
      out[w] = k == 2 ? shift_y(near, far, o1) : near;
    }
  }
}

}  // namespace hpcplan::dense
