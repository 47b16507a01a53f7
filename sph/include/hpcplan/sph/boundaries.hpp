#pragma once
// The obstacle boxes' motion, on the host for every backend (a handful of numbers per
// substep). The particles' hard constraints against the domain and the boxes are physics,
// written once for both backends: physics/push_out.hpp.
#include "hpcplan/sph/fluid_state.hpp"

namespace hpcplan::sph {

// Moves a box by dt and reflects it off the domain's walls (it stays inside the domain).
void move_box(const Box3& domain, MovingBox& box, double dt);

}  // namespace hpcplan::sph
