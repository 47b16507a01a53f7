#include "hpcplan/env/bend_points.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "hpcplan/core/error.hpp"

namespace hpcplan::env {

namespace {

void check_spacing(double spacing, double lift) {
  if (!(spacing > 0) || !std::isfinite(spacing))
    throw InputError("the bend-point spacing must be a positive number");
  if (!(lift > 0) || !std::isfinite(lift)) throw InputError("the bend-point lift must be positive");
}

// The visibility graph costs up to n^2 segment tests: refuse sizes no search would finish.
constexpr double kMaxBendPoints = 1e6;

void check_count(double count, double spacing) {
  if (count > kMaxBendPoints) {
    char text[160];
    std::snprintf(text, sizeof text,
                  "a bend-point spacing of %g would place %.3g bend points (at most %g); use a "
                  "coarser --spacing",
                  spacing, count, kMaxBendPoints);
    throw InputError(text);
  }
}

Vec<3> axis(int k, double sign) {
  Vec<3> v{0, 0, 0};
  v[k] = sign;
  return v;
}

}  // namespace

std::vector<BendPoint<3>> bend_points(const BoxWorld& world, double spacing, double lift) {
  check_spacing(spacing, lift);
  double count = 0;  // an upper bound: 8 corners and 4 edges' samples along each axis
  for (const Block& block : world.blocks()) {
    count += 8;
    for (int a = 0; a < 3; ++a)
      count += 4 * std::ceil((block.box.hi[a] - block.box.lo[a]) / spacing);
  }
  check_count(count, spacing);
  std::vector<BendPoint<3>> out;
  auto keep = [&](const BendPoint<3>& b) {
    if (world.point_free(b.point)) out.push_back(b);
  };
  for (const Block& block : world.blocks()) {
    const Aabb<3>& box = block.box;
    auto side = [&](int k, double sign) { return sign < 0 ? box.lo[k] - lift : box.hi[k] + lift; };
    // Corners: all three faces meet.
    for (int corner = 0; corner < 8; ++corner) {
      BendPoint<3> b;
      for (int k = 0; k < 3; ++k) {
        const double sign = (corner >> k) & 1 ? 1.0 : -1.0;
        b.point[k] = side(k, sign);
        b.normals[k] = axis(k, sign);
      }
      b.normal_count = 3;
      keep(b);
    }
    // Edge interiors: along axis a, on the faces of the other two axes' chosen sides.
    for (int a = 0; a < 3; ++a) {
      const int u = (a + 1) % 3, v = (a + 2) % 3;
      const double length = box.hi[a] - box.lo[a];
      const int pieces = std::max(1, static_cast<int>(std::ceil(length / spacing)));
      for (int sides = 0; sides < 4; ++sides) {
        const double su = sides & 1 ? 1.0 : -1.0, sv = sides & 2 ? 1.0 : -1.0;
        for (int j = 1; j < pieces; ++j) {
          BendPoint<3> b;
          b.point[a] = box.lo[a] + length * j / pieces;
          b.point[u] = side(u, su);
          b.point[v] = side(v, sv);
          b.normals[0] = axis(u, su);
          b.normals[1] = axis(v, sv);
          b.normal_count = 2;
          keep(b);
        }
      }
    }
  }
  return out;
}

std::vector<BendPoint<2>> bend_points(const SphereWorld& world, double spacing, double lift) {
  check_spacing(spacing, lift);
  double count = 0;
  for (const Circle& c : world.obstacles())
    count += std::max(8.0, std::ceil(2 * std::numbers::pi * c.radius / spacing));
  check_count(count, spacing);
  std::vector<BendPoint<2>> out;
  for (const Circle& c : world.obstacles()) {
    if (!(c.radius > 0)) continue;
    const int sides =
        std::max(8, static_cast<int>(std::ceil(2 * std::numbers::pi * c.radius / spacing)));
    const double step = 2 * std::numbers::pi / sides;
    // A regular polygon with inradius r + lift has its corners at (r + lift) / cos(step / 2).
    const double corner_radius = (c.radius + lift) / std::cos(step / 2);
    for (int i = 0; i < sides; ++i) {
      const double angle = step * i;
      BendPoint<2> b;
      b.point = {c.centre[0] + corner_radius * std::cos(angle),
                 c.centre[1] + corner_radius * std::sin(angle)};
      b.normals[0] = {std::cos(angle - step / 2), std::sin(angle - step / 2)};
      b.normals[1] = {std::cos(angle + step / 2), std::sin(angle + step / 2)};
      b.normal_count = 2;
      if (world.point_free(b.point)) out.push_back(b);
    }
  }
  return out;
}

}  // namespace hpcplan::env
