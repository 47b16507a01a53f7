#include "hpcplan/sph/particles.hpp"

#include <cstddef>

namespace hpcplan::sph {

namespace {

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
  for (auto* a : {&x, &y, &z, &vx, &vy, &vz, &ax, &ay, &az, &rho, &drho, &p}) a->resize(n, 0.0);
  neighbours.resize(n, 0);
  id.resize(n, 0);
  wall.resize(n, 0);
}

void Particles::add(const Vec3& position, const Vec3& velocity, double rho0, bool is_wall) {
  const std::size_t i = size();
  resize(i + 1);
  x[i] = position[0], y[i] = position[1], z[i] = position[2];
  vx[i] = velocity[0], vy[i] = velocity[1], vz[i] = velocity[2];
  rho[i] = rho0;
  id[i] = static_cast<std::uint32_t>(i);
  wall[i] = is_wall ? 1 : 0;
}

void Particles::permute(std::span<const std::uint32_t> order) {
  std::vector<double> d;
  for (auto* a : {&x, &y, &z, &vx, &vy, &vz, &ax, &ay, &az, &rho, &drho, &p}) gather(*a, order, d);
  std::vector<std::uint32_t> u;
  gather(neighbours, order, u);
  gather(id, order, u);
  std::vector<std::uint8_t> b;
  gather(wall, order, b);
}

}  // namespace hpcplan::sph
