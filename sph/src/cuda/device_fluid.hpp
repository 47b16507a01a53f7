#pragma once
// The GPU side of the CUDA backend, behind a plain interface: nothing here names a CUDA type,
// and the header is C++17, so that nvcc (Debian ships 11.8, which has no C++20) compiles the
// kernels while the rest of hpcplan stays C++20. cuda_backend.cpp adapts a FluidState to it.
//
// The particles live on the GPU from construction on, in the same structure of arrays as the
// CPU's (sph::Particles), in double precision, sorted by cell every substep (radix sort of the
// cell keys, then one gather of every array into a second set of buffers). Only positions, ids
// and wall flags come back each frame, into pinned buffers, on a stream of their own.
//
// Threads: one host thread uses a DeviceFluid.
#include <cstddef>
#include <cstdint>
#include <string>

namespace hpcplan::sph::cuda {

// The physics parameters the kernels read (a copy of FluidParams' numbers).
struct DeviceParams {
  bool water = false;  // false: the seed preset's Müller kernels
  double particle_mass = 0, rest_density = 0, support = 0, smoothing_length = 0;
  double gravity[3] = {0, 0, 0};
  double gas_constant = 0, viscosity = 0;  // seed
  double sound_speed = 0, alpha = 0;       // water
  double restitution = 0;
  double kick_horizontal = 0, kick_up = 0;
};

// The neighbour grid's geometry (as sph::NeighbourGrid computes it: cells no smaller than
// the support, x fastest).
struct DeviceGrid {
  double lo[3] = {0, 0, 0};
  double inv_cell[3] = {0, 0, 0};
  std::int64_t n[3] = {1, 1, 1};
};

struct DeviceBox {
  double lo[3], hi[3], v[3];
};

// Host arrays of one particle set, each `count` long (the vectors of sph::Particles).
struct HostParticles {
  std::size_t count = 0;
  double *x = nullptr, *y = nullptr, *z = nullptr;
  double *vx = nullptr, *vy = nullptr, *vz = nullptr;
  double *ax = nullptr, *ay = nullptr, *az = nullptr;
  double *rho = nullptr, *drho = nullptr, *p = nullptr;
  std::uint32_t *neighbours = nullptr, *id = nullptr;
  std::uint8_t* wall = nullptr;
};

struct Limits {
  double max_speed2 = 0, max_acceleration2 = 0;
  std::uint32_t most_neighbours = 0;
  bool compressed = false;
};

// The first unsound fluid particle (by id), as first_problem() words it.
struct Problem {
  enum Kind : int { none = 0, position, velocity, density, outside, in_box };
  Kind kind = none;
  std::uint32_t id = 0;
};

// "" when a CUDA device is usable, else why not (no device, driver too old, ...).
std::string unavailable_reason();
// The device's name ("NVIDIA H100 80GB HBM3").
std::string device_name();

class DeviceFluid {
 public:
  DeviceFluid(const HostParticles& particles, const DeviceParams& params, const DeviceGrid& grid,
              std::uint64_t seed);
  ~DeviceFluid();
  DeviceFluid(const DeviceFluid&) = delete;
  DeviceFluid& operator=(const DeviceFluid&) = delete;

  Limits limits();  // waits for the reduction
  // One substep: sort by cell, cell ranges, densities, (water) wall pressures, accelerations,
  // integration against the domain and the boxes (their positions at the substep's end).
  void substep(double dt, const double domain_lo[3], const double domain_hi[3],
               const DeviceBox* boxes, int box_count);
  void agitate(std::uint64_t frame);
  // Starts copying positions, ids and wall flags back (asynchronous, pinned buffers).
  void start_position_copy();
  // Waits for the copy started last (if any is pending) and writes it into `out`.
  void finish_position_copy(HostParticles& out);
  // Every array into `out` (waits).
  void download(HostParticles& out);
  // The first unsound fluid particle after the last substep (waits for a small result).
  Problem check(const double domain_lo[3], const double domain_hi[3], const DeviceBox* boxes,
                int box_count);
  // Milliseconds the last substep's sort and cell ranges took on the GPU.
  double last_grid_ms() const;

 private:
  struct Impl;
  Impl* impl_;
};

}  // namespace hpcplan::sph::cuda
