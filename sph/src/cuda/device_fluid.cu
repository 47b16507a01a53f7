// The CUDA backend's kernels. The physics is the CPU backend's (cpu_step.cpp), phase for phase,
// in double precision; each kernel has one thread per particle, and a thread writes only its
// particle's entries, as on the CPU. What differs is bookkeeping:
//   - the particles are sorted by cell every substep (CUB's radix sort of the cell keys, then a
//     gather of every array into the second buffer set), so a cell's particles are contiguous
//     and the 3 cells of an x-row form one range: a neighbour query reads 9 ranges;
//   - neighbours are found from the cell ranges in every pass (no lists: the GPU re-reads the
//     ranges faster than it could store 96 indices per particle);
//   - sums run in cell order, so results match the CPU's to round-off, not bit for bit.
#include <cuda_runtime.h>
#include <cub/device/device_radix_sort.cuh>

#include <cmath>
#include <cstring>
#include <stdexcept>
#include <string>
#include <utility>

#include "device_fluid.hpp"

namespace hpcplan::sph::cuda {

namespace {

constexpr int kBlock = 256;
constexpr std::uint32_t kEmpty = 0xFFFFFFFFu;
constexpr double kPi = 3.14159265358979323846;

void ensure(cudaError_t e, const char* what) {
  if (e != cudaSuccess)
    throw std::runtime_error(std::string("CUDA: ") + what + ": " + cudaGetErrorString(e));
}

unsigned blocks_for(std::size_t n) {
  return static_cast<unsigned>((n + kBlock - 1) / kBlock);
}

// One set of particle arrays on the device.
struct Arrays {
  double *x, *y, *z, *vx, *vy, *vz, *ax, *ay, *az, *rho, *drho, *p;
  std::uint32_t *nb, *id;
  std::uint8_t* wall;
};

template <class T>
T* device_alloc(std::size_t n) {
  void* ptr = nullptr;
  ensure(cudaMalloc(&ptr, (n > 0 ? n : 1) * sizeof(T)), "cudaMalloc");
  return static_cast<T*>(ptr);
}

Arrays alloc_arrays(std::size_t n) {
  Arrays a;
  double** d[] = {&a.x,  &a.y,  &a.z,  &a.vx,  &a.vy,   &a.vz,
                  &a.ax, &a.ay, &a.az, &a.rho, &a.drho, &a.p};
  for (double** q : d) *q = device_alloc<double>(n);
  a.nb = device_alloc<std::uint32_t>(n);
  a.id = device_alloc<std::uint32_t>(n);
  a.wall = device_alloc<std::uint8_t>(n);
  return a;
}

// fn(device array, host array, bytes per element) for each of the 15 arrays: the one list
// both the upload and the download walk.
template <class Fn>
void for_each_array(const Arrays& d, const HostParticles& h, Fn&& fn) {
  fn(d.x, h.x, 8), fn(d.y, h.y, 8), fn(d.z, h.z, 8);
  fn(d.vx, h.vx, 8), fn(d.vy, h.vy, 8), fn(d.vz, h.vz, 8);
  fn(d.ax, h.ax, 8), fn(d.ay, h.ay, 8), fn(d.az, h.az, 8);
  fn(d.rho, h.rho, 8), fn(d.drho, h.drho, 8), fn(d.p, h.p, 8);
  fn(d.nb, h.neighbours, 4), fn(d.id, h.id, 4), fn(d.wall, h.wall, 1);
}

void free_arrays(Arrays& a) {
  void* d[] = {a.x,  a.y,   a.z,    a.vx, a.vy, a.vz, a.ax,  a.ay,
               a.az, a.rho, a.drho, a.p,  a.nb, a.id, a.wall};
  for (void* q : d) cudaFree(q);
}

// ---- device helpers --------------------------------------------------------------------------

__device__ inline std::int64_t cell_coordinate(double v, int k, const DeviceGrid& g) {
  const double c = (v - g.lo[k]) * g.inv_cell[k];
  if (!(c >= 0.0)) return 0;  // also NaN
  if (c >= static_cast<double>(g.n[k])) return g.n[k] - 1;
  return static_cast<std::int64_t>(c);
}

// fn(j, dx, dy, dz, r2) for every particle j != i within the support of particle i.
template <class Fn>
__device__ inline void for_each_neighbour(std::uint32_t i, const Arrays& a, const DeviceGrid& g,
                                          const std::uint32_t* start, const std::uint32_t* end,
                                          double support2, Fn&& fn) {
  const double xi = a.x[i], yi = a.y[i], zi = a.z[i];
  const std::int64_t cx = cell_coordinate(xi, 0, g), cy = cell_coordinate(yi, 1, g),
                     cz = cell_coordinate(zi, 2, g);
  const std::int64_t x0 = cx > 0 ? cx - 1 : 0, x1 = cx + 1 < g.n[0] ? cx + 1 : cx;
  for (std::int64_t k = cz > 0 ? cz - 1 : 0; k <= cz + 1 && k < g.n[2]; ++k)
    for (std::int64_t j = cy > 0 ? cy - 1 : 0; j <= cy + 1 && j < g.n[1]; ++j) {
      const std::int64_t row = g.n[0] * (j + g.n[1] * k);
      // The cells of one x-row are consecutive in key order: their particles form one range.
      std::uint32_t s = kEmpty, e = 0;
      for (std::int64_t c = row + x0; c <= row + x1; ++c) {
        const std::uint32_t cs = start[c];
        if (cs == kEmpty) continue;
        if (s == kEmpty) s = cs;
        e = end[c];
      }
      if (s == kEmpty) continue;
      for (std::uint32_t q = s; q < e; ++q) {
        if (q == i) continue;
        const double dx = xi - a.x[q], dy = yi - a.y[q], dz = zi - a.z[q];
        const double r2 = dx * dx + dy * dy + dz * dz;
        if (r2 < support2) fn(q, dx, dy, dz, r2);
      }
    }
}

__device__ inline double tait_pressure(const DeviceParams& f, double rho) {
  const double b = f.rest_density * f.sound_speed * f.sound_speed / 7.0;
  const double r = rho / f.rest_density;
  const double r2 = r * r;
  return fmax(0.0, b * (r2 * r2 * r2 * r - 1.0));
}

__device__ inline double tait_density(const DeviceParams& f, double p) {
  const double b = f.rest_density * f.sound_speed * f.sound_speed / 7.0;
  return f.rest_density * pow(p / b + 1.0, 1.0 / 7.0);
}

// Wendland C2, h = smoothing length: w(r) and dW/dr.
__device__ inline double wendland_w(const DeviceParams& f, double r) {
  const double h = f.smoothing_length, q = r / h;
  if (q >= 2.0) return 0.0;
  const double a = 1.0 - 0.5 * q, a2 = a * a;
  return 21.0 / (16.0 * kPi * h * h * h) * a2 * a2 * (2.0 * q + 1.0);
}
__device__ inline double wendland_dwdr(const DeviceParams& f, double r) {
  const double h = f.smoothing_length, q = r / h;
  if (q >= 2.0) return 0.0;
  const double a = 1.0 - 0.5 * q;
  return -5.0 * 21.0 / (16.0 * kPi * h * h * h) / h * q * a * a * a;
}

__device__ inline std::uint64_t splitmix64_mix(std::uint64_t x) {
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

// ---- kernels ---------------------------------------------------------------------------------

__global__ void cell_keys(Arrays a, std::size_t n, DeviceGrid g, std::uint32_t* key,
                          std::uint32_t* index) {
  const std::size_t i = blockIdx.x * static_cast<std::size_t>(blockDim.x) + threadIdx.x;
  if (i >= n) return;
  key[i] = static_cast<std::uint32_t>(
      cell_coordinate(a.x[i], 0, g) +
      g.n[0] * (cell_coordinate(a.y[i], 1, g) + g.n[1] * cell_coordinate(a.z[i], 2, g)));
  index[i] = static_cast<std::uint32_t>(i);
}

__global__ void gather(Arrays to, Arrays from, const std::uint32_t* order, std::size_t n) {
  const std::size_t k = blockIdx.x * static_cast<std::size_t>(blockDim.x) + threadIdx.x;
  if (k >= n) return;
  const std::uint32_t i = order[k];
  to.x[k] = from.x[i], to.y[k] = from.y[i], to.z[k] = from.z[i];
  to.vx[k] = from.vx[i], to.vy[k] = from.vy[i], to.vz[k] = from.vz[i];
  to.ax[k] = from.ax[i], to.ay[k] = from.ay[i], to.az[k] = from.az[i];
  to.rho[k] = from.rho[i], to.drho[k] = from.drho[i], to.p[k] = from.p[i];
  to.nb[k] = from.nb[i], to.id[k] = from.id[i], to.wall[k] = from.wall[i];
}

__global__ void cell_ranges(const std::uint32_t* key, std::size_t n, std::uint32_t* start,
                            std::uint32_t* end) {
  const std::size_t k = blockIdx.x * static_cast<std::size_t>(blockDim.x) + threadIdx.x;
  if (k >= n) return;
  const std::uint32_t c = key[k];
  if (k == 0 || key[k - 1] != c) start[c] = static_cast<std::uint32_t>(k);
  if (k + 1 == n || key[k + 1] != c) end[c] = static_cast<std::uint32_t>(k + 1);
}

struct Grid {
  DeviceGrid g;
  const std::uint32_t* start;
  const std::uint32_t* end;
  double support2;
};

// Seed preset: density (poly6, itself included) and the clamped pressure, every particle.
__global__ void seed_density(Arrays a, std::size_t n, Grid grid, DeviceParams f) {
  const std::size_t i = blockIdx.x * static_cast<std::size_t>(blockDim.x) + threadIdx.x;
  if (i >= n) return;
  const double h2 = f.support * f.support;
  const double h3 = h2 * f.support;
  const double norm = 315.0 / (64.0 * kPi * h3 * h3 * h3);
  const double m = f.particle_mass;
  double rho = m * norm * h2 * h2 * h2;
  std::uint32_t count = 0;
  for_each_neighbour(static_cast<std::uint32_t>(i), a, grid.g, grid.start, grid.end, grid.support2,
                     [&](std::uint32_t, double, double, double, double r2) {
                       const double d = h2 - r2;
                       rho += m * norm * d * d * d;
                       ++count;
                     });
  a.rho[i] = rho;
  a.p[i] = f.gas_constant * fmax(0.0, rho - f.rest_density);
  a.nb[i] = count;
}

// Seed preset: spiky pressure, viscosity Laplacian, gravity as an acceleration.
__global__ void seed_forces(Arrays a, std::size_t n, Grid grid, DeviceParams f) {
  const std::size_t i = blockIdx.x * static_cast<std::size_t>(blockDim.x) + threadIdx.x;
  if (i >= n) return;
  const double h = f.support;
  const double spiky = 15.0 / (kPi * h * h * h * h * h * h);
  const double lap = 45.0 / (kPi * h * h * h * h * h * h);
  const double m = f.particle_mass;
  const double pi = a.p[i], vxi = a.vx[i], vyi = a.vy[i], vzi = a.vz[i];
  double fx = 0.0, fy = 0.0, fz = 0.0;
  for_each_neighbour(
      static_cast<std::uint32_t>(i), a, grid.g, grid.start, grid.end, grid.support2,
      [&](std::uint32_t j, double dx, double dy, double dz, double r2) {
        const double r = sqrt(r2);
        const double inv_rho_j = 1.0 / a.rho[j];
        const double pj = a.p[j];
        if (r > 0.0 && (pi > 0.0 || pj > 0.0)) {
          const double d = h - r;
          const double dwdr = r >= h ? 0.0 : -3.0 * spiky * d * d;
          const double c = -m * 0.5 * (pi + pj) * inv_rho_j * dwdr / r;
          fx += c * dx, fy += c * dy, fz += c * dz;
        }
        const double c = f.viscosity * m * inv_rho_j * (r >= h ? 0.0 : lap * (h - r));
        fx += c * (a.vx[j] - vxi), fy += c * (a.vy[j] - vyi), fz += c * (a.vz[j] - vzi);
      });
  const double inv_rho = 1.0 / a.rho[i];
  a.ax[i] = fx * inv_rho + f.gravity[0];
  a.ay[i] = fy * inv_rho + f.gravity[1];
  a.az[i] = fz * inv_rho + f.gravity[2];
}

// Water: the continuity equation stepped (walls at rest), then Tait's pressure.
__global__ void water_density(Arrays a, std::size_t n, Grid grid, DeviceParams f, double dt) {
  const std::size_t i = blockIdx.x * static_cast<std::size_t>(blockDim.x) + threadIdx.x;
  if (i >= n || a.wall[i]) return;
  const double m = f.particle_mass;
  const double vxi = a.vx[i], vyi = a.vy[i], vzi = a.vz[i];
  double drho = 0.0;
  for_each_neighbour(static_cast<std::uint32_t>(i), a, grid.g, grid.start, grid.end, grid.support2,
                     [&](std::uint32_t j, double dx, double dy, double dz, double r2) {
                       if (r2 == 0.0) return;
                       const double r = sqrt(r2);
                       const bool wall = a.wall[j];
                       const double ux = vxi - (wall ? 0.0 : a.vx[j]),
                                    uy = vyi - (wall ? 0.0 : a.vy[j]),
                                    uz = vzi - (wall ? 0.0 : a.vz[j]);
                       drho += m * (ux * dx + uy * dy + uz * dz) * wendland_dwdr(f, r) / r;
                     });
  a.drho[i] = drho;
  a.rho[i] += dt * drho;
  a.p[i] = tait_pressure(f, a.rho[i]);
}

// Water: wall pressure extrapolated from the fluid, plus the hydrostatic difference (Adami et
// al. 2012); a wall with no fluid in reach rests.
__global__ void water_walls(Arrays a, std::size_t n, Grid grid, DeviceParams f) {
  const std::size_t i = blockIdx.x * static_cast<std::size_t>(blockDim.x) + threadIdx.x;
  if (i >= n || !a.wall[i]) return;
  double sum_w = 0.0, sum_pw = 0.0, sum_rho_r = 0.0;
  std::uint32_t count = 0;
  for_each_neighbour(static_cast<std::uint32_t>(i), a, grid.g, grid.start, grid.end, grid.support2,
                     [&](std::uint32_t j, double dx, double dy, double dz, double r2) {
                       if (a.wall[j]) return;
                       const double w = wendland_w(f, sqrt(r2));
                       sum_w += w;
                       sum_pw += a.p[j] * w;
                       sum_rho_r += a.rho[j] * w *
                                    (f.gravity[0] * dx + f.gravity[1] * dy + f.gravity[2] * dz);
                       ++count;
                     });
  const double pw = sum_w > 0.0 ? fmax(0.0, (sum_pw + sum_rho_r) / sum_w) : 0.0;
  a.p[i] = pw;
  a.rho[i] = count > 0 ? tait_density(f, pw) : f.rest_density;
  a.nb[i] = count;
}

// Water: pressure gradient, Monaghan's viscosity among fluid particles, gravity.
__global__ void water_forces(Arrays a, std::size_t n, Grid grid, DeviceParams f) {
  const std::size_t i = blockIdx.x * static_cast<std::size_t>(blockDim.x) + threadIdx.x;
  if (i >= n || a.wall[i]) return;
  const double m = f.particle_mass, h = f.smoothing_length;
  const double eta2 = 0.01 * h * h;
  const double visc = f.alpha * f.sound_speed;
  const double rho_i = a.rho[i];
  const double pi_term = a.p[i] / (rho_i * rho_i);
  const double vxi = a.vx[i], vyi = a.vy[i], vzi = a.vz[i];
  double ax = 0.0, ay = 0.0, az = 0.0;
  std::uint32_t count = 0;
  for_each_neighbour(static_cast<std::uint32_t>(i), a, grid.g, grid.start, grid.end, grid.support2,
                     [&](std::uint32_t j, double dx, double dy, double dz, double r2) {
                       if (r2 == 0.0) return;
                       ++count;
                       const double r = sqrt(r2);
                       const double g = wendland_dwdr(f, r) / r;
                       const double rho_j = a.rho[j];
                       double c = pi_term + a.p[j] / (rho_j * rho_j);
                       if (!a.wall[j]) {
                         const double vr =
                             (vxi - a.vx[j]) * dx + (vyi - a.vy[j]) * dy + (vzi - a.vz[j]) * dz;
                         if (vr < 0.0) c -= visc * (h * vr / (r2 + eta2)) / (0.5 * (rho_i + rho_j));
                       }
                       c *= -m * g;
                       ax += c * dx, ay += c * dy, az += c * dz;
                     });
  a.ax[i] = ax + f.gravity[0];
  a.ay[i] = ay + f.gravity[1];
  a.az[i] = az + f.gravity[2];
  a.nb[i] = count;
}

struct Bounds {
  double lo[3], hi[3];
};

__device__ inline bool in_interior(const DeviceBox& b, const double x[3]) {
  for (int k = 0; k < 3; ++k)
    if (!(x[k] > b.lo[k] && x[k] < b.hi[k])) return false;
  return true;
}

// Symplectic Euler, then the hard constraints (boundaries.cpp's keep_out_of_obstacles).
__global__ void integrate(Arrays a, std::size_t n, double dt, Bounds d, const DeviceBox* boxes,
                          int box_count, double restitution) {
  const std::size_t i = blockIdx.x * static_cast<std::size_t>(blockDim.x) + threadIdx.x;
  if (i >= n || a.wall[i]) return;
  double v[3] = {a.vx[i] + dt * a.ax[i], a.vy[i] + dt * a.ay[i], a.vz[i] + dt * a.az[i]};
  double x[3] = {a.x[i] + dt * v[0], a.y[i] + dt * v[1], a.z[i] + dt * v[2]};
  for (int b = 0; b < box_count; ++b) {
    const DeviceBox& box = boxes[b];
    if (!in_interior(box, x)) continue;
    // Out through the nearest face whose far side is in the domain and in no other box's
    // interior; the nearest face if none is.
    int best_axis = -1, first_axis = 0;
    bool best_upper = false, first_upper = false;
    double best = INFINITY, first = INFINITY;
    for (int k = 0; k < 3; ++k)
      for (int u = 0; u < 2; ++u) {
        const bool upper = u == 1;
        const double depth = upper ? box.hi[k] - x[k] : x[k] - box.lo[k];
        if (depth < first) first = depth, first_axis = k, first_upper = upper;
        if (depth >= best) continue;
        double y[3] = {x[0], x[1], x[2]};
        y[k] = upper ? box.hi[k] : box.lo[k];
        bool clear = true;
        for (int q = 0; q < 3; ++q) clear = clear && y[q] >= d.lo[q] && y[q] <= d.hi[q];
        for (int o = 0; o < box_count && clear; ++o) clear = o == b || !in_interior(boxes[o], y);
        if (clear) best = depth, best_axis = k, best_upper = upper;
      }
    if (best_axis < 0) best_axis = first_axis, best_upper = first_upper;
    x[best_axis] = best_upper ? box.hi[best_axis] : box.lo[best_axis];
    const double relative = v[best_axis] - box.v[best_axis];
    if (best_upper ? relative < 0.0 : relative > 0.0)
      v[best_axis] = box.v[best_axis] - restitution * relative;
  }
  for (int k = 0; k < 3; ++k) {
    if (!(x[k] >= d.lo[k])) {
      if (isnan(x[k])) continue;
      x[k] = d.lo[k];
      if (v[k] < 0.0) v[k] = -restitution * v[k];
    } else if (x[k] > d.hi[k]) {
      x[k] = d.hi[k];
      if (v[k] > 0.0) v[k] = -restitution * v[k];
    }
  }
  a.vx[i] = v[0], a.vy[i] = v[1], a.vz[i] = v[2];
  a.x[i] = x[0], a.y[i] = x[1], a.z[i] = x[2];
}

// Reduction targets: non-negative doubles compare as their bit patterns.
struct LimitBits {
  unsigned long long speed2, acceleration2;
  unsigned int neighbours, compressed;
};

__global__ void reduce_limits(Arrays a, std::size_t n, double rest_density, LimitBits* out) {
  const std::size_t i = blockIdx.x * static_cast<std::size_t>(blockDim.x) + threadIdx.x;
  double v2 = 0.0, a2 = 0.0;
  unsigned int nb = 0, compressed = 0;
  if (i < n && !a.wall[i]) {
    v2 = a.vx[i] * a.vx[i] + a.vy[i] * a.vy[i] + a.vz[i] * a.vz[i];
    a2 = a.ax[i] * a.ax[i] + a.ay[i] * a.ay[i] + a.az[i] * a.az[i];
    nb = a.nb[i];
    compressed = a.rho[i] > rest_density ? 1u : 0u;
  }
  for (int offset = 16; offset > 0; offset /= 2) {
    v2 = fmax(v2, __shfl_down_sync(0xFFFFFFFFu, v2, offset));
    a2 = fmax(a2, __shfl_down_sync(0xFFFFFFFFu, a2, offset));
    nb = max(nb, __shfl_down_sync(0xFFFFFFFFu, nb, offset));
    compressed |= __shfl_down_sync(0xFFFFFFFFu, compressed, offset);
  }
  if ((threadIdx.x & 31) == 0) {
    atomicMax(&out->speed2, static_cast<unsigned long long>(__double_as_longlong(v2)));
    atomicMax(&out->acceleration2, static_cast<unsigned long long>(__double_as_longlong(a2)));
    atomicMax(&out->neighbours, nb);
    if (compressed) atomicOr(&out->compressed, 1u);
  }
}

__global__ void agitate_kernel(Arrays a, std::size_t n, std::uint64_t seed, std::uint64_t frame,
                               double kick_horizontal, double kick_up) {
  const std::size_t i = blockIdx.x * static_cast<std::size_t>(blockDim.x) + threadIdx.x;
  if (i >= n || a.wall[i]) return;
  // The CPU's generator, seeded by (run seed, frame, particle id): the same kicks.
  std::uint64_t state =
      splitmix64_mix(seed ^ splitmix64_mix(frame ^ (static_cast<std::uint64_t>(a.id[i]) << 32)));
  auto uniform = [&](double lo, double hi) {
    state += 0x9e3779b97f4a7c15ULL;
    return lo + (hi - lo) * static_cast<double>(splitmix64_mix(state) >> 11) * 0x1.0p-53;
  };
  a.vx[i] = uniform(-kick_horizontal, kick_horizontal);
  a.vy[i] = uniform(-kick_horizontal, kick_horizontal);
  a.vz[i] = uniform(0.0, kick_up);
}

// The first unsound fluid particle by id: (id << 8 | kind), minimised.
__global__ void check_kernel(Arrays a, std::size_t n, Bounds d, const DeviceBox* boxes,
                             int box_count, unsigned long long* first) {
  const std::size_t i = blockIdx.x * static_cast<std::size_t>(blockDim.x) + threadIdx.x;
  if (i >= n || a.wall[i]) return;
  const double x[3] = {a.x[i], a.y[i], a.z[i]};
  int kind = Problem::none;
  if (!isfinite(x[0]) || !isfinite(x[1]) || !isfinite(x[2]))
    kind = Problem::position;
  else if (!isfinite(a.vx[i]) || !isfinite(a.vy[i]) || !isfinite(a.vz[i]))
    kind = Problem::velocity;
  else if (!isfinite(a.rho[i]) || !isfinite(a.p[i]))
    kind = Problem::density;
  else {
    bool inside = true;
    for (int k = 0; k < 3; ++k) inside = inside && x[k] >= d.lo[k] && x[k] <= d.hi[k];
    if (!inside) kind = Problem::outside;
    for (int b = 0; b < box_count && kind == Problem::none; ++b)
      if (in_interior(boxes[b], x)) kind = Problem::in_box;
  }
  if (kind != Problem::none)
    atomicMin(first, (static_cast<unsigned long long>(a.id[i]) << 8) |
                         static_cast<unsigned long long>(kind));
}

}  // namespace

// ---- the host side ---------------------------------------------------------------------------

struct DeviceFluid::Impl {
  std::size_t n = 0;
  DeviceParams params;
  DeviceGrid grid;
  std::uint64_t seed = 0;
  std::size_t cells = 0;
  int key_bits = 1;
  Arrays cur{}, alt{};
  int cur_set = 0;  // which buffer set `cur` is (0 or 1), for the copy-back's hazard
  std::uint32_t *key = nullptr, *key_sorted = nullptr, *index = nullptr, *order = nullptr;
  std::uint32_t *cell_start = nullptr, *cell_end = nullptr;
  void* sort_temp = nullptr;
  std::size_t sort_temp_bytes = 0;
  DeviceBox* boxes = nullptr;
  int box_capacity = 0;
  LimitBits* limits_dev = nullptr;
  LimitBits* limits_host = nullptr;  // pinned
  unsigned long long* problem_dev = nullptr;
  unsigned long long* problem_host = nullptr;  // pinned
  // The copy-back: pinned buffers, its own stream, an event when it is done.
  double *px = nullptr, *py = nullptr, *pz = nullptr;
  std::uint32_t* pid = nullptr;
  std::uint8_t* pwall = nullptr;
  bool copy_pending = false;
  int copy_set = -1;  // the buffer set being copied (a gather must not overwrite it meanwhile)
  cudaStream_t compute = nullptr, copy = nullptr;
  cudaEvent_t frame_done = nullptr, copy_done = nullptr, grid_begin = nullptr, grid_end = nullptr;
  bool grid_timed = false;
  double grid_ms = 0.0;

  Grid grid_view() const { return {grid, cell_start, cell_end, params.support * params.support}; }

  void upload_boxes(const DeviceBox* host, int count) {
    if (count > box_capacity) {
      cudaFree(boxes);
      boxes = device_alloc<DeviceBox>(static_cast<std::size_t>(count));
      box_capacity = count;
    }
    if (count > 0)
      ensure(cudaMemcpyAsync(boxes, host, sizeof(DeviceBox) * static_cast<std::size_t>(count),
                             cudaMemcpyHostToDevice, compute),
             "copy the boxes");
  }
};

std::string unavailable_reason() {
  int count = 0;
  const cudaError_t e = cudaGetDeviceCount(&count);
  if (e != cudaSuccess) return std::string("no usable CUDA device (") + cudaGetErrorString(e) + ")";
  if (count == 0) return "no CUDA device is present";
  return "";
}

std::string device_name() {
  cudaDeviceProp prop{};
  if (cudaGetDeviceProperties(&prop, 0) != cudaSuccess) return "?";
  return prop.name;
}

DeviceFluid::DeviceFluid(const HostParticles& h, const DeviceParams& params, const DeviceGrid& grid,
                         std::uint64_t seed)
    : impl_(new Impl) {
  Impl& m = *impl_;
  m.n = h.count;
  m.params = params;
  m.grid = grid;
  m.seed = seed;
  m.cells = static_cast<std::size_t>(grid.n[0] * grid.n[1] * grid.n[2]);
  while (m.key_bits < 32 && (std::size_t{1} << m.key_bits) < m.cells) ++m.key_bits;
  ensure(cudaStreamCreateWithFlags(&m.compute, cudaStreamNonBlocking), "create a stream");
  ensure(cudaStreamCreateWithFlags(&m.copy, cudaStreamNonBlocking), "create a stream");
  ensure(cudaEventCreateWithFlags(&m.frame_done, cudaEventDisableTiming), "create an event");
  ensure(cudaEventCreateWithFlags(&m.copy_done, cudaEventDisableTiming), "create an event");
  ensure(cudaEventCreate(&m.grid_begin), "create an event");
  ensure(cudaEventCreate(&m.grid_end), "create an event");
  m.cur = alloc_arrays(m.n);
  m.alt = alloc_arrays(m.n);
  m.key = device_alloc<std::uint32_t>(m.n);
  m.key_sorted = device_alloc<std::uint32_t>(m.n);
  m.index = device_alloc<std::uint32_t>(m.n);
  m.order = device_alloc<std::uint32_t>(m.n);
  m.cell_start = device_alloc<std::uint32_t>(m.cells);
  m.cell_end = device_alloc<std::uint32_t>(m.cells);
  ensure(cub::DeviceRadixSort::SortPairs(nullptr, m.sort_temp_bytes, m.key, m.key_sorted, m.index,
                                         m.order, static_cast<int>(m.n), 0, m.key_bits, m.compute),
         "size the sort");
  m.sort_temp = device_alloc<char>(m.sort_temp_bytes);
  m.limits_dev = device_alloc<LimitBits>(1);
  m.problem_dev = device_alloc<unsigned long long>(1);
  ensure(cudaMallocHost(&m.limits_host, sizeof(LimitBits)), "cudaMallocHost");
  ensure(cudaMallocHost(&m.problem_host, sizeof(unsigned long long)), "cudaMallocHost");
  const std::size_t bytes = (m.n > 0 ? m.n : 1) * sizeof(double);
  ensure(cudaMallocHost(&m.px, bytes), "cudaMallocHost");
  ensure(cudaMallocHost(&m.py, bytes), "cudaMallocHost");
  ensure(cudaMallocHost(&m.pz, bytes), "cudaMallocHost");
  ensure(cudaMallocHost(&m.pid, (m.n > 0 ? m.n : 1) * sizeof(std::uint32_t)), "cudaMallocHost");
  ensure(cudaMallocHost(&m.pwall, m.n > 0 ? m.n : 1), "cudaMallocHost");
  // The one upload of the particles.
  for_each_array(m.cur, h, [&](void* device, const void* host, std::size_t size) {
    ensure(cudaMemcpy(device, host, size * m.n, cudaMemcpyHostToDevice), "upload the particles");
  });
}

DeviceFluid::~DeviceFluid() {
  Impl& m = *impl_;
  cudaDeviceSynchronize();
  free_arrays(m.cur);
  free_arrays(m.alt);
  void* d[] = {m.key,      m.key_sorted, m.index, m.order,      m.cell_start,
               m.cell_end, m.sort_temp,  m.boxes, m.limits_dev, m.problem_dev};
  for (void* q : d) cudaFree(q);
  void* pinned[] = {m.limits_host, m.problem_host, m.px, m.py, m.pz, m.pid, m.pwall};
  for (void* q : pinned) cudaFreeHost(q);
  cudaEventDestroy(m.frame_done);
  cudaEventDestroy(m.copy_done);
  cudaEventDestroy(m.grid_begin);
  cudaEventDestroy(m.grid_end);
  cudaStreamDestroy(m.compute);
  cudaStreamDestroy(m.copy);
  delete impl_;
}

Limits DeviceFluid::limits() {
  Impl& m = *impl_;
  ensure(cudaMemsetAsync(m.limits_dev, 0, sizeof(LimitBits), m.compute), "clear the limits");
  if (m.n > 0)
    reduce_limits<<<blocks_for(m.n), kBlock, 0, m.compute>>>(m.cur, m.n, m.params.rest_density,
                                                             m.limits_dev);
  ensure(cudaGetLastError(), "reduce the limits");
  ensure(cudaMemcpyAsync(m.limits_host, m.limits_dev, sizeof(LimitBits), cudaMemcpyDeviceToHost,
                         m.compute),
         "copy the limits");
  ensure(cudaStreamSynchronize(m.compute), "the substep");
  if (m.grid_timed) {
    float ms = 0.0f;
    ensure(cudaEventElapsedTime(&ms, m.grid_begin, m.grid_end), "time the grid");
    m.grid_ms = ms;
  }
  Limits l;
  const LimitBits& b = *m.limits_host;
  std::memcpy(&l.max_speed2, &b.speed2, sizeof(double));
  std::memcpy(&l.max_acceleration2, &b.acceleration2, sizeof(double));
  l.most_neighbours = b.neighbours;
  l.compressed = b.compressed != 0;
  return l;
}

void DeviceFluid::substep(double dt, const double domain_lo[3], const double domain_hi[3],
                          const DeviceBox* boxes, int box_count) {
  Impl& m = *impl_;
  if (m.n == 0) return;
  m.upload_boxes(boxes, box_count);
  const unsigned blocks = blocks_for(m.n);
  ensure(cudaEventRecord(m.grid_begin, m.compute), "record an event");
  cell_keys<<<blocks, kBlock, 0, m.compute>>>(m.cur, m.n, m.grid, m.key, m.index);
  ensure(
      cub::DeviceRadixSort::SortPairs(m.sort_temp, m.sort_temp_bytes, m.key, m.key_sorted, m.index,
                                      m.order, static_cast<int>(m.n), 0, m.key_bits, m.compute),
      "sort by cell");
  // The gather writes the other buffer set: if a copy-back still reads it, wait for that.
  if (m.copy_pending && m.copy_set == 1 - m.cur_set)
    ensure(cudaStreamWaitEvent(m.compute, m.copy_done, 0), "wait for the copy-back");
  gather<<<blocks, kBlock, 0, m.compute>>>(m.alt, m.cur, m.order, m.n);
  std::swap(m.cur, m.alt);
  m.cur_set = 1 - m.cur_set;
  ensure(cudaMemsetAsync(m.cell_start, 0xFF, m.cells * sizeof(std::uint32_t), m.compute),
         "clear the cells");
  cell_ranges<<<blocks, kBlock, 0, m.compute>>>(m.key_sorted, m.n, m.cell_start, m.cell_end);
  ensure(cudaEventRecord(m.grid_end, m.compute), "record an event");
  m.grid_timed = true;
  const Grid g = m.grid_view();
  if (m.params.water) {
    water_density<<<blocks, kBlock, 0, m.compute>>>(m.cur, m.n, g, m.params, dt);
    water_walls<<<blocks, kBlock, 0, m.compute>>>(m.cur, m.n, g, m.params);
    water_forces<<<blocks, kBlock, 0, m.compute>>>(m.cur, m.n, g, m.params);
  } else {
    seed_density<<<blocks, kBlock, 0, m.compute>>>(m.cur, m.n, g, m.params);
    seed_forces<<<blocks, kBlock, 0, m.compute>>>(m.cur, m.n, g, m.params);
  }
  Bounds d{};
  for (int k = 0; k < 3; ++k) d.lo[k] = domain_lo[k], d.hi[k] = domain_hi[k];
  integrate<<<blocks, kBlock, 0, m.compute>>>(m.cur, m.n, dt, d, m.boxes, box_count,
                                              m.params.restitution);
  ensure(cudaGetLastError(), "launch the substep");
}

void DeviceFluid::agitate(std::uint64_t frame) {
  Impl& m = *impl_;
  if (m.n == 0) return;
  agitate_kernel<<<blocks_for(m.n), kBlock, 0, m.compute>>>(
      m.cur, m.n, m.seed, frame, m.params.kick_horizontal, m.params.kick_up);
  ensure(cudaGetLastError(), "agitate");
}

void DeviceFluid::start_position_copy() {
  Impl& m = *impl_;
  if (m.copy_pending) ensure(cudaEventSynchronize(m.copy_done), "the copy-back");
  ensure(cudaEventRecord(m.frame_done, m.compute), "record an event");
  ensure(cudaStreamWaitEvent(m.copy, m.frame_done, 0), "order the copy-back");
  const std::size_t n = m.n;
  auto down = [&](void* to, const void* from, std::size_t size) {
    ensure(cudaMemcpyAsync(to, from, size * n, cudaMemcpyDeviceToHost, m.copy), "copy back");
  };
  down(m.px, m.cur.x, 8), down(m.py, m.cur.y, 8), down(m.pz, m.cur.z, 8);
  down(m.pid, m.cur.id, 4), down(m.pwall, m.cur.wall, 1);
  ensure(cudaEventRecord(m.copy_done, m.copy), "record an event");
  m.copy_pending = true;
  m.copy_set = m.cur_set;
}

void DeviceFluid::finish_position_copy(HostParticles& out) {
  Impl& m = *impl_;
  if (!m.copy_pending) return;
  ensure(cudaEventSynchronize(m.copy_done), "the copy-back");
  m.copy_pending = false;
  const std::size_t n = m.n;
  std::memcpy(out.x, m.px, n * 8), std::memcpy(out.y, m.py, n * 8), std::memcpy(out.z, m.pz, n * 8);
  std::memcpy(out.id, m.pid, n * 4), std::memcpy(out.wall, m.pwall, n);
}

void DeviceFluid::download(HostParticles& h) {
  Impl& m = *impl_;
  if (m.copy_pending) {
    ensure(cudaEventSynchronize(m.copy_done), "the copy-back");
    m.copy_pending = false;
  }
  ensure(cudaStreamSynchronize(m.compute), "the substep");
  for_each_array(m.cur, h, [&](const void* device, void* host, std::size_t size) {
    ensure(cudaMemcpy(host, device, size * m.n, cudaMemcpyDeviceToHost), "download the particles");
  });
}

Problem DeviceFluid::check(const double domain_lo[3], const double domain_hi[3],
                           const DeviceBox* boxes, int box_count) {
  Impl& m = *impl_;
  Problem result;
  if (m.n == 0) return result;
  m.upload_boxes(boxes, box_count);
  ensure(cudaMemsetAsync(m.problem_dev, 0xFF, sizeof(unsigned long long), m.compute),
         "clear the check");
  Bounds d{};
  for (int k = 0; k < 3; ++k) d.lo[k] = domain_lo[k], d.hi[k] = domain_hi[k];
  check_kernel<<<blocks_for(m.n), kBlock, 0, m.compute>>>(m.cur, m.n, d, m.boxes, box_count,
                                                          m.problem_dev);
  ensure(cudaGetLastError(), "check the fluid");
  ensure(cudaMemcpyAsync(m.problem_host, m.problem_dev, sizeof(unsigned long long),
                         cudaMemcpyDeviceToHost, m.compute),
         "copy the check");
  ensure(cudaStreamSynchronize(m.compute), "check the fluid");
  const unsigned long long first = *m.problem_host;
  if (first != ~0ull) {
    result.kind = static_cast<Problem::Kind>(first & 0xFF);
    result.id = static_cast<std::uint32_t>(first >> 8);
  }
  return result;
}

double DeviceFluid::last_grid_ms() const {
  return impl_->grid_ms;
}

}  // namespace hpcplan::sph::cuda
