#include "hpcplan/env/benchmark_spaces.hpp"

#include "hpcplan/core/error.hpp"
#include "hpcplan/env/hypercube.hpp"
#include "hpcplan/env/kinematic_chain.hpp"

namespace hpcplan {

const std::vector<std::string>& benchmark_space_names() {
  static const std::vector<std::string> names = {"chain", "hypercube"};
  return names;
}

bool is_benchmark_space(std::string_view name) {
  for (const auto& n : benchmark_space_names())
    if (n == name) return true;
  return false;
}

BenchmarkSpace make_benchmark_space(std::string_view name, int dims, double fraction) {
  if (!is_benchmark_space(name))
    throw InputError("unknown configuration space '" + std::string(name) +
                     "' (expected chain or hypercube)");
  if (dims < kBenchmarkMinDims || dims > kBenchmarkMaxDims)
    throw InputError("--dims for " + std::string(name) + " must be in " +
                     std::to_string(kBenchmarkMinDims) + ".." + std::to_string(kBenchmarkMaxDims) +
                     ", got " + std::to_string(dims));
  if (fraction < 0.0 || fraction > 1.0)
    throw InputError("--resolution must be a fraction of the space's extent in (0, 1], got " +
                     std::to_string(fraction));
  BenchmarkSpace b;
  if (name == "chain") {
    auto chain = std::make_shared<KinematicChain>(dims, fraction > 0.0 ? fraction : 0.01);
    b.start = chain->start();
    b.goal = chain->goal();
    // Up to 6 links, joint steps of pi/(2n): the start's angles pi/n are vertices. Beyond, the
    // (4n)^n lattice outgrows A* (8 links at 32 cells did not finish in 10 s on the 2-core VM),
    // and coarser ones still thread the horn: 16 cells to 8 links (0.38 s at 8), 12 beyond
    // (16 links in 110 s; 16 cells there leave the start joined to no vertex). docs/CSPACE.md.
    b.cells = dims <= 6 ? 4 * dims : dims <= 8 ? 16 : 12;
    b.space = std::move(chain);
  } else {
    auto cube = std::make_shared<Hypercube>(dims, 0.1, fraction > 0.0 ? fraction : 0.001);
    b.start = cube->start();
    b.goal = cube->goal();
    // Vertices at i/10: 0 and 0.1 inside the edges' 0.1-wide slabs, the corners included.
    b.cells = 11;
    b.space = std::move(cube);
  }
  return b;
}

}  // namespace hpcplan
