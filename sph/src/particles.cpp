#include "hpcplan/sph/particles.hpp"

#include <cstddef>
#include <tuple>

namespace hpcplan::sph {

namespace {

// Entry k of `a` becomes old entry order[k]; `scratch` (any contents) is reused across the
// arrays of one type and comes back holding the old array.
template <class T>
void gather(std::vector<T>& a, std::span<const std::uint32_t> order, std::vector<T>& scratch) {
  scratch.resize(a.size());
  const std::ptrdiff_t n = static_cast<std::ptrdiff_t>(a.size());
#pragma omp parallel for schedule(static)
  for (std::ptrdiff_t k = 0; k < n; ++k) scratch[k] = a[order[k]];
  a.swap(scratch);
}

}  // namespace

void Particles::resize(std::size_t n) {
#define HPCPLAN_SPH_RESIZE(type, name) name.resize(n, type{});
  HPCPLAN_SPH_PARTICLE_FIELDS(HPCPLAN_SPH_RESIZE)
#undef HPCPLAN_SPH_RESIZE
}

void Particles::add(const Vec3& position, const Vec3& velocity, double rho0, bool is_wall) {
  const std::size_t i = size();
  resize(i + 1);
  x[i] = position[0], y[i] = position[1], z[i] = position[2];
  vx[i] = velocity[0], vy[i] = velocity[1], vz[i] = velocity[2];
  rho[i] = rho0;
  id[i] = static_cast<std::uint32_t>(i);
  wall[i] = is_wall ? kNoSlipWall : 0;
}

ParticleView Particles::view() {
  ParticleView v;
#define HPCPLAN_SPH_POINTER(type, name) v.name = name.data();
  HPCPLAN_SPH_PARTICLE_FIELDS(HPCPLAN_SPH_POINTER)
#undef HPCPLAN_SPH_POINTER
  return v;
}

void Particles::permute(std::span<const std::uint32_t> order) {
  std::tuple<std::vector<double>, std::vector<std::uint32_t>, std::vector<std::uint8_t>> scratch;
#define HPCPLAN_SPH_GATHER(type, name) gather(name, order, std::get<std::vector<type>>(scratch));
  HPCPLAN_SPH_PARTICLE_FIELDS(HPCPLAN_SPH_GATHER)
#undef HPCPLAN_SPH_GATHER
}

}  // namespace hpcplan::sph
