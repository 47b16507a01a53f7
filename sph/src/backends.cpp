#include <string>

#include "hpcplan/core/error.hpp"
#include "hpcplan/sph/step_backend.hpp"

namespace hpcplan::sph {

void check_backend_name(std::string_view name) {
  if (name == "cpu") return;
  if (name != "cuda")
    throw InputError("unknown --backend '" + std::string(name) + "' (expected cpu or cuda)");
  if (const std::string why = cuda_unavailable_reason(); !why.empty())
    throw InputError("--backend cuda: " + why);
}

std::unique_ptr<StepBackend> make_backend(std::string_view name, const FluidState& state) {
  check_backend_name(name);
  return name == "cpu" ? make_cpu_backend() : make_cuda_backend(state);
}

}  // namespace hpcplan::sph
