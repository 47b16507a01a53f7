#pragma once
// Exact segment/box intersection by the slab method. The segment a->b is a + t (b - a) for
// t in [0, 1]; each axis clips t to the interval where the coordinate lies in the box's slab,
// and the segment meets the (closed) box when the intersection of those intervals is not
// empty. An axis the segment does not move along clips nothing or everything, so no division
// by zero (or by a fudge epsilon, which shifts the answer near faces) is ever made.
#include <utility>

#include "hpcplan/env/point.hpp"

namespace hpcplan::env {

template <int D>
bool segment_hits_box(const Vec<D>& a, const Vec<D>& b, const Aabb<D>& box) {
  double enter = 0.0, leave = 1.0;
  for (int k = 0; k < D; ++k) {
    const double d = b[k] - a[k];
    if (d == 0.0) {
      if (a[k] < box.lo[k] || a[k] > box.hi[k]) return false;
      continue;
    }
    double t0 = (box.lo[k] - a[k]) / d;
    double t1 = (box.hi[k] - a[k]) / d;
    if (t0 > t1) std::swap(t0, t1);
    if (t0 > enter) enter = t0;
    if (t1 < leave) leave = t1;
    if (enter > leave) return false;
  }
  return true;
}

}  // namespace hpcplan::env
