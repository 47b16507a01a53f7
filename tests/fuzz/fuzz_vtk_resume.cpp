// libFuzzer target for what a restarted fluid run reads of its VTK directory
// (VtkSeries::resume, io/vtk_fluid.hpp): the names of the files there, each read by
// series_frame. Any name must either be the name frame F's fluid file is written under
// (fluid_ and F padded to six digits, .vtu), giving F, or be passed over; anything else (an
// exception, a crash, a sanitizer report, a frame read from another name, so that the series
// would list a file twice or one that is not there) is a bug.
//
// The input is a directory listing: names separated by '/' (which no file name holds).
//
// The sweeps' own resume files are read by bash and Python, not C++ (docs/PERFORMANCE.md,
// issue 34): bench/sim_sweep.sh skips a cell whose CSV exists, and slurm/common.sh's
// hpcplan_already_done reads earlier jobs' meta.json and CSV labels.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <string>
#include <string_view>

#include "hpcplan/io/vtk_fluid.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view listing(reinterpret_cast<const char*>(data), size);
  for (std::size_t at = 0; at <= listing.size();) {
    const std::size_t slash = std::min(listing.find('/', at), listing.size());
    const std::string_view name = listing.substr(at, slash - at);
    at = slash + 1;
    const std::optional<std::uint64_t> frame = hpcplan::io::series_frame(name);
    if (!frame) continue;
    char expected[64];
    std::snprintf(expected, sizeof expected, "fluid_%06llu.vtu",
                  static_cast<unsigned long long>(*frame));
    if (name != expected) std::abort();
  }
  return 0;
}
