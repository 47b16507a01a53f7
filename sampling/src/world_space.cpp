#include "hpcplan/sampling/world_space.hpp"

#include <cmath>
#include <string>

#include "hpcplan/core/error.hpp"

namespace hpcplan::sampling {

MotionCheck parse_motion_check(std::string_view name) {
  if (name == "exact") return MotionCheck::exact;
  if (name == "discrete") return MotionCheck::discrete;
  throw InputError("unknown --motion '" + std::string(name) + "' (expected exact or discrete)");
}

void check_resolution(double resolution) {
  if (!(resolution >= 0.0) || !std::isfinite(resolution))
    throw InputError("the motion-check resolution must be a finite number >= 0, got " +
                     std::to_string(resolution));
}

}  // namespace hpcplan::sampling
