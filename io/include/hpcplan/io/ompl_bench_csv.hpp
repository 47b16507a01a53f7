#pragma once
// The OMPL comparison's runs as CSV, one row per planner run with seed 002's metrics (empty
// cells where a metric does not apply: no "best" for planners that never improved, no lengths
// for unsolved runs) and the improvement trace as time:length pairs.
#include <string>

#include "hpcplan/plan/ompl_benchmark.hpp"

namespace hpcplan::io {

std::string ompl_bench_csv(const plan::OmplBenchResult& result);

}  // namespace hpcplan::io
