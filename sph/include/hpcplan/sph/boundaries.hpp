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

}  // namespace hpcplan::sph
