#pragma once
// Every planner hpcplan runs, in one registry: its name, the settings (subcommands) that run it,
// what family it belongs to, and its declared parameters (type, range, default, help), as
// OMPL's declareParam does. The CLI builds its options and errors from it, `hpcplan planners`
// lists it, and the sweep drivers and the OMPL harness check names against it. A planner is
// added in one place: the table of its setting (grid_problem.cpp for the GOG lattice,
// world_planner.cpp for box maps and sphere worlds, ompl_benchmark.cpp for the OMPL harness;
// OMPL's own planners come from sampling/ompl_planners.cpp), which carries both its entry here
// and how to run it.
//
// Threads: built once on first use, immutable afterwards; safe to read from any thread.
#include <string>
#include <string_view>
#include <vector>

namespace hpcplan::plan {

enum class ParamType { real, integer, flag, choice };

struct ParamSpec {
  std::string name;  // the option is --<name with _ as ->
  ParamType type = ParamType::real;
  double lo = 0, hi = 0;             // real and integer: the accepted range
  std::vector<std::string> choices;  // choice
  std::string default_text;
  std::string help;
  std::string option() const;  // "--max-states"
};

struct PlannerSpec {
  std::string name;
  std::string family;               // grid search, any-angle, visibility graph, tree, hybrid, ompl
  std::vector<std::string> worlds;  // settings: grid, map3d, sphere2d, ompl, sim
  std::vector<std::string> params;  // names in the parameter table
  std::string help;
};

class PlannerRegistry {
 public:
  static const PlannerRegistry& get();

  const std::vector<PlannerSpec>& planners() const { return planners_; }
  const std::vector<ParamSpec>& params() const { return params_; }
  const ParamSpec& param(std::string_view name) const;  // std::logic_error if undeclared
  const PlannerSpec* find(std::string_view world, std::string_view name) const;
  std::vector<std::string> names(std::string_view world) const;
  // The spec, or an InputError naming the known planners of that setting.
  const PlannerSpec& require(std::string_view world, std::string_view name) const;

 private:
  PlannerRegistry();
  std::vector<PlannerSpec> planners_;
  std::vector<ParamSpec> params_;
};

// Each setting's table contributes its entries (defined beside the code that runs them).
std::vector<PlannerSpec> grid_planner_specs();
std::vector<PlannerSpec> world_planner_specs();
std::vector<PlannerSpec> ompl_harness_specs();
std::vector<PlannerSpec> fluid_planner_specs();  // fluid_planner.cpp (hpcplan sim)

}  // namespace hpcplan::plan
