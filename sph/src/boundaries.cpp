#include "hpcplan/sph/boundaries.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace hpcplan::sph {

void move_box(const Box3& domain, MovingBox& b, double dt) {
  for (int k = 0; k < 3; ++k) {
    const double size = b.box.hi[k] - b.box.lo[k];
    double lo = b.box.lo[k] + dt * b.velocity[k];
    if (lo < domain.lo[k]) {
      lo = 2.0 * domain.lo[k] - lo;
      b.velocity[k] = -b.velocity[k];
    } else if (lo + size > domain.hi[k]) {
      lo = 2.0 * (domain.hi[k] - size) - lo;
      b.velocity[k] = -b.velocity[k];
    }
    lo = std::clamp(lo, domain.lo[k], domain.hi[k] - size);
    b.box.lo[k] = lo;
    b.box.hi[k] = lo + size;
  }
}

void keep_out_of_obstacles(const Box3& domain, const std::vector<MovingBox>& boxes,
                           double restitution, Particles& p, std::size_t i) {
  double* pos[3] = {&p.x[i], &p.y[i], &p.z[i]};
  double* vel[3] = {&p.vx[i], &p.vy[i], &p.vz[i]};
  // Out of a box through its nearest face whose far side is inside the domain and in no
  // other box's interior (moving boxes may overlap one another); the nearest face if none is.
  for (std::size_t b = 0; b < boxes.size(); ++b) {
    const Box3& box = boxes[b].box;
    const Vec3 x{*pos[0], *pos[1], *pos[2]};
    if (!box.interior_contains(x)) continue;
    int best_axis = -1, first_axis = 0;
    bool best_upper = false, first_upper = false;
    double best = std::numeric_limits<double>::infinity(), first = best;
    for (int k = 0; k < 3; ++k)
      for (const bool upper : {false, true}) {
        const double depth = upper ? box.hi[k] - x[k] : x[k] - box.lo[k];
        if (depth < first) first = depth, first_axis = k, first_upper = upper;
        if (depth >= best) continue;
        Vec3 y = x;
        y[k] = upper ? box.hi[k] : box.lo[k];
        bool clear = domain.contains(y);
        for (std::size_t o = 0; o < boxes.size() && clear; ++o)
          clear = o == b || !boxes[o].box.interior_contains(y);
        if (clear) best = depth, best_axis = k, best_upper = upper;
      }
    if (best_axis < 0) best_axis = first_axis, best_upper = first_upper;
    *pos[best_axis] = best_upper ? box.hi[best_axis] : box.lo[best_axis];
    const double relative = *vel[best_axis] - boxes[b].velocity[best_axis];
    if (best_upper ? relative < 0.0 : relative > 0.0)
      *vel[best_axis] = boxes[b].velocity[best_axis] - restitution * relative;
  }
  for (int k = 0; k < 3; ++k) {
    if (!(*pos[k] >= domain.lo[k])) {  // also NaN: the frame check reports it
      if (std::isnan(*pos[k])) continue;
      *pos[k] = domain.lo[k];
      if (*vel[k] < 0.0) *vel[k] = -restitution * *vel[k];
    } else if (*pos[k] > domain.hi[k]) {
      *pos[k] = domain.hi[k];
      if (*vel[k] > 0.0) *vel[k] = -restitution * *vel[k];
    }
  }
}

}  // namespace hpcplan::sph
