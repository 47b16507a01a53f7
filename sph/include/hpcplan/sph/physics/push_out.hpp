#pragma once
// The hard constraints every substep ends with, on the host and the GPU (see physics.hpp): a
// fluid particle is inside the domain (closed box) and in no obstacle box's interior. A
// particle that crossed a face is put back on it and keeps `restitution` of its normal
// velocity (relative to the face), reversed.
#include <cmath>

#include "hpcplan/core/portable.hpp"
#include "hpcplan/sph/physics/params.hpp"

namespace hpcplan::sph {

// Strictly inside (a point on a face is not).
HPCPLAN_HD inline bool in_interior(const Box3& b, const double x[3]) {
  for (int k = 0; k < 3; ++k)
    if (!(x[k] > b.lo[k] && x[k] < b.hi[k])) return false;
  return true;
}

HPCPLAN_HD inline bool in_closed(const Box3& b, const double x[3]) {
  for (int k = 0; k < 3; ++k)
    if (!(x[k] >= b.lo[k] && x[k] <= b.hi[k])) return false;
  return true;
}

// Enforces both constraints on one particle's position x and velocity v: boxes first (out
// through the nearest face whose far side is inside the domain and in no other box's interior,
// since moving boxes may overlap one another; the nearest face if none is), then the domain,
// whose faces no box crosses. The common case (inside the domain, in no box) returns at once.
HPCPLAN_HD inline void push_out_of_obstacles(const Box3& domain, const MovingBox* boxes,
                                             int box_count, double restitution, double x[3],
                                             double v[3]) {
  using std::isnan;
  bool clear = in_closed(domain, x);
  for (int b = 0; b < box_count && clear; ++b) clear = !in_interior(boxes[b].box, x);
  if (clear) return;
  for (int b = 0; b < box_count; ++b) {
    const Box3& box = boxes[b].box;
    if (!in_interior(box, x)) continue;
    int best_axis = -1, first_axis = 0;
    bool best_upper = false, first_upper = false;
    double best = INFINITY, first = INFINITY;
    for (int k = 0; k < 3; ++k)
      for (int u = 0; u < 2; ++u) {
        const bool upper = u == 1;
        const double depth = upper ? box.hi[k] - x[k] : x[k] - box.lo[k];
        if (depth < first) first = depth, first_axis = k, first_upper = upper;
        if (depth >= best) continue;
        double y[3] = {x[0], x[1], x[2]};
        y[k] = upper ? box.hi[k] : box.lo[k];
        bool face_clear = in_closed(domain, y);
        for (int o = 0; o < box_count && face_clear; ++o)
          face_clear = o == b || !in_interior(boxes[o].box, y);
        if (face_clear) best = depth, best_axis = k, best_upper = upper;
      }
    if (best_axis < 0) best_axis = first_axis, best_upper = first_upper;
    x[best_axis] = best_upper ? box.hi[best_axis] : box.lo[best_axis];
    const double relative = v[best_axis] - boxes[b].velocity[best_axis];
    if (best_upper ? relative < 0.0 : relative > 0.0)
      v[best_axis] = boxes[b].velocity[best_axis] - restitution * relative;
  }
  for (int k = 0; k < 3; ++k) {
    if (!(x[k] >= domain.lo[k])) {  // also NaN: the frame check reports it
      if (isnan(x[k])) continue;
      x[k] = domain.lo[k];
      if (v[k] < 0.0) v[k] = -restitution * v[k];
    } else if (x[k] > domain.hi[k]) {
      x[k] = domain.hi[k];
      if (v[k] > 0.0) v[k] = -restitution * v[k];
    }
  }
}

// What is wrong with one fluid particle (the frame check): each backend reports the lowest
// particle id with a problem, in words of its own kind.
enum class ParticleProblem : int { none = 0, position, velocity, density, outside, in_box };

HPCPLAN_HD inline ParticleProblem particle_problem(const Box3& domain, const MovingBox* boxes,
                                                   int box_count, const double x[3],
                                                   const double v[3], double rho, double p) {
  using std::isfinite;
  for (int k = 0; k < 3; ++k)
    if (!isfinite(x[k])) return ParticleProblem::position;
  for (int k = 0; k < 3; ++k)
    if (!isfinite(v[k])) return ParticleProblem::velocity;
  if (!isfinite(rho) || !isfinite(p)) return ParticleProblem::density;
  if (!in_closed(domain, x)) return ParticleProblem::outside;
  for (int b = 0; b < box_count; ++b)
    if (in_interior(boxes[b].box, x)) return ParticleProblem::in_box;
  return ParticleProblem::none;
}

}  // namespace hpcplan::sph
