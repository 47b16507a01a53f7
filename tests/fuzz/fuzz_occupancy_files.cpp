// libFuzzer target for the occupancy files (env/occupancy_io.hpp): every input goes to all five
// parsers (.map, .3dmap, .npy, .scen, .3dscen), and each must either parse into something whose
// queries work or reject it with an InputError. Any other exception, a crash, a sanitizer report
// or an allocation past libFuzzer's limits is a bug. What parses is checked further: a .map's
// grid written as a .npy (npy_header) reads back as the same grid, in C and Fortran order.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <string_view>
#include <vector>

#include "hpcplan/core/error.hpp"
#include "hpcplan/env/occupancy_io.hpp"

namespace {

using hpcplan::InputError;
using hpcplan::OccupancyGrid;

// Every cell's bit against is_free, and the counts; a few cells outside answer false.
void query(const OccupancyGrid& g) {
  std::vector<int> c(static_cast<std::size_t>(g.dims()), 0);
  (void)g.checksum();
  if (g.cells() > (1u << 16)) return;
  std::uint64_t free = 0;
  for (std::uint64_t n = 0; n < g.cells(); ++n) {
    free += g.is_free(c);
    for (int a = 0; a < g.dims() && ++c[a] == g.size(a); ++a) c[a] = 0;
  }
  if (free != g.free_cells()) std::abort();
  c.assign(c.size(), -1);
  if (g.is_free(c)) std::abort();
}

// The grid as a .npy of bytes (1 = blocked) in NumPy's order (the grid's last axis first), C or
// Fortran order; it must read back as the same grid.
void round_trip(const OccupancyGrid& g, bool fortran) {
  if (g.cells() > (1u << 16)) return;
  const int d = g.dims();
  std::vector<std::int64_t> shape(static_cast<std::size_t>(d));
  for (int a = 0; a < d; ++a) shape[static_cast<std::size_t>(d - 1 - a)] = g.size(a);
  std::string bytes = hpcplan::env::npy_header("|b1", shape);
  if (fortran) {
    const std::string key = "'fortran_order': False";
    bytes.replace(bytes.find(key), key.size(), "'fortran_order': True ");
  }
  const std::size_t at = bytes.size();
  bytes.resize(at + g.cells());
  std::vector<int> c(static_cast<std::size_t>(d), 0);
  for (std::uint64_t n = 0; n < g.cells(); ++n) {
    // C order: the grid's axis 0 (the array's last) fastest; Fortran: the grid's last axis.
    std::uint64_t offset = 0, stride = 1;
    for (int k = 0; k < d; ++k) {
      const int axis = fortran ? d - 1 - k : k;
      offset += static_cast<std::uint64_t>(c[static_cast<std::size_t>(axis)]) * stride;
      stride *= static_cast<std::uint64_t>(g.size(axis));
    }
    bytes[at + offset] = g.is_free(c) ? 0 : 1;
    for (int a = 0; a < d && ++c[static_cast<std::size_t>(a)] == g.size(a); ++a)
      c[static_cast<std::size_t>(a)] = 0;
  }
  const OccupancyGrid back = hpcplan::env::parse_npy(bytes, "round-trip");
  if (back.shape() != g.shape() || back.checksum() != g.checksum()) std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  using namespace hpcplan::env;
  for (const Terrain terrain : {Terrain::ground, Terrain::water}) {
    try {
      const OccupancyGrid g = parse_movingai_map(text, "fuzz.map", terrain);
      query(g);
      round_trip(g, false);
      round_trip(g, true);
      (void)movingai_cell(text, 0, 0);
      (void)movingai_cell(text, g.size(0) - 1, g.size(1) - 1);
    } catch (const InputError&) {
    }
  }
  (void)movingai_cell(text, 1, 1);
  try {
    // A lower voxel limit than the default, 512 KiB: every input stays cheap (a 2 GiB grid is
    // allowed in use, not in a fuzzing loop with -malloc_limit_mb=512).
    query(parse_voxel_map(text, "fuzz.3dmap", std::uint64_t{1} << 19));
  } catch (const InputError&) {
  }
  try {
    const OccupancyGrid g = parse_npy(text, "fuzz.npy");
    query(g);
    round_trip(g, false);
  } catch (const InputError&) {
  }
  for (const bool voxel : {false, true}) {
    try {
      const Scenario s = parse_scenario(text, voxel ? "fuzz.3dscen" : "fuzz.scen", voxel);
      for (const ScenarioRow& r : s.rows)
        if (r.start.size() != (voxel ? 3u : 2u) || r.goal.size() != r.start.size() ||
            !(r.optimal >= 0))
          std::abort();
    } catch (const InputError&) {
    }
  }
  return 0;
}
