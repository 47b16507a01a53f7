// libFuzzer target for the simulator's checkpoint (hpcplan sim --restart,
// io/sim_checkpoint.hpp): any byte string must either decode into the finished runs a restart
// keeps, or be refused with an InputError. Any other exception (a JSON or CBOR error that got
// through), a crash or a sanitizer report is a bug.
//
// Each input is tried twice: as a whole file (decode_sim_checkpoint: core's envelope first,
// whose checksum a mutation almost never passes) and as the CBOR payload behind the envelope
// (decode_sim_checkpoint_payload: the same decoder after the envelope's checks), so that
// mutations reach the payload's checks. The corpus holds both: small files written by
// hpcplan sim --checkpoint, and their payloads.
//
// A decoded checkpoint is used as a restart uses it: encoded again (the restart's next
// checkpoint holds its runs), and that file must decode (an InputError there is a bug too) to
// records that encode to the same bytes.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <string_view>

#include "hpcplan/core/error.hpp"
#include "hpcplan/io/sim_checkpoint.hpp"

namespace {

void use(const hpcplan::io::SimCheckpoint& c) {
  const std::string file = hpcplan::io::encode_sim_checkpoint(c);
  try {
    if (hpcplan::io::encode_sim_checkpoint(hpcplan::io::decode_sim_checkpoint(file, "again")) !=
        file)
      std::abort();
  } catch (const hpcplan::InputError&) {
    std::abort();
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  const std::string name = "fuzz";
  try {
    use(hpcplan::io::decode_sim_checkpoint(bytes, name));
  } catch (const hpcplan::InputError&) {
  }
  try {
    use(hpcplan::io::decode_sim_checkpoint_payload(bytes, name));
  } catch (const hpcplan::InputError&) {
  }
  return 0;
}
