#pragma once
// The seed preset's agitation (FluidParams::agitate_every), on the host and the GPU: the
// fresh velocity of one fluid particle, drawn from SplitMix64 seeded by (run seed, frame,
// particle id), so that neither the thread count nor the particle order changes it.
#include <cstdint>

#include "hpcplan/core/portable.hpp"
#include "hpcplan/core/splitmix64.hpp"
#include "hpcplan/sph/physics/params.hpp"

namespace hpcplan::sph {

HPCPLAN_HD inline void agitation_velocity(const FluidParams& f, std::uint64_t seed,
                                          std::uint64_t frame, std::uint32_t id, double v[3]) {
  SplitMix64 rng(splitmix64_mix(seed ^ splitmix64_mix(frame ^ (std::uint64_t{id} << 32))));
  const double lo[3] = {-f.kick_horizontal, -f.kick_horizontal, 0.0};
  const double hi[3] = {f.kick_horizontal, f.kick_horizontal, f.kick_up};
  for (int k = 0; k < 3; ++k)
    v[k] = lo[k] + (hi[k] - lo[k]) * static_cast<double>(rng.next() >> 11) * 0x1.0p-53;
}

}  // namespace hpcplan::sph
