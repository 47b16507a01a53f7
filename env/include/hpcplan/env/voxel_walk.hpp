#pragma once
// The exact segment test of a grid of unit cells (Amanatides-Woo in d dimensions): every cell
// whose closed box the segment touches is offered to `blocked`, and where the segment crosses an
// edge or corner of several cells at once, every cell meeting there is. Touching counts, so a
// segment never slips between two blocked cells that share only a corner (the lattices'
// no-corner-cutting rule), and no sampling resolution is involved.
//
// Coordinates are in cell units: cell c along axis i covers [c, c + 1), the grid spans
// [0, extent[i]] and its upper face belongs to the last cell. Cells outside the grid are only
// touched along its faces and never block. Used by the GOG field (unit cells already) and the
// fluid's occupancy grid (scaled into cell units).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <type_traits>

namespace hpcplan::env {

inline constexpr int kVoxelWalkMaxDims = 16;

struct VoxelWalk {
  bool free = true;
  double blocked_at = 1.0;  // when not free: the segment parameter of the first blocked touch
  std::uint64_t cells = 0;  // cells offered to the predicate
};

// True when every coordinate of x lies in [0, extent[i]] (NaN is outside).
template <class Dims>
bool in_voxel_grid(Dims d, const int* extent, const double* x) {
  for (int i = 0; i < d; ++i)
    if (!(x[i] >= 0.0 && x[i] <= static_cast<double>(extent[i]))) return false;
  return true;
}

// The walk from a to b (both in cell units). A segment with an end outside the grid is blocked
// at t = 0. `blocked(const int* cell)` sees only cells inside the grid. d <= kVoxelWalkMaxDims
// (the caller checks). `d` is an int, or a std::integral_constant for a dimension known at
// compile time: then every per-axis loop unrolls (the 2D taut path, env/taut_path_2d.hpp,
// took about 10% less).
template <class Dims, class Blocked>
VoxelWalk voxel_walk(Dims d, const int* extent, const double* a, const double* b,
                     Blocked&& blocked) {
  constexpr double kTie = 1e-12;  // crossings this close in t happen at once (edges, corners)
  VoxelWalk walk;
  // Both ends inside put the whole segment inside (the grid is convex).
  if (!in_voxel_grid(d, extent, a) || !in_voxel_grid(d, extent, b)) {
    walk.free = false;
    walk.blocked_at = 0.0;
    return walk;
  }
  int cell[kVoxelWalkMaxDims], dir[kVoxelWalkMaxDims];
  double t_max[kVoxelWalkMaxDims], t_delta[kVoxelWalkMaxDims];
  auto test = [&](const int* c) {
    for (int i = 0; i < d; ++i)
      if (c[i] < 0 || c[i] >= extent[i]) return false;
    ++walk.cells;
    return static_cast<bool>(blocked(c));
  };
  // c moved by dir along every non-empty subset of `axes` (the cells meeting at the edge or
  // corner the segment touches), and c itself.
  auto any_blocked_around = [&](const int* c, const int* axes, int k) {
    for (unsigned mask = 0; mask < (1u << k); ++mask) {
      int probe[kVoxelWalkMaxDims] = {};
      for (int i = 0; i < d; ++i) probe[i] = c[i];
      for (int j = 0; j < k; ++j)
        if (mask & (1u << j)) probe[axes[j]] += dir[axes[j]];
      if (test(probe)) return true;
    }
    return false;
  };
  auto stop_at = [&](double t) {
    walk.free = false;
    walk.blocked_at = t;
    return walk;
  };

  // Start: the cell holding a, and the cells on the other side of each face a lies on.
  int on_face[kVoxelWalkMaxDims], faces = 0;
  for (int i = 0; i < d; ++i) {
    const double x = a[i];
    const double fl = std::floor(x);
    dir[i] = b[i] > x ? 1 : (b[i] < x ? -1 : 0);
    cell[i] = static_cast<int>(fl);
    if (x == fl && x > 0.0 && x < extent[i]) {
      if (dir[i] < 0) cell[i] -= 1;  // moving down from a face starts in the lower cell
      on_face[faces++] = i;
    }
    if (cell[i] >= extent[i]) cell[i] = extent[i] - 1;
    const double len = std::abs(b[i] - x);
    if (dir[i] == 0) {
      t_max[i] = t_delta[i] = std::numeric_limits<double>::infinity();
    } else {
      const double next = dir[i] > 0 ? cell[i] + 1.0 : static_cast<double>(cell[i]);
      t_max[i] = std::abs(next - x) / len;
      t_delta[i] = 1.0 / len;
    }
  }
  {
    int walk_dir[kVoxelWalkMaxDims];
    for (int i = 0; i < d; ++i) walk_dir[i] = dir[i];
    for (int j = 0; j < faces; ++j) dir[on_face[j]] = dir[on_face[j]] < 0 ? 1 : -1;
    const bool hit = any_blocked_around(cell, on_face, faces);
    for (int i = 0; i < d; ++i) dir[i] = walk_dir[i];
    if (hit) return stop_at(0.0);
  }

  for (;;) {
    double t = std::numeric_limits<double>::infinity();
    for (int i = 0; i < d; ++i) t = std::min(t, t_max[i]);
    if (t > 1.0 + kTie) break;
    int axes[kVoxelWalkMaxDims], k = 0;
    for (int i = 0; i < d; ++i)
      if (t_max[i] <= t + kTie) axes[k++] = i;
    if (any_blocked_around(cell, axes, k)) return stop_at(std::min(1.0, t));
    for (int j = 0; j < k; ++j) {
      cell[axes[j]] += dir[axes[j]];
      t_max[axes[j]] += t_delta[axes[j]];
    }
  }
  return walk;
}

}  // namespace hpcplan::env
