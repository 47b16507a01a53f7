#pragma once
// The frame as planners see it: obstacle particles and boxes copied out of the fluid between
// frames (the planner thread never reads the fluid's arrays). The simulator leaves out the
// goal's particle alone (a robot does not plan around its target); the robot's own particle is
// not in the fluid any more (it left when the robot took its place: simulator.hpp).
#include <cstdint>
#include <span>

#include "hpcplan/env/fluid_snapshot.hpp"
#include "hpcplan/sph/fluid_state.hpp"

namespace hpcplan::sim {

// Fluid particles (walls excluded) whose id is not in `exclude`, and the obstacle boxes.
env::FluidSnapshot take_snapshot(const sph::FluidState& state,
                                 std::span<const std::uint32_t> exclude);
// The same into `into`, reusing its memory.
void take_snapshot(const sph::FluidState& state, std::span<const std::uint32_t> exclude,
                   env::FluidSnapshot& into);

// Where the particle with this id is now (particles are reordered by cell every few substeps,
// so its index moves); throws RunError if no particle has it.
env::Vec<3> particle_position(const sph::FluidState& state, std::uint32_t id);

}  // namespace hpcplan::sim
