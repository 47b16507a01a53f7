// libFuzzer target for the fluid's checkpoint (hpcplan sph --restart, sph/checkpoint.hpp): any
// byte string must either decode into a checkpoint a restart can continue, or be refused with
// an InputError. Any other exception, a crash, a sanitizer report, or a decode that allocates
// or runs out of proportion to its input (libFuzzer's -rss_limit_mb and -timeout) is a bug.
//
// Each input is tried twice: as a whole file (decode_checkpoint: core's envelope first, whose
// checksum a mutation almost never passes) and as the payload behind the envelope
// (decode_checkpoint_payload: the same decoder after the envelope's checks), so that mutations
// reach the payload's checks. The corpus holds both: small files written by hpcplan sph
// --checkpoint, and their payloads.
//
// A decoded checkpoint is used as a restart uses it: its particle counts are those its
// problem builds, and the neighbour grid is rebuilt over its particles and the frame check run
// (what the restarted run's first substep and frame end do first).
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <string_view>

#include "hpcplan/core/error.hpp"
#include "hpcplan/sph/checkpoint.hpp"
#include "hpcplan/sph/fluid.hpp"

namespace {

void use(hpcplan::sph::FluidCheckpoint& c) {
  hpcplan::sph::FluidState& s = c.state;
  if (s.particles.size() < s.fluid_count || s.particles.id.size() != s.particles.size())
    std::abort();
  s.grid.build(s.particles);
  (void)hpcplan::sph::first_problem(s);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  const std::string name = "fuzz";
  try {
    hpcplan::sph::FluidCheckpoint c = hpcplan::sph::decode_checkpoint(bytes, name);
    use(c);
  } catch (const hpcplan::InputError&) {
  }
  try {
    hpcplan::sph::FluidCheckpoint c = hpcplan::sph::decode_checkpoint_payload(bytes, name);
    use(c);
  } catch (const hpcplan::InputError&) {
  }
  return 0;
}
