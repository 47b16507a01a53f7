#pragma once
// The GPU side of the CUDA backend, behind a plain interface: nothing here names a CUDA type,
// and the header is C++17, so that nvcc (Debian ships 11.8, which has no C++20) compiles the
// kernels while the rest of hpcplan stays C++20. cuda_backend.cpp adapts a FluidState to it.
//
// The physics is not here: the kernels run the phases of physics.hpp, the one source both
// backends include. The particles live on the GPU from construction on, in the fields of
// particle_fields.hpp, in double precision, sorted by cell every substep (radix sort of the
// cell keys, then one gather of every field into a second set of buffers). Only positions,
// ids and wall flags come back each frame, into pinned buffers, on a stream of their own.
//
// Threads: one host thread uses a DeviceFluid.
#include <cstddef>
#include <cstdint>
#include <string>

#include "hpcplan/sph/particle_fields.hpp"
#include "hpcplan/sph/physics/grid_walk.hpp"
#include "hpcplan/sph/physics/params.hpp"
#include "hpcplan/sph/physics/push_out.hpp"

namespace hpcplan::sph::cuda {

struct Limits {
  double max_speed2 = 0, max_acceleration2 = 0;
  std::uint32_t most_neighbours = 0;
  bool compressed = false;
};

// The first unsound fluid particle, by id.
struct Problem {
  ParticleProblem kind = ParticleProblem::none;
  std::uint32_t id = 0;
};

// "" when a CUDA device is usable, else why not (no device, driver too old, ...).
std::string unavailable_reason();
// The device's name ("NVIDIA H100 80GB HBM3").
std::string device_name();

class DeviceFluid {
 public:
  // `host`: `count` particles, every field (uploaded once).
  DeviceFluid(const ParticleView& host, std::size_t count, const FluidParams& params,
              const GridGeometry& grid, std::uint64_t seed);
  ~DeviceFluid();
  DeviceFluid(const DeviceFluid&) = delete;
  DeviceFluid& operator=(const DeviceFluid&) = delete;

  Limits limits();  // waits for the reduction
  // One substep: sort by cell, cell ranges, the preset's force phases, Integrate against the
  // domain and the boxes (their positions at the substep's end).
  void substep(double dt, const Box3& domain, const MovingBox* boxes, int box_count);
  void agitate(std::uint64_t frame);
  // Starts copying positions, ids and wall flags back (asynchronous, pinned buffers).
  void start_position_copy();
  // Waits for the copy started last (if any is pending) and writes it into `out`.
  void finish_position_copy(const ParticleView& out);
  // Every field into `out` (waits).
  void download(const ParticleView& out);
  // The first unsound fluid particle after the last substep (waits for a small result).
  Problem check(const Box3& domain, const MovingBox* boxes, int box_count);
  // Milliseconds the last substep's sort and cell ranges took on the GPU.
  double last_grid_ms() const;

 private:
  struct Impl;
  Impl* impl_;
};

}  // namespace hpcplan::sph::cuda
