// The CUDA backend: the StepBackend calls in terms of cuda::DeviceFluid (cuda/device_fluid.cu).
// The boxes move on the host (a handful of numbers) and go to the GPU with each substep, as
// they are (MovingBox is plain data both sides read); the particles stay on the GPU.
#include <string>
#include <vector>

#include "cuda/device_fluid.hpp"
#include "hpcplan/core/error.hpp"
#include "hpcplan/sph/boundaries.hpp"
#include "hpcplan/sph/fluid.hpp"
#include "hpcplan/sph/step_backend.hpp"

namespace hpcplan::sph {

namespace {

class CudaBackend final : public StepBackend {
 public:
  // The upload only reads the arrays (a ParticleView has one pointer type for both ways).
  explicit CudaBackend(const FluidState& s)
      : device_(const_cast<Particles&>(s.particles).view(), s.particles.size(), s.params,
                s.grid.geometry(), s.seed) {}

  std::string name() const override { return "cuda"; }

  double stable_dt(const FluidState& s) override {
    const cuda::Limits l = device_.limits();
    return stable_dt_from(s, {l.max_speed2, l.max_acceleration2, l.most_neighbours, l.compressed});
  }

  SubstepReport substep(FluidState& s, double dt) override {
    for (MovingBox& b : s.boxes) move_box(s.domain, b, dt);
    device_.substep(dt, s.domain, s.boxes.data(), static_cast<int>(s.boxes.size()));
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
    const cuda::Problem p =
        device_.check(s.domain, s.boxes.data(), static_cast<int>(s.boxes.size()));
    return describe(p.kind, p.id);
  }

  void sync_positions(FluidState& s) override {
    if (!copied_) {  // asked between frames' ends (a per-substep observer): copy now
      device_.start_position_copy();
      copied_ = true;
    }
    device_.finish_position_copy(s.particles.view());
  }

  void download(FluidState& s) override { device_.download(s.particles.view()); }

 private:
  cuda::DeviceFluid device_;
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
