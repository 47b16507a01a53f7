#include "hpcplan/dense/free_windows.hpp"

#include <stdexcept>

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

}  // namespace

std::uint64_t FreeWindows::table_bytes(const TileLayout& layout, int threshold,
                                       int max_word_steps) {
  const Range r = tau_range(layout, threshold, max_word_steps);
  return positions(layout) * kWindows * static_cast<std::uint64_t>(r.tau_max - r.tau_min + 1) *
         sizeof(Word);
}

FreeWindows::FreeWindows(const GogField& field, const TileLayout& layout, int max_word_steps)
    : layout_(layout),
      dims_(layout.dims()),
      extent_(layout.extent()),
      in_tile_axes_(layout.in_tile_axes()),
      tiles1_(layout.in_tile_axes() == 2 ? layout.tiles(1) : 1),
      threshold_(field.threshold()) {
  const Range r = tau_range(layout, threshold_, max_word_steps);
  out_of_box_ = r.out_of_box;
  tau_offset_ = -r.tau_min;
  range_ = r.tau_max - r.tau_min + 1;
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

}  // namespace hpcplan::dense
