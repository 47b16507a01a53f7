#pragma once
// The one table of OMPL's geometric planners that hpcplan offers, by the names users type: the
// continuous worlds' "ompl:<name>" and the GOG harness (hpcplan ompl) both make their planners
// here. Every planner comes without OMPL Benchmark's progress properties: Benchmark samples
// them from a second thread while the planner runs, and several planners read unsynchronised
// data structures there (BIT*'s GNAT, FMT*'s neighbourhoods), which crashed 20 s runs at 4D.
//
// Threads: the table is immutable; a made planner belongs to one run.
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include <ompl/base/Planner.h>

namespace hpcplan::sampling {

struct OmplPlannerKind {
  std::string name;       // what users type: bitstar, fmt, rrtconnect, ...
  std::string ompl_name;  // the name in OMPL's benchmark log (unique)
  std::string help;
  bool asymptotically_optimal = false;
  std::function<ompl::base::PlannerPtr(const ompl::base::SpaceInformationPtr&)> make;
};

const std::vector<OmplPlannerKind>& ompl_planners();
const OmplPlannerKind* find_ompl_planner(std::string_view name);  // null if unknown

}  // namespace hpcplan::sampling
