#include "hpcplan/env/gog_world.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <type_traits>

#include "hpcplan/core/error.hpp"
#include "hpcplan/env/voxel_walk.hpp"

namespace hpcplan::env {

namespace {

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

namespace {

template <class Dims>
GogSegmentWalk walk_field(const GogField& field, Dims d, const double* a, const double* b) {
  const int threshold = field.threshold();
  int extent[kGogMaxDims];
  std::fill(extent, extent + static_cast<int>(d), field.extent());
  const VoxelWalk w = voxel_walk(d, extent, a, b, [&](const int* c) {
    int sum = 0;
    for (int i = 0; i < d; ++i) sum += field.level_table(i)[c[i]];
    return sum >= threshold;
  });
  GogSegmentWalk walk;
  walk.free = w.free;
  walk.blocked_at = w.blocked_at;
  walk.cells = w.cells;
  return walk;
}

}  // namespace

GogSegmentWalk gog_walk_segment(const GogField& field, const double* a, const double* b) {
  const int d = field.dims();
  if (d > kGogMaxDims) throw RunError("GOG segment test: more than 16 dimensions");
  // The smoothing's dimensions (2D taut path, 3D tightener) walk with the dimension fixed.
  if (d == 2) return walk_field(field, std::integral_constant<int, 2>{}, a, b);
  if (d == 3) return walk_field(field, std::integral_constant<int, 3>{}, a, b);
  return walk_field(field, d, a, b);
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
