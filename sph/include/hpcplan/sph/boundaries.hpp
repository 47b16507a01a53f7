#pragma once
// The hard constraints every substep ends with: a fluid particle is inside the domain (closed
// box) and in no obstacle box's interior. A particle that crossed a face is put back on it and
// keeps `restitution` of its normal velocity (relative to the face), reversed.
#include <vector>

#include "hpcplan/sph/fluid_state.hpp"

namespace hpcplan::sph {

// Moves a box by dt and reflects it off the domain's walls (it stays inside the domain).
void move_box(const Box3& domain, MovingBox& box, double dt);

// Enforces both constraints on particle i (boxes first, then the domain, whose faces no box
// crosses).
void keep_out_of_obstacles(const Box3& domain, const std::vector<MovingBox>& boxes,
                           double restitution, Particles& p, std::size_t i);

// The same, with the common case (inside the domain, in no box) decided inline.
inline void keep_out_of_obstacles_fast(const Box3& domain, const std::vector<MovingBox>& boxes,
                                       double restitution, Particles& p, std::size_t i) {
  const double x = p.x[i], y = p.y[i], z = p.z[i];
  bool clear = x >= domain.lo[0] && x <= domain.hi[0] && y >= domain.lo[1] && y <= domain.hi[1] &&
               z >= domain.lo[2] && z <= domain.hi[2];
  for (const MovingBox& b : boxes)
    clear = clear && !(x > b.box.lo[0] && x < b.box.hi[0] && y > b.box.lo[1] && y < b.box.hi[1] &&
                       z > b.box.lo[2] && z < b.box.hi[2]);
  if (!clear) keep_out_of_obstacles(domain, boxes, restitution, p, i);
}

}  // namespace hpcplan::sph
