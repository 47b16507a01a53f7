#include "hpcplan/sph/boundaries.hpp"

#include <algorithm>

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

}  // namespace hpcplan::sph
