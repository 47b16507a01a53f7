#pragma once
// Everything one substep reads and writes: the parameters, the particles, the obstacle boxes
// and the neighbour grid. A backend (step_backend.hpp) advances it; the physics parameters are
// plain data so that a second backend (CUDA) reads the same ones.
//
// Threads: a value owned by one Fluid; the step writes it, so readers (a planner) take a
// snapshot between frames, never a reference during one.
#include <cstdint>
#include <string_view>
#include <vector>

#include "hpcplan/sph/neighbour_grid.hpp"
#include "hpcplan/sph/particles.hpp"
#include "hpcplan/sph/physics/params.hpp"
#include "hpcplan/sph/vec3.hpp"

namespace hpcplan::sph {

struct FluidState {
  FluidParams params;
  Box3 domain;  // fluid particles never leave it; wall particles lie outside it
  Particles particles;
  std::vector<MovingBox> boxes;
  NeighbourGrid grid;
  double time = 0.0;
  std::uint64_t substeps = 0;
  std::uint64_t seed = 1;       // the run's seed (initial state, boxes, agitation)
  std::size_t fluid_count = 0;  // particles that are fluid (the rest are walls)
};

std::string_view to_string(Preset p);

}  // namespace hpcplan::sph
