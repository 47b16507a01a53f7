// The CUDA backend: the StepBackend calls in terms of cuda::DeviceFluid (cuda/device_fluid.cu).
// The boxes move on the host (a handful of numbers) and go to the GPU with each substep; the
// particles stay on the GPU.
#include <string>
#include <vector>

#include "cuda/device_fluid.hpp"
#include "hpcplan/core/error.hpp"
#include "hpcplan/sph/boundaries.hpp"
#include "hpcplan/sph/step_backend.hpp"

namespace hpcplan::sph {

namespace {

cuda::HostParticles view(Particles& p) {
  cuda::HostParticles h;
  h.count = p.size();
  h.x = p.x.data(), h.y = p.y.data(), h.z = p.z.data();
  h.vx = p.vx.data(), h.vy = p.vy.data(), h.vz = p.vz.data();
  h.ax = p.ax.data(), h.ay = p.ay.data(), h.az = p.az.data();
  h.rho = p.rho.data(), h.drho = p.drho.data(), h.p = p.p.data();
  h.neighbours = p.neighbours.data(), h.id = p.id.data(), h.wall = p.wall.data();
  return h;
}

cuda::DeviceParams device_params(const FluidParams& f) {
  cuda::DeviceParams d;
  d.water = f.preset == Preset::water;
  d.particle_mass = f.particle_mass;
  d.rest_density = f.rest_density;
  d.support = f.support;
  d.smoothing_length = f.smoothing_length;
  for (int k = 0; k < 3; ++k) d.gravity[k] = f.gravity[k];
  d.gas_constant = f.gas_constant;
  d.viscosity = f.viscosity;
  d.sound_speed = f.sound_speed;
  d.alpha = f.alpha;
  d.restitution = f.restitution;
  d.kick_horizontal = f.kick_horizontal;
  d.kick_up = f.kick_up;
  return d;
}

cuda::DeviceGrid device_grid(const NeighbourGrid& g) {
  cuda::DeviceGrid d;
  for (int k = 0; k < 3; ++k) {
    d.lo[k] = g.region().lo[k];
    d.inv_cell[k] = g.inverse_cell()[k];
    d.n[k] = g.cells_per_axis()[k];
  }
  return d;
}

class CudaBackend final : public StepBackend {
 public:
  // The upload only reads the arrays (HostParticles has one pointer type for both ways).
  explicit CudaBackend(const FluidState& s)
      : device_(view(const_cast<Particles&>(s.particles)), device_params(s.params),
                device_grid(s.grid), s.seed) {}

  std::string name() const override { return "cuda"; }

  double stable_dt(const FluidState& s) override {
    const cuda::Limits l = device_.limits();
    return stable_dt_from(s, {l.max_speed2, l.max_acceleration2, l.most_neighbours, l.compressed});
  }

  SubstepReport substep(FluidState& s, double dt) override {
    for (MovingBox& b : s.boxes) move_box(s.domain, b, dt);
    fill_boxes(s);
    device_.substep(dt, s.domain.lo.data(), s.domain.hi.data(), boxes_.data(),
                    static_cast<int>(boxes_.size()));
    s.time += dt;
    ++s.substeps;
    copied_ = false;
    // The GPU's time for the previous substep's sort (read at the last synchronisation).
    return {device_.last_grid_ms()};
  }

  void agitate(FluidState&, std::uint64_t frame) override { device_.agitate(frame); }

  std::string end_frame(FluidState& s) override {
    device_.start_position_copy();
    copied_ = true;
    fill_boxes(s);
    const cuda::Problem p = device_.check(s.domain.lo.data(), s.domain.hi.data(), boxes_.data(),
                                          static_cast<int>(boxes_.size()));
    const std::string who = "particle " + std::to_string(p.id);
    switch (p.kind) {
      case cuda::Problem::none:
        return "";
      case cuda::Problem::position:
        return "non-finite position of " + who;
      case cuda::Problem::velocity:
        return "non-finite velocity of " + who;
      case cuda::Problem::density:
        return "non-finite density or pressure of " + who;
      case cuda::Problem::outside:
        return who + " left the domain";
      case cuda::Problem::in_box:
        return who + " is inside an obstacle box";
    }
    return "unknown problem with " + who;
  }

  void sync_positions(FluidState& s) override {
    if (!copied_) {  // asked between frames' ends (a per-substep observer): copy now
      device_.start_position_copy();
      copied_ = true;
    }
    cuda::HostParticles h = view(s.particles);
    device_.finish_position_copy(h);
  }

  void download(FluidState& s) override {
    cuda::HostParticles h = view(s.particles);
    device_.download(h);
  }

 private:
  void fill_boxes(const FluidState& s) {
    boxes_.clear();
    for (const MovingBox& b : s.boxes) {
      cuda::DeviceBox d{};
      for (int k = 0; k < 3; ++k)
        d.lo[k] = b.box.lo[k], d.hi[k] = b.box.hi[k], d.v[k] = b.velocity[k];
      boxes_.push_back(d);
    }
  }

  cuda::DeviceFluid device_;
  std::vector<cuda::DeviceBox> boxes_;
  bool copied_ = true;  // a copy of the current positions was started (the upload's: current)
};

}  // namespace

std::string cuda_unavailable_reason() {
  return cuda::unavailable_reason();
}

std::string cuda_device_name() {
  return cuda::unavailable_reason().empty() ? cuda::device_name() : "";
}

std::unique_ptr<StepBackend> make_cuda_backend(const FluidState& state) {
  if (const std::string why = cuda::unavailable_reason(); !why.empty())
    throw InputError("--backend cuda: " + why);
  return std::make_unique<CudaBackend>(state);
}

}  // namespace hpcplan::sph
