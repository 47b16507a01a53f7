#pragma once
// One frame of the fluid as the planners see it: the box the fluid lives in, the centres of the
// particles that are obstacles and the obstacle boxes where they are at that frame. Plain data,
// copied out of the simulation between frames, so a planner thread never reads particles the
// physics is writing (env knows nothing of the fluid's layer; sim fills this in).
#include <vector>

#include "hpcplan/env/point.hpp"

namespace hpcplan::env {

struct FluidSnapshot {
  Aabb<3> domain{};               // the fluid's box
  std::vector<Vec<3>> particles;  // obstacle particle centres
  std::vector<Aabb<3>> boxes;     // obstacle boxes (static or moving) at this frame
  double time = 0.0;              // simulated time of the frame (s)
};

}  // namespace hpcplan::env
