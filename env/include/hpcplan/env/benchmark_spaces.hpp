#pragma once
// The configuration spaces of OMPL's dimension-scalable benchmarks by name, with their queries:
// "chain" (KinematicChainBenchmark: n links in the horn, env/kinematic_chain.hpp) and
// "hypercube" (HypercubeBenchmark: the narrow passage along the cube's edges,
// env/hypercube.hpp). The front ends (hpcplan grid/ompl --world, Python's world=) build them here.
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "hpcplan/env/config_space.hpp"

namespace hpcplan {

struct BenchmarkSpace {
  std::shared_ptr<const ConfigSpace> space;
  std::vector<double> start, goal;  // the benchmark's own query
  int cells = 0;                    // the lattice's default cells per axis for it
};

inline constexpr int kBenchmarkMinDims = 2;
inline constexpr int kBenchmarkMaxDims = 16;

// InputError for an unknown name or dims outside 2..16. resolution_fraction > 0 replaces the
// benchmark's motion-check resolution (a fraction of the space's maximum extent, as OMPL's
// setStateValidityCheckingResolution): the chain's 0.01 (OMPL's default), the hypercube's 0.001.
BenchmarkSpace make_benchmark_space(std::string_view name, int dims,
                                    double resolution_fraction = 0.0);
bool is_benchmark_space(std::string_view name);
const std::vector<std::string>& benchmark_space_names();

}  // namespace hpcplan
