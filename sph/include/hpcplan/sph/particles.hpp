#pragma once
// The fluid's particles as a structure of arrays: one array per quantity, so that a phase
// streams through only the arrays it reads, and a particle's entries share one index. The
// arrays are the fields of particle_fields.hpp, declared from that one list.
// Boundary particles (the water preset's walls) live in the same arrays, flagged `wall`, so
// that one neighbour grid serves fluid-fluid and fluid-wall pairs.
//
// Threads: a value; phases write disjoint index ranges from several threads (each particle
// only its own entries), never resize concurrently.
#include <cstdint>
#include <span>
#include <vector>

#include "hpcplan/sph/particle_fields.hpp"
#include "hpcplan/sph/vec3.hpp"

namespace hpcplan::sph {

struct Particles {
#define HPCPLAN_SPH_VECTOR_MEMBER(type, name) std::vector<type> name;
  HPCPLAN_SPH_PARTICLE_FIELDS(HPCPLAN_SPH_VECTOR_MEMBER)
#undef HPCPLAN_SPH_VECTOR_MEMBER

  std::size_t size() const {
    return x.size();
  }
  void resize(std::size_t n);
  // Appends a particle at rest with density rho0 (id = its index).
  void add(const Vec3& position, const Vec3& velocity, double rho0, bool is_wall);

  Vec3 position(std::size_t i) const {
    return {x[i], y[i], z[i]};
  }
  Vec3 velocity(std::size_t i) const {
    return {vx[i], vy[i], vz[i]};
  }

  // Every array as a pointer (valid until the next resize or permute).
  ParticleView view();

  // Reorders every array at once: entry k of each array becomes old entry order[k]. `order`
  // must be a permutation of 0 .. size()-1.
  void permute(std::span<const std::uint32_t> order);

  // Bytes held per particle, for memory budgets.
  static constexpr std::size_t kBytesPerParticle = kParticleFieldBytes;
};

}  // namespace hpcplan::sph
