#pragma once
// Points of the continuous worlds (2D sphere world, 3D box maps) and the little vector algebra
// the planners need; a world is any type with kDim, bounds, point_free and segment_free.
#include <algorithm>
#include <array>
#include <cmath>
#include <concepts>
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

namespace hpcplan::env {

template <int D>
using Vec = std::array<double, D>;

template <int D>
double distance(const Vec<D>& a, const Vec<D>& b) {
  double s = 0.0;
  for (int k = 0; k < D; ++k) s += (a[k] - b[k]) * (a[k] - b[k]);
  return std::sqrt(s);
}

// a + t (b - a). Not exactly b at t = 1: a + (b - a) may round to a neighbour of b (4.9 +
// (0.1 - 4.9) is 0.1000000000000005), so code that must land on b uses b itself.
template <int D>
Vec<D> lerp(const Vec<D>& a, const Vec<D>& b, double t) {
  Vec<D> p;
  for (int k = 0; k < D; ++k) p[k] = a[k] + t * (b[k] - a[k]);
  return p;
}

template <int D>
double polyline_length(const std::vector<Vec<D>>& path) {
  double l = 0.0;
  for (std::size_t i = 1; i < path.size(); ++i) l += distance<D>(path[i - 1], path[i]);
  return l;
}

template <int D>
struct Aabb {
  Vec<D> lo, hi;
  // Closed box: touching the surface counts as inside.
  bool contains(const Vec<D>& p) const {
    for (int k = 0; k < D; ++k)
      if (p[k] < lo[k] || p[k] > hi[k]) return false;
    return true;
  }
  double largest_side() const {
    double m = 0.0;
    for (int k = 0; k < D; ++k) m = std::max(m, hi[k] - lo[k]);
    return m;
  }
  double volume() const {
    double v = 1.0;
    for (int k = 0; k < D; ++k) v *= hi[k] - lo[k];
    return v;
  }
};

template <int D>
std::string format_point(const Vec<D>& p) {
  std::string s = "(";
  for (int k = 0; k < D; ++k) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%s%g", k ? ", " : "", p[k]);
    s += buf;
  }
  return s + ")";
}

// What planners need of a world. Obstacles are closed sets: a point on an obstacle's surface
// is in collision, and so is a segment that only touches one. Queries count themselves in
// collision_checks(). A world is immutable once built and safe for concurrent readers: several
// planner threads may share one (the counter is a relaxed atomic, CheckCounter).
template <class W>
concept World = requires(const W& w, const Vec<W::kDim>& p) {
  { W::kDim } -> std::convertible_to<int>;
  { w.bounds() } -> std::convertible_to<Aabb<W::kDim>>;
  { w.point_free(p) } -> std::same_as<bool>;
  { w.segment_free(p, p) } -> std::same_as<bool>;
  { w.collision_checks() } -> std::convertible_to<std::uint64_t>;
  { w.free_volume() } -> std::convertible_to<double>;
  { w.why_not_free(p) } -> std::convertible_to<std::string>;
};

}  // namespace hpcplan::env
