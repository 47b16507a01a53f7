#include "hpcplan/env/gog_world.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "hpcplan/core/error.hpp"

namespace hpcplan::env {

namespace {
constexpr double kTie = 1e-12;  // crossings this close in t happen at once (edges, corners)

bool inside_box(const GogField& field, const double* x) {
  const double upper = static_cast<double>(field.extent());
  for (int i = 0; i < field.dims(); ++i)
    if (!(x[i] >= 0.0 && x[i] <= upper)) return false;  // also rejects NaN
  return true;
}

int cell_coordinate(const GogField& field, double x) {
  return std::clamp(static_cast<int>(std::floor(x)), 0, field.extent() - 1);
}

}  // namespace

bool gog_point_free(const GogField& field, const double* x) {
  if (!inside_box(field, x)) return false;
  int sum = 0;
  for (int i = 0; i < field.dims(); ++i) sum += field.level_table(i)[cell_coordinate(field, x[i])];
  return sum < field.threshold();
}

std::vector<int> gog_cell_of(const GogField& field, const double* x) {
  std::vector<int> cell(field.dims());
  for (int i = 0; i < field.dims(); ++i) cell[i] = cell_coordinate(field, x[i]);
  return cell;
}

GogSegmentWalk gog_walk_segment(const GogField& field, const double* a, const double* b) {
  const int d = field.dims();
  const int extent = field.extent();
  const int threshold = field.threshold();
  if (d > kGogMaxDims) throw RunError("GOG segment test: more than 16 dimensions");
  GogSegmentWalk walk;
  // Both ends inside the box put the whole segment inside (the box is convex).
  if (!inside_box(field, a) || !inside_box(field, b)) {
    walk.free = false;
    walk.blocked_at = 0.0;
    return walk;
  }

  int cell[kGogMaxDims], dir[kGogMaxDims];
  double t_max[kGogMaxDims], t_delta[kGogMaxDims];
  // Cells outside the box are only touched along its faces and do not block.
  auto blocked = [&](const int* c) {
    int sum = 0;
    for (int i = 0; i < d; ++i) {
      if (c[i] < 0 || c[i] >= extent) return false;
      sum += field.level_table(i)[c[i]];
    }
    ++walk.cells;
    return sum >= threshold;
  };
  // c moved by dir along every non-empty subset of `axes` (the cells meeting at the edge or
  // corner the segment touches), and c itself.
  auto any_blocked_around = [&](const int* c, const int* axes, int k) {
    for (unsigned mask = 0; mask < (1u << k); ++mask) {
      int probe[kGogMaxDims] = {};
      for (int i = 0; i < d; ++i) probe[i] = c[i];
      for (int j = 0; j < k; ++j)
        if (mask & (1u << j)) probe[axes[j]] += dir[axes[j]];
      if (blocked(probe)) return true;
    }
    return false;
  };
  auto stop_at = [&](double t) {
    walk.free = false;
    walk.blocked_at = t;
    return walk;
  };

  // Start: the cell holding a, and the cells on the other side of each face a lies on.
  int on_face[kGogMaxDims], faces = 0;
  for (int i = 0; i < d; ++i) {
    const double x = a[i];
    const double fl = std::floor(x);
    dir[i] = b[i] > x ? 1 : (b[i] < x ? -1 : 0);
    cell[i] = static_cast<int>(fl);
    if (x == fl && x > 0.0 && x < extent) {
      if (dir[i] < 0) cell[i] -= 1;  // moving down from a face starts in the lower cell
      on_face[faces++] = i;
    }
    if (cell[i] >= extent) cell[i] = extent - 1;
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
    int walk_dir[kGogMaxDims];
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
    int axes[kGogMaxDims], k = 0;
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

std::string gog_why_not_free(const GogField& field, const double* x) {
  if (!inside_box(field, x)) return "outside the box [0, " + std::to_string(field.extent()) + "]";
  if (gog_point_free(field, x)) return "";
  std::string s = "in blocked cell (";
  const std::vector<int> cell = gog_cell_of(field, x);
  for (std::size_t i = 0; i < cell.size(); ++i) s += (i ? ", " : "") + std::to_string(cell[i]);
  return s + ")";
}

double gog_free_volume(const GogField& field) {
  return std::pow(static_cast<double>(field.extent()), field.dims()) *
         (1.0 - field.blocked_fraction());
}

void require_gog_dims(const GogField& field, int dims) {
  if (field.dims() != dims)
    throw InputError("a " + std::to_string(dims) + "D GOG world needs a " + std::to_string(dims) +
                     "D field, got " + std::to_string(field.dims()) + "D");
}

}  // namespace hpcplan::env
