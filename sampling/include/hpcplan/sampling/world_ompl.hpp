#pragma once
// The continuous worlds (box maps, sphere world) as an OMPL problem: a bounded real vector
// space, a point validity checker and a motion validator that is the world's exact segment
// test, so OMPL's planners are judged on the same collision rules as hpcplan's.
#include <stop_token>
#include <string>
#include <vector>

#include "hpcplan/tree/tree_common.hpp"

namespace hpcplan::sampling {

// Runs OMPL planner `name` for up to time_s seconds (anytime planners use all of it, unless
// `stop_at_first`: then the objective is satisfied by any path and they end at their first).
// Only an exact solution counts: the path is completed to the exact goal when OMPL stops within
// its goal threshold and that last segment is free. `cancel` ends it early (OMPL's termination
// condition polls it).
template <class W>
tree::TreeResult<W::kDim> solve_with_ompl(const W& world, const env::Vec<W::kDim>& start,
                                          const env::Vec<W::kDim>& goal, const std::string& name,
                                          double time_s, std::uint64_t seed,
                                          std::stop_token cancel = {}, bool stop_at_first = false);

}  // namespace hpcplan::sampling
