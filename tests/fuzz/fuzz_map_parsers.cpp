// libFuzzer target for the world file parsers (box maps and sphere worlds): any byte string
// must either parse into a world whose queries work, or be rejected with an InputError. Any
// other exception, a crash or a sanitizer report is a bug.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "hpcplan/core/error.hpp"
#include "hpcplan/env/box_map_io.hpp"
#include "hpcplan/env/sphere_world.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    const auto m = hpcplan::env::parse_box_map(text, "fuzz");
    const auto& b = m.world.bounds();
    (void)m.world.segment_free(b.lo, b.hi);
    (void)m.world.point_free(b.hi);
  } catch (const hpcplan::InputError&) {
  }
  try {
    const auto m = hpcplan::env::parse_sphere_map(text, "fuzz");
    const auto b = m.world.bounds();
    (void)m.world.segment_free(b.lo, b.hi);
  } catch (const hpcplan::InputError&) {
  }
  return 0;
}
