// The CUDA backend's entry points in a build without it (no CUDA compiler was found when the
// build was configured).
#include "hpcplan/core/error.hpp"
#include "hpcplan/sph/step_backend.hpp"

namespace hpcplan::sph {

std::string cuda_unavailable_reason() {
  return "this build has no CUDA backend (no CUDA compiler was found when it was configured; "
         "scripts/setup.sh --with-cuda installs one)";
}

std::string cuda_device_name() {
  return "";
}

std::unique_ptr<StepBackend> make_cuda_backend(const FluidState&) {
  throw InputError("--backend cuda: " + cuda_unavailable_reason());
}

}  // namespace hpcplan::sph
