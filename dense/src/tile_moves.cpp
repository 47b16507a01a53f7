#include "hpcplan/dense/tile_moves.hpp"

namespace hpcplan::dense {

TableMoves::TableMoves(const TileLayout& layout, int max_axes) {
  const int dims = layout.dims(), k = layout.in_tile_axes();
  // Every move: a digit per axis in {-1, 0, +1} (base 3), at most max_axes of them non-zero.
  int count = 1;
  for (int a = 0; a < dims; ++a) count *= 3;
  for (int code = 0; code < count; ++code) {
    int step[kMaxDims];
    int axes = 0;
    for (int a = 0, c = code; a < dims; ++a, c /= 3) {
      step[a] = c % 3 - 1;
      if (step[a] != 0) ++axes;
    }
    if (axes == 0 || axes > max_axes) continue;
    Move mv;
    mv.axes = axes;
    int moved[kMaxDims], m = 0;
    for (int a = 0; a < dims; ++a) {
      if (step[a] == 0) continue;
      moved[m++] = a;
      if (a < k) {
        mv.in_axis[mv.in_steps] = a;
        mv.in_sign[mv.in_steps++] = step[a];
      } else {
        mv.word_axis[mv.word_steps] = a;
        mv.word_sign[mv.word_steps++] = step[a];
      }
    }
    // Corners: every non-empty subset of the moved axes (the full subset is the target, last).
    for (unsigned subset = 1; subset < (1u << m); ++subset) {
      Corner c;
      int o[2] = {0, 0};
      for (int j = 0; j < m; ++j) {
        if (!(subset & (1u << j))) continue;
        const int a = moved[j];
        if (a < k) {
          o[a] = step[a];
        } else {
          c.word_axis[c.word_steps] = a;
          c.word_sign[c.word_steps++] = step[a];
        }
      }
      c.window = FreeWindows::window(o[0], o[1]);
      mv.corners.push_back(c);
    }
    moves_.push_back(std::move(mv));
  }
}

}  // namespace hpcplan::dense
