#include "hpcplan/sim/snapshot.hpp"

#include <algorithm>
#include <string>

#include "hpcplan/core/error.hpp"

namespace hpcplan::sim {

env::FluidSnapshot take_snapshot(const sph::FluidState& state,
                                 std::span<const std::uint32_t> exclude) {
  env::FluidSnapshot s;
  take_snapshot(state, exclude, s);
  return s;
}

void take_snapshot(const sph::FluidState& state, std::span<const std::uint32_t> exclude,
                   env::FluidSnapshot& s) {
  s.domain = {{state.domain.lo[0], state.domain.lo[1], state.domain.lo[2]},
              {state.domain.hi[0], state.domain.hi[1], state.domain.hi[2]}};
  s.time = state.time;
  const sph::Particles& p = state.particles;
  s.particles.clear();
  s.particles.reserve(state.fluid_count);
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (p.wall[i]) continue;
    if (std::find(exclude.begin(), exclude.end(), p.id[i]) != exclude.end()) continue;
    s.particles.push_back({p.x[i], p.y[i], p.z[i]});
  }
  s.boxes.clear();
  for (const sph::MovingBox& b : state.boxes)
    s.boxes.push_back(
        {{b.box.lo[0], b.box.lo[1], b.box.lo[2]}, {b.box.hi[0], b.box.hi[1], b.box.hi[2]}});
}

env::Vec<3> particle_position(const sph::FluidState& state, std::uint32_t id) {
  const sph::Particles& p = state.particles;
  // Reordering moves particles only a little in index between frames, but a scan is simple
  // and costs ~20 us at 25,000 particles, once per frame.
  for (std::size_t i = 0; i < p.size(); ++i)
    if (p.id[i] == id) return {p.x[i], p.y[i], p.z[i]};
  throw RunError("internal error: no particle has id " + std::to_string(id));
}

}  // namespace hpcplan::sim
