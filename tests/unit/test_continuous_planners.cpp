// The grid searches, Lazy Theta* and the tree planners in continuous worlds, each checked
// against an independent oracle: Dijkstra's cost, the weighted-A* bound, the exact segment
// test on every returned segment, dense sampling against thin walls.
#include <gtest/gtest.h>

#include <string>

#include "hpcplan/env/box_map_io.hpp"
#include "hpcplan/env/path_shortcut.hpp"
#include "hpcplan/env/sphere_world.hpp"
#include "hpcplan/graph/continuous_grid.hpp"
#include "hpcplan/search/best_first.hpp"
#include "hpcplan/search/dense_visited_map.hpp"
#include "hpcplan/search/lazy_theta_star.hpp"
#include "hpcplan/tree/rrt.hpp"
#include "hpcplan/tree/rrt_connect.hpp"
#include "hpcplan/tree/rrt_star.hpp"
#include "support/path_checks.hpp"

namespace hpcplan {
namespace {

using env::BoxMap;
using env::BoxWorld;
using env::Vec;
using test_support::expect_valid;
using Grid3 = ContinuousGrid<BoxWorld>;

const char* kMaps[] = {"single_box", "maze", "thin_walls", "tower", "window", "forest"};

BoxMap shipped(const std::string& name) {
  return env::load_box_map(std::string(HPCPLAN_MAPS_DIR) + "/" + name + ".txt");
}

struct GridRun {
  search::Result<Grid3::State> result;
  std::vector<Vec<3>> path;
};

template <class H>
GridRun grid_search(const Grid3& g, const H& h, search::Options o, bool theta = false) {
  o.dense_keys = g.vertex_count();
  GridRun r;
  r.result = theta ? search::lazy_theta_star<search::DenseThenHashPolicy>(g, Grid3::kStart,
                                                                          Grid3::kGoal, h, o)
                   : search::best_first_search<search::DenseThenHashPolicy>(g, Grid3::kStart,
                                                                            Grid3::kGoal, h, o);
  for (auto s : r.result.path) r.path.push_back(g.point(s));
  return r;
}

TEST(ContinuousGrid, AStarCostEqualsDijkstraAndWeightedStaysInBound) {
  for (const char* name : kMaps) {
    const BoxMap m = shipped(name);
    for (double res : {0.5, 0.3}) {
      const Grid3 g(m.world, *m.start, *m.goal, {res});
      const auto dijkstra = grid_search(g, search::ZeroHeuristic{}, {});
      const auto astar = grid_search(g, LatticeToGoal<Grid3>{&g}, {});
      const auto euclid = grid_search(g, EuclideanToGoal<Grid3>{&g}, {});
      ASSERT_EQ(dijkstra.result.status, search::Status::solved) << name << " " << res;
      EXPECT_NEAR(astar.result.cost, dijkstra.result.cost, 1e-9 * dijkstra.result.cost) << name;
      EXPECT_NEAR(euclid.result.cost, dijkstra.result.cost, 1e-9 * dijkstra.result.cost) << name;
      expect_valid(m.world, astar.path, *m.start, *m.goal, name);
      for (double w : {1.5, 3.0}) {
        search::Options o;
        o.weight = w;
        o.reopen_closed = false;
        const auto wa = grid_search(g, LatticeToGoal<Grid3>{&g}, o);
        ASSERT_EQ(wa.result.status, search::Status::solved);
        EXPECT_LE(wa.result.cost, w * dijkstra.result.cost + 1e-9) << name << " w=" << w;
        expect_valid(m.world, wa.path, *m.start, *m.goal, name);
      }
      const auto theta = grid_search(g, EuclideanToGoal<Grid3>{&g}, {}, true);
      ASSERT_EQ(theta.result.status, search::Status::solved) << name;
      EXPECT_LE(theta.result.cost, astar.result.cost + 1e-9) << name;  // any-angle is shorter
      expect_valid(m.world, theta.path, *m.start, *m.goal, std::string(name) + " theta");
    }
  }
}

TEST(ContinuousGrid, ThinWallIsNeverCrossedAtAnyResolution) {
  // A 1 cm wall splits the world completely: every resolution must report no path.
  const BoxWorld sealed({{0, 0, 0}, {10, 10, 10}}, {env::Block{{{4.995, 0, 0}, {5.005, 10, 10}}}});
  for (double res : {0.1, 0.3, 0.5, 0.7, 1.0, 2.5, 3.3}) {
    const Grid3 g(sealed, {1, 5, 5}, {9, 5, 5}, {res});
    EXPECT_EQ(grid_search(g, LatticeToGoal<Grid3>{&g}, {}).result.status, search::Status::no_path)
        << res;
    EXPECT_EQ(grid_search(g, EuclideanToGoal<Grid3>{&g}, {}, true).result.status,
              search::Status::no_path)
        << res;
  }
  // The shipped corridor of 2 cm walls: coarse grids may fail to fit the doors, but whatever
  // they return goes through the doors.
  const BoxMap m = shipped("thin_walls");
  int solved = 0;
  for (double res : {0.1, 0.25, 0.5, 0.75, 1.0}) {
    const Grid3 g(m.world, *m.start, *m.goal, {res});
    const auto r = grid_search(g, LatticeToGoal<Grid3>{&g}, {});
    if (r.result.status == search::Status::solved) {
      ++solved;
      expect_valid(m.world, r.path, *m.start, *m.goal, "thin");
    } else {
      EXPECT_EQ(r.result.status, search::Status::no_path) << res;
    }
  }
  EXPECT_GE(solved, 1);  // the fine grid fits the doors
}

TEST(ContinuousGrid, MemoryBudgetStopsTheSearch) {
  const BoxMap m = shipped("maze");
  const Grid3 g(m.world, *m.start, *m.goal, {0.1});
  search::Options o;
  o.max_states = 1000;
  EXPECT_EQ(grid_search(g, LatticeToGoal<Grid3>{&g}, o).result.status,
            search::Status::budget_exceeded);
}

TEST(TreePlanners, SolveEveryShippedMapWithValidPaths) {
  for (const char* name : kMaps) {
    const BoxMap m = shipped(name);
    for (std::uint64_t seed : {1, 2}) {
      tree::TreeOptions o;
      o.seed = seed;
      o.stop = Stop::after(60.0);  // a guard against a hang only: RRT and RRT-Connect end at a path
      const auto a = tree::rrt(m.world, *m.start, *m.goal, o);
      ASSERT_EQ(a.status, search::Status::solved) << name;
      expect_valid(m.world, a.path, *m.start, *m.goal, std::string(name) + " rrt");
      const auto b = tree::rrt_connect(m.world, *m.start, *m.goal, o);
      ASSERT_EQ(b.status, search::Status::solved) << name;
      expect_valid(m.world, b.path, *m.start, *m.goal, std::string(name) + " birrt");
      // RRT* by a sample budget, not the clock: the outcome must not depend on load or on the
      // sanitizers' slowdown.
      o.max_samples = 20000;
      const auto c = tree::rrt_star(m.world, *m.start, *m.goal, o);
      ASSERT_EQ(c.status, search::Status::solved) << name << " seed " << seed;
      expect_valid(m.world, c.path, *m.start, *m.goal, std::string(name) + " rrtstar");
      EXPECT_NEAR(c.cost, env::polyline_length<3>(c.path), 1e-9);
      EXPECT_EQ(c.hops + 1, c.path.size());  // the one Result's fields agree
      EXPECT_GT(c.counters.peak_states, 1u);
      EXPECT_EQ(c.counters.samples, 20000u);
      EXPECT_LE(c.cost, c.counters.first_cost + 1e-9);  // refinement never lengthens
      // Shortcutting keeps the ends and validity and never lengthens.
      const auto s = env::tighten_path(m.world, env::shortcut_path(m.world, a.path));
      expect_valid(m.world, s, *m.start, *m.goal, std::string(name) + " shortcut");
      EXPECT_LE(env::polyline_length<3>(s), a.cost + 1e-9);
    }
  }
}

TEST(TreePlanners, RrtStarApproachesTheAnyAngleOptimumOnOneBox) {
  const BoxMap m = shipped("single_box");
  // A sample budget, not a time budget: the outcome must not depend on the machine's load or
  // on the sanitizers' slowdown.
  tree::TreeOptions o;
  o.max_samples = 20000;
  const auto r = tree::rrt_star(m.world, *m.start, *m.goal, o);
  const Grid3 g(m.world, *m.start, *m.goal, {0.1});
  const auto theta = grid_search(g, EuclideanToGoal<Grid3>{&g}, {}, true);
  ASSERT_EQ(r.status, search::Status::solved);
  EXPECT_LT(r.cost, theta.result.cost * 1.05);
}

TEST(TreePlanners, UnreachableGoalEndsWithoutAPath) {
  const BoxWorld sealed({{0, 0, 0}, {10, 10, 10}}, {env::Block{{{4.9, 0, 0}, {5.1, 10, 10}}}});
  tree::TreeOptions o;
  o.max_samples = 3000;
  EXPECT_NE(tree::rrt(sealed, {1, 5, 5}, {9, 5, 5}, o).status, search::Status::solved);
  EXPECT_NE(tree::rrt_connect(sealed, {1, 5, 5}, {9, 5, 5}, o).status, search::Status::solved);
  EXPECT_NE(tree::rrt_star(sealed, {1, 5, 5}, {9, 5, 5}, o).status, search::Status::solved);
  EXPECT_THROW(tree::rrt(sealed, {5, 5, 5}, {9, 5, 5}, o), InputError);  // start in the wall
}

TEST(SphereWorld, GridAStarEqualsDijkstraAndTheHybridReturnsValidPaths) {
  const auto m = env::load_sphere_map(std::string(HPCPLAN_MAPS_DIR) + "/sphere_dense.txt");
  using Grid2 = ContinuousGrid<env::SphereWorld>;
  const Grid2 g(m.world, *m.start, *m.goal, {0.25});
  const auto d =
      search::best_first_search(g, Grid2::kStart, Grid2::kGoal, search::ZeroHeuristic{}, {});
  const auto a =
      search::best_first_search(g, Grid2::kStart, Grid2::kGoal, LatticeToGoal<Grid2>{&g}, {});
  ASSERT_EQ(a.status, search::Status::solved);
  EXPECT_NEAR(a.cost, d.cost, 1e-9 * d.cost);
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    for (int variant = 0; variant < 3; ++variant) {
      Grid2::Config c{0.25};
      c.seed = seed;
      c.samples_per_expansion = variant == 1 ? 0 : 10;
      const Grid2 hg(m.world, *m.start, *m.goal, c);
      search::Options o;
      o.seed = seed;
      o.reopen_closed = false;  // as the planner runs it: sampled successors are not regenerated
      if (variant != 2) o.frontier = search::Frontier::random;
      const auto h = search::best_first_search(hg, Grid2::kStart, Grid2::kGoal,
                                               EuclideanToGoal<Grid2>{&hg}, o);
      ASSERT_EQ(h.status, search::Status::solved) << seed << " " << variant;
      std::vector<Vec<2>> path;
      for (auto s : h.path) path.push_back(hg.point(s));
      expect_valid(m.world, path, *m.start, *m.goal, "hybrid");
      if (variant == 2) {
        EXPECT_LE(h.cost, a.cost * 1.05);  // A* order keeps it near optimal
      }
    }
  }
}

}  // namespace
}  // namespace hpcplan
