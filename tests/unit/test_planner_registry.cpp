// The planner registry against what actually runs: every registered planner of every setting
// can be run by its name (and returns a valid path on an easy map), every declared parameter
// exists with a sane range, and nothing runs that is not registered.
#include <gtest/gtest.h>

#include <set>
#include <string>

#include "hpcplan/core/error.hpp"
#include "hpcplan/env/box_map_io.hpp"
#include "hpcplan/env/sphere_world.hpp"
#include "hpcplan/plan/grid_problem.hpp"
#include "hpcplan/plan/ompl_benchmark.hpp"
#include "hpcplan/plan/planner_registry.hpp"
#include "hpcplan/plan/world_planner.hpp"
#include "support/path_checks.hpp"

namespace hpcplan {
namespace {

using plan::PlannerRegistry;

TEST(PlannerRegistry, NamesAreUniquePerSettingAndParametersAreDeclared) {
  const auto& r = PlannerRegistry::get();
  int total = 0;
  for (const char* world : {"grid", "map3d", "sphere2d", "ompl"}) {
    const auto names = r.names(world);
    EXPECT_EQ(std::set<std::string>(names.begin(), names.end()).size(), names.size()) << world;
    EXPECT_GE(names.size(), 4u) << world;
    total += static_cast<int>(names.size());
  }
  EXPECT_GE(total, 40);
  for (const auto& p : r.params()) {
    EXPECT_FALSE(p.help.empty()) << p.name;
    EXPECT_EQ(p.option().substr(0, 2), "--");
    if (p.type == plan::ParamType::real || p.type == plan::ParamType::integer) {
      EXPECT_LE(p.lo, p.hi) << p.name;
    }
  }
  EXPECT_THROW(r.param("no_such_parameter"), std::logic_error);
  EXPECT_THROW(r.require("map3d", "bfs"), InputError);  // bfs is a lattice planner only
}

TEST(PlannerRegistry, EveryGridPlannerParsesToItsAlgorithm) {
  std::set<GridAlgorithm> seen;
  for (const auto& name : PlannerRegistry::get().names("grid")) {
    const GridAlgorithm a = parse_grid_algorithm(name);
    EXPECT_EQ(to_string(a), name);
    seen.insert(a);
  }
  EXPECT_EQ(seen.size(), 4u);
  EXPECT_THROW(parse_grid_algorithm("dfs"), InputError);
}

TEST(PlannerRegistry, TheOmplHarnessAcceptsExactlyItsRegisteredPlanners) {
  EXPECT_EQ(plan::known_planners(), PlannerRegistry::get().names("ompl"));
  for (const auto& name : plan::known_planners()) {
    plan::OmplBenchOptions o;
    o.planners = {name};
    EXPECT_NO_THROW(plan::validate(o)) << name;
  }
}

// Every registered world planner, by name, on an easy map of each world: solved, with a path
// that passes the exact re-check (plan_in_world throws otherwise).
TEST(PlannerRegistry, EveryWorldPlannerRunsByItsName) {
  const auto box = env::load_box_map(std::string(HPCPLAN_MAPS_DIR) + "/single_box.txt");
  const auto disc = env::load_sphere_map(std::string(HPCPLAN_MAPS_DIR) + "/sphere_world.txt");
  int ran = 0;
  const auto run_all = [&](const char* setting, const auto& map) {
    for (const auto& name : PlannerRegistry::get().names(setting)) {
      SCOPED_TRACE(name);
      plan::WorldPlanOptions o;
      o.algo = name;
      o.resolution = 0.25;
      // Every planner ends at its first path (anytime ones too): the time is only a guard, so
      // the outcome does not depend on the machine's speed (or a sanitizer's).
      o.stop_at_first = true;
      o.time_s = 60.0;
      const auto p = plan::plan_in_world(map.world, *map.start, *map.goal, o);
      EXPECT_EQ(p.status, Status::solved);
      if (p.status == Status::solved)
        test_support::expect_valid(map.world, p.path, *map.start, *map.goal, name);
      ++ran;
    }
  };
  run_all("map3d", box);
  run_all("sphere2d", disc);
  EXPECT_GE(ran, 40);
  plan::WorldPlanOptions o;
  o.algo = "dfs";
  EXPECT_THROW(plan::plan_in_world(box.world, *box.start, *box.goal, o), InputError);
}

}  // namespace
}  // namespace hpcplan
