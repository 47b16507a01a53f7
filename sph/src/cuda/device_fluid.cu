// The CUDA backend's loops and bookkeeping. The physics is physics.hpp's, the same source the
// CPU backend runs: each phase is a kernel with one thread per particle (run_phase), and a
// thread writes only its particle's entries, as on the CPU. What differs is bookkeeping:
//   - the particles are sorted by cell every substep (CUB's radix sort of the cell keys, then a
//     gather of every field into the second buffer set), so a cell's particles are contiguous
//     and the 3 cells of an x-row form one range: a neighbour query reads 9 ranges;
//   - neighbours are found from the cell ranges in every pass (no lists: the GPU re-reads the
//     ranges faster than it could store 96 indices per particle);
//   - sums run in cell order, so results match the CPU's to round-off, not bit for bit.
#include <cuda_runtime.h>
#include <cub/device/device_radix_sort.cuh>

#include <cstring>
#include <stdexcept>
#include <string>
#include <utility>

#include "device_fluid.hpp"
#include "hpcplan/sph/physics.hpp"

namespace hpcplan::sph::cuda {

namespace {

constexpr int kBlock = 256;
constexpr std::uint32_t kEmpty = 0xFFFFFFFFu;

void ensure(cudaError_t e, const char* what) {
  if (e != cudaSuccess)
    throw std::runtime_error(std::string("CUDA: ") + what + ": " + cudaGetErrorString(e));
}

unsigned blocks_for(std::size_t n) {
  return static_cast<unsigned>((n + kBlock - 1) / kBlock);
}

template <class T>
T* device_alloc(std::size_t n) {
  void* ptr = nullptr;
  ensure(cudaMalloc(&ptr, (n > 0 ? n : 1) * sizeof(T)), "cudaMalloc");
  return static_cast<T*>(ptr);
}

// Every field of particle_fields.hpp on the device.
ParticleView alloc_fields(std::size_t n) {
  ParticleView a;
  for_each_field(a, [&](auto*& field) {
    field = device_alloc<std::remove_pointer_t<std::remove_reference_t<decltype(field)>>>(n);
  });
  return a;
}

void free_fields(ParticleView& a) {
  for_each_field(a, [](auto*& field) {
    cudaFree(field);
    field = nullptr;
  });
}

// The cell-sorted particles' ranges per cell, and the grid they belong to.
struct CellRanges {
  GridGeometry g;
  const std::uint32_t* start;
  const std::uint32_t* end;
  double support2;
};

// One force phase of physics/phases.hpp over every particle: neighbours from the cell ranges.
template <class Phase>
__global__ void run_phase(Phase phase, StepView s, std::size_t n, CellRanges cells) {
  const std::size_t i = blockIdx.x * static_cast<std::size_t>(blockDim.x) + threadIdx.x;
  if (i >= n) return;
  const ParticleView& a = s.a;
  phase(s, i, [&](auto&& fn) {
    for_each_within(
        cells.g, cells.support2, a.x[i], a.y[i], a.z[i], a.x, a.y, a.z,
        [&](std::uint64_t first, std::uint64_t last, auto&& visit) {
          // The cells of one x-row are consecutive in key order: their particles, one range.
          std::uint32_t b = kEmpty, e = 0;
          for (std::uint64_t c = first; c <= last; ++c) {
            if (cells.start[c] == kEmpty) continue;
            if (b == kEmpty) b = cells.start[c];
            e = cells.end[c];
          }
          if (b == kEmpty) return;
          for (std::uint32_t q = b; q < e; ++q) visit(q);
        },
        [&](std::uint32_t j, double dx, double dy, double dz, double r2) {
          if (j != i) fn(j, dx, dy, dz, r2);
        });
  });
}

// A phase without neighbours (Integrate) over every particle.
template <class Phase>
__global__ void run_local(Phase phase, StepView s, std::size_t n) {
  const std::size_t i = blockIdx.x * static_cast<std::size_t>(blockDim.x) + threadIdx.x;
  if (i < n) phase(s, i);
}

__global__ void cell_keys(ParticleView a, std::size_t n, GridGeometry g, std::uint32_t* key,
                          std::uint32_t* index) {
  const std::size_t i = blockIdx.x * static_cast<std::size_t>(blockDim.x) + threadIdx.x;
  if (i >= n) return;
  key[i] = cell_key(g, a.x[i], a.y[i], a.z[i]);
  index[i] = static_cast<std::uint32_t>(i);
}

// Every field of particle k of `to` from particle order[k] of `from`.
__global__ void gather(ParticleView to, ParticleView from, const std::uint32_t* order,
                       std::size_t n) {
  const std::size_t k = blockIdx.x * static_cast<std::size_t>(blockDim.x) + threadIdx.x;
  if (k >= n) return;
  const std::uint32_t i = order[k];
#define HPCPLAN_SPH_GATHER_FIELD(type, name) to.name[k] = from.name[i];
  HPCPLAN_SPH_PARTICLE_FIELDS(HPCPLAN_SPH_GATHER_FIELD)
#undef HPCPLAN_SPH_GATHER_FIELD
}

__global__ void cell_ranges(const std::uint32_t* key, std::size_t n, std::uint32_t* start,
                            std::uint32_t* end) {
  const std::size_t k = blockIdx.x * static_cast<std::size_t>(blockDim.x) + threadIdx.x;
  if (k >= n) return;
  const std::uint32_t c = key[k];
  if (k == 0 || key[k - 1] != c) start[c] = static_cast<std::uint32_t>(k);
  if (k + 1 == n || key[k + 1] != c) end[c] = static_cast<std::uint32_t>(k + 1);
}

// Reduction targets: non-negative doubles compare as their bit patterns.
struct LimitBits {
  unsigned long long speed2, acceleration2;
  unsigned int neighbours, compressed;
};

__global__ void reduce_limits(ParticleView a, std::size_t n, double rest_density, LimitBits* out) {
  const std::size_t i = blockIdx.x * static_cast<std::size_t>(blockDim.x) + threadIdx.x;
  double v2 = 0.0, a2 = 0.0;
  unsigned int nb = 0, compressed = 0;
  if (i < n && !a.wall[i]) {
    v2 = a.vx[i] * a.vx[i] + a.vy[i] * a.vy[i] + a.vz[i] * a.vz[i];
    a2 = a.ax[i] * a.ax[i] + a.ay[i] * a.ay[i] + a.az[i] * a.az[i];
    nb = a.neighbours[i];
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

__global__ void agitate_kernel(ParticleView a, std::size_t n, FluidParams f, std::uint64_t seed,
                               std::uint64_t frame) {
  const std::size_t i = blockIdx.x * static_cast<std::size_t>(blockDim.x) + threadIdx.x;
  if (i >= n || a.wall[i]) return;
  double v[3];
  agitation_velocity(f, seed, frame, a.id[i], v);
  a.vx[i] = v[0], a.vy[i] = v[1], a.vz[i] = v[2];
}

// The first unsound fluid particle by id: (id << 8 | kind), minimised.
__global__ void check_kernel(ParticleView a, std::size_t n, Box3 domain, const MovingBox* boxes,
                             int box_count, unsigned long long* first) {
  const std::size_t i = blockIdx.x * static_cast<std::size_t>(blockDim.x) + threadIdx.x;
  if (i >= n || a.wall[i]) return;
  const double x[3] = {a.x[i], a.y[i], a.z[i]}, v[3] = {a.vx[i], a.vy[i], a.vz[i]};
  const ParticleProblem kind = particle_problem(domain, boxes, box_count, x, v, a.rho[i], a.p[i]);
  if (kind != ParticleProblem::none)
    atomicMin(first, (static_cast<unsigned long long>(a.id[i]) << 8) |
                         static_cast<unsigned long long>(kind));
}

}  // namespace

// ---- the host side ---------------------------------------------------------------------------

struct DeviceFluid::Impl {
  std::size_t n = 0;
  FluidParams params;
  GridGeometry grid;
  std::uint64_t seed = 0;
  std::size_t cells = 0;
  int key_bits = 1;
  ParticleView cur{}, alt{};
  int cur_set = 0;  // which buffer set `cur` is (0 or 1), for the copy-back's hazard
  std::uint32_t *key = nullptr, *key_sorted = nullptr, *index = nullptr, *order = nullptr;
  std::uint32_t *cell_start = nullptr, *cell_end = nullptr;
  void* sort_temp = nullptr;
  std::size_t sort_temp_bytes = 0;
  MovingBox* boxes = nullptr;
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

  CellRanges cell_ranges_view() const {
    return {grid, cell_start, cell_end, params.support * params.support};
  }

  void upload_boxes(const MovingBox* host, int count) {
    if (count > box_capacity) {
      cudaFree(boxes);
      boxes = device_alloc<MovingBox>(static_cast<std::size_t>(count));
      box_capacity = count;
    }
    if (count > 0)
      ensure(cudaMemcpyAsync(boxes, host, sizeof(MovingBox) * static_cast<std::size_t>(count),
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

DeviceFluid::DeviceFluid(const ParticleView& h, std::size_t count, const FluidParams& params,
                         const GridGeometry& grid, std::uint64_t seed)
    : impl_(new Impl) {
  Impl& m = *impl_;
  m.n = count;
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
  m.cur = alloc_fields(m.n);
  m.alt = alloc_fields(m.n);
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
  for_each_field_pair(m.cur, h, [&](auto* device, const auto* host) {
    ensure(cudaMemcpy(device, host, sizeof(*host) * m.n, cudaMemcpyHostToDevice),
           "upload the particles");
  });
}

DeviceFluid::~DeviceFluid() {
  Impl& m = *impl_;
  cudaDeviceSynchronize();
  free_fields(m.cur);
  free_fields(m.alt);
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

void DeviceFluid::substep(double dt, const Box3& domain, const MovingBox* boxes, int box_count) {
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
  const CellRanges cells = m.cell_ranges_view();
  const StepView view{m.cur, dt, domain, m.boxes, box_count};
  with_solver(m.params.preset, [&](auto solver) {
    decltype(solver)::force_phases(m.params, [&](const auto& phase) {
      run_phase<<<blocks, kBlock, 0, m.compute>>>(phase, view, m.n, cells);
    });
  });
  run_local<<<blocks, kBlock, 0, m.compute>>>(Integrate(m.params), view, m.n);
  ensure(cudaGetLastError(), "launch the substep");
}

void DeviceFluid::agitate(std::uint64_t frame) {
  Impl& m = *impl_;
  if (m.n == 0) return;
  agitate_kernel<<<blocks_for(m.n), kBlock, 0, m.compute>>>(m.cur, m.n, m.params, m.seed, frame);
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

void DeviceFluid::finish_position_copy(const ParticleView& out) {
  Impl& m = *impl_;
  if (!m.copy_pending) return;
  ensure(cudaEventSynchronize(m.copy_done), "the copy-back");
  m.copy_pending = false;
  const std::size_t n = m.n;
  std::memcpy(out.x, m.px, n * 8), std::memcpy(out.y, m.py, n * 8), std::memcpy(out.z, m.pz, n * 8);
  std::memcpy(out.id, m.pid, n * 4), std::memcpy(out.wall, m.pwall, n);
}

void DeviceFluid::download(const ParticleView& h) {
  Impl& m = *impl_;
  if (m.copy_pending) {
    ensure(cudaEventSynchronize(m.copy_done), "the copy-back");
    m.copy_pending = false;
  }
  ensure(cudaStreamSynchronize(m.compute), "the substep");
  for_each_field_pair(h, m.cur, [&](auto* host, const auto* device) {
    ensure(cudaMemcpy(host, device, sizeof(*device) * m.n, cudaMemcpyDeviceToHost),
           "download the particles");
  });
}

Problem DeviceFluid::check(const Box3& domain, const MovingBox* boxes, int box_count) {
  Impl& m = *impl_;
  Problem result;
  if (m.n == 0) return result;
  m.upload_boxes(boxes, box_count);
  ensure(cudaMemsetAsync(m.problem_dev, 0xFF, sizeof(unsigned long long), m.compute),
         "clear the check");
  check_kernel<<<blocks_for(m.n), kBlock, 0, m.compute>>>(m.cur, m.n, domain, m.boxes, box_count,
                                                          m.problem_dev);
  ensure(cudaGetLastError(), "check the fluid");
  ensure(cudaMemcpyAsync(m.problem_host, m.problem_dev, sizeof(unsigned long long),
                         cudaMemcpyDeviceToHost, m.compute),
         "copy the check");
  ensure(cudaStreamSynchronize(m.compute), "check the fluid");
  const unsigned long long first = *m.problem_host;
  if (first != ~0ull) {
    result.kind = static_cast<ParticleProblem>(first & 0xFF);
    result.id = static_cast<std::uint32_t>(first >> 8);
  }
  return result;
}

double DeviceFluid::last_grid_ms() const {
  return impl_->grid_ms;
}

}  // namespace hpcplan::sph::cuda
