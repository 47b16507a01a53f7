// Bend points, the visibility graph and path tightening, each against an independent oracle:
// shortest paths known in closed form (around a full-height wall by unfolding, around a disc
// by tangents and an arc), an unfiltered Dijkstra on the same graph, and the exact re-check.
#include <gtest/gtest.h>

#include <cmath>
#include <iomanip>
#include <numbers>
#include <string>

#include "hpcplan/core/error.hpp"
#include "hpcplan/env/bend_points.hpp"
#include "hpcplan/env/box_map_io.hpp"
#include "hpcplan/env/path_shortcut.hpp"
#include "hpcplan/env/sphere_world.hpp"
#include "hpcplan/graph/continuous_grid.hpp"
#include "hpcplan/graph/visibility_graph.hpp"
#include "hpcplan/search/best_first.hpp"
#include "hpcplan/search/dense_visited_map.hpp"
#include "hpcplan/search/lazy_theta_star.hpp"
#include "support/path_checks.hpp"

namespace hpcplan {
namespace {

using env::BoxWorld;
using env::Vec;
using test_support::expect_valid;
using VisBox = VisibilityGraph<BoxWorld>;

env::BoxMap shipped(const std::string& name) {
  return env::load_box_map(std::string(HPCPLAN_MAPS_DIR) + "/" + name + ".txt");
}

// The same graph with only the two-argument successor walk: the engine cannot filter edges
// before their collision test, so every visible, tangent edge is offered.
template <class G>
struct Unfiltered {
  using State = typename G::State;
  using Move = typename G::Move;
  using Cost = typename G::Cost;
  using Hash = typename G::Hash;
  static constexpr Move kNoMove = G::kNoMove;
  const G& g;
  State predecessor(State s, Move m) const { return g.predecessor(s, m); }
  double checked_edge_length(State a, State b) const { return g.checked_edge_length(a, b); }
  std::uint64_t collision_checks() const { return g.collision_checks(); }
  template <class Emit>
  void for_each_successor(State s, Emit&& emit) const {
    g.for_each_successor(s, emit);
  }
};

template <class G>
std::vector<Vec<G::D>> points(const G& g, const std::vector<typename G::State>& states) {
  std::vector<Vec<G::D>> out;
  for (auto s : states) out.push_back(g.point(s));
  return out;
}

// A* with the straight-line heuristic on a visibility graph, as the planner runs it.
template <class G>
search::Result<typename G::State> shortest(const G& g) {
  search::Options o;
  o.dense_keys = g.vertex_count();
  return search::best_first_search<search::DenseThenHashPolicy>(g, G::kStart, G::kGoal,
                                                                EuclideanToGoal<G>{&g}, o);
}

TEST(BendPoints, CornersAndEdgeSamplesLiftedOffOneBox) {
  const BoxWorld w({{0, 0, 0}, {10, 10, 10}}, {env::Block{{{4, 4, 4}, {6, 6, 6}}}});
  const double lift = 1e-6;
  const auto bends = env::bend_points(w, 0.5, lift);
  ASSERT_EQ(bends.size(), 8u + 12u * 3u);  // corners, and 3 inner samples on each 2 m edge
  int corners = 0;
  for (const auto& b : bends) {
    EXPECT_TRUE(w.point_free(b.point));
    // Lifted by `lift` along each of its normals, so its distance to the box is lift*sqrt(n).
    double d2 = 0;
    for (int k = 0; k < 3; ++k) {
      const double out = std::max({4.0 - b.point[k], b.point[k] - 6.0, 0.0});
      d2 += out * out;
    }
    EXPECT_NEAR(std::sqrt(d2), lift * std::sqrt(double(b.normal_count)), 1e-12);
    corners += b.normal_count == 3;
  }
  EXPECT_EQ(corners, 8);
}

TEST(BendPoints, NoneInsideNeighboursOrOutsideTheBoundary) {
  // A low box A = [2,4]x[2,4]x[0,2] against a tall box B = [4,6]x[2,4]x[0,4], both on the
  // floor; spacing 1 puts one inner sample on each 2 m edge and three on B's 4 m ones.
  // Under the floor: every bottom corner and bottom-edge sample. Inside B: the sample of A's
  // top edge at x = 4, lifted towards +x and +z (that edge's corners are also lifted past
  // B's sides in y, so they stay). Left: A has 4 top corners, 3 top-edge and 4 vertical-edge
  // samples; B has 4 top corners, 4 top-edge and 4 x 3 vertical-edge samples.
  const BoxWorld w({{0, 0, 0}, {10, 10, 10}},
                   {env::Block{{{2, 2, 0}, {4, 4, 2}}}, env::Block{{{4, 2, 0}, {6, 4, 4}}}});
  const auto bends = env::bend_points(w, 1.0, 1e-6);
  EXPECT_EQ(bends.size(), 11u + 20u);
  for (const auto& b : bends) {
    EXPECT_TRUE(w.point_free(b.point));
    EXPECT_GT(b.point[2], 0.0);
  }
}

TEST(BendPoints, TangencyRejectsDirectionsIntoOrStraightOutOfTheObstacle) {
  env::BendPoint<3> edge;  // an edge along z, the obstacle towards -x and -y
  edge.normals[0] = {1, 0, 0};
  edge.normals[1] = {0, 1, 0};
  edge.normal_count = 2;
  EXPECT_FALSE(edge.tangent({-1, -1, 0}));    // into the block
  EXPECT_FALSE(edge.tangent({1, 1, 0.5}));    // straight out: the line behind enters it
  EXPECT_TRUE(edge.tangent({1, -1, 0}));      // wraps the edge
  EXPECT_TRUE(edge.tangent({0, 0, 1}));       // along the edge
  EXPECT_TRUE(edge.tangent({1, 0, 0}));       // along a face
  EXPECT_TRUE(edge.tangent({-1, 1e-12, 0}));  // along a face, rounded
  EXPECT_TRUE(edge.tangent({0, 0, 0}));
}

TEST(VisibilityGraph, FilteredAStarEqualsUnfilteredDijkstraOnShippedMaps) {
  for (const char* name : {"single_box", "maze", "thin_walls", "tower", "window"}) {
    const auto m = shipped(name);
    const VisBox g(m.world, *m.start, *m.goal, env::bend_points(m.world, 0.5, 1e-5));
    const auto astar = shortest(g);
    const Unfiltered<VisBox> plain{g};
    const auto dijkstra = search::best_first_search(plain, VisBox::kStart, VisBox::kGoal,
                                                    search::ZeroHeuristic{}, {});
    ASSERT_EQ(astar.status, search::Status::solved) << name;
    ASSERT_EQ(dijkstra.status, search::Status::solved) << name;
    EXPECT_NEAR(astar.cost, dijkstra.cost, 1e-9 * dijkstra.cost) << name;
    EXPECT_LT(astar.counters.collision_checks, dijkstra.counters.collision_checks) << name;
    expect_valid(m.world, points(g, astar.path), *m.start, *m.goal, name);
  }
}

// Around a full-height wall the shortest path is the shortest 2D path around the wall's
// footprint, lifted: length sqrt(s^2 + dz^2), where s is the 2D length (unfold the vertical
// faces it follows into a plane).
struct WallCase {
  BoxWorld world{{{0, 0, 0}, {10, 10, 10}}, {env::Block{{{4, 0, 0}, {6, 6, 10}}}}};
  Vec<3> start{2, 2, 1}, goal{8, 2, 9};
  double optimum() const {
    const double s = 2 * std::hypot(2.0, 4.0) + 2.0;
    return std::hypot(s, 8.0);
  }
};

TEST(VisibilityGraph, TightenedPathMatchesTheUnfoldedOptimumAroundAWall) {
  const WallCase c;
  for (double spacing : {2.0, 0.7, 0.25}) {
    const VisBox g(c.world, c.start, c.goal, env::bend_points(c.world, spacing, 1e-6));
    const auto r = shortest(g);
    ASSERT_EQ(r.status, search::Status::solved) << spacing;
    const auto raw = points(g, r.path);
    expect_valid(c.world, raw, c.start, c.goal, "raw");
    // No free path is shorter than the optimum; sampled bends cost at most a little more.
    EXPECT_GE(r.cost, c.optimum() - 1e-9) << spacing;
    EXPECT_LE(r.cost, c.optimum() * 1.02) << spacing;
    const auto tight = env::tighten_path(c.world, raw);
    expect_valid(c.world, tight, c.start, c.goal, "tightened");
    const double length = env::polyline_length<3>(tight);
    EXPECT_GE(length, c.optimum() - 1e-9) << spacing;
    EXPECT_LE(length, c.optimum() * (1 + 1e-5)) << spacing;
  }
}

TEST(TightenPath, SlidesBendsAlongEdgesToTheOptimum) {
  // A valid but poor path: over the wall's corner edges at the wrong heights.
  const WallCase c;
  const std::vector<Vec<3>> path{c.start, {3.9, 6.3, 8.0}, {6.1, 6.3, 2.0}, c.goal};
  expect_valid(c.world, path, c.start, c.goal, "input");
  const auto tight = env::tighten_path(c.world, path);
  expect_valid(c.world, tight, c.start, c.goal, "tightened");
  // Bends far from their edges converge slowly at the end (coordinate-wise slides): within
  // 1e-4 of the optimum from an input 1.4% longer.
  EXPECT_GT(env::polyline_length<3>(path), c.optimum() * 1.01);
  EXPECT_LE(env::polyline_length<3>(tight), c.optimum() * (1 + 1e-4))
      << std::setprecision(12) << env::polyline_length<3>(tight) << " vs " << c.optimum();
  EXPECT_GE(env::polyline_length<3>(tight), c.optimum() - 1e-9);
}

TEST(VisibilityGraph, TightenedPathMatchesTangentsAndArcAroundADisc) {
  const env::SphereWorld w({{0, 0}, 10.0}, {env::Circle{{0, 0}, 2.0}});
  const Vec<2> start{-5, 0}, goal{5, 0};
  // Two tangents of length sqrt(5^2 - 2^2) and the arc between their touching points.
  const double optimum = 2 * std::sqrt(21.0) + 2.0 * (std::numbers::pi - 2 * std::acos(0.4));
  using VisDisc = VisibilityGraph<env::SphereWorld>;
  for (double spacing : {0.5, 0.1}) {
    const VisDisc g(w, start, goal, env::bend_points(w, spacing, 1e-6));
    const auto r = shortest(g);
    ASSERT_EQ(r.status, search::Status::solved);
    EXPECT_GE(r.cost, optimum - 1e-9);
    EXPECT_LE(r.cost, optimum * 1.01) << spacing;
    const auto tight = env::tighten_path(w, points(g, r.path));
    expect_valid(w, tight, start, goal, "disc");
    const double length = env::polyline_length<2>(tight);
    EXPECT_GE(length, optimum - 1e-9);
    EXPECT_LE(length, optimum * 1.002) << spacing;
  }
}

TEST(VisibilityGraph, SealedGoalHasNoPathAndBadSpacingIsRejected) {
  const BoxWorld sealed({{0, 0, 0}, {10, 10, 10}}, {env::Block{{{4.99, 0, 0}, {5.01, 10, 10}}}});
  const VisBox g(sealed, {1, 5, 5}, {9, 5, 5}, env::bend_points(sealed, 0.5, 1e-6));
  const auto r = shortest(g);
  EXPECT_EQ(r.status, search::Status::no_path);
  EXPECT_TRUE(r.path.empty());
  EXPECT_THROW(env::bend_points(sealed, -1.0, 1e-6), InputError);
  EXPECT_THROW(env::bend_points(sealed, std::nan(""), 1e-6), InputError);
  EXPECT_THROW(env::bend_points(sealed, 0.5, 0.0), InputError);
}

TEST(VisibilityGraph, NoLongerThanTightenedThetaStarOnShippedMaps) {
  // Not a theorem, a regression guard: the any-angle grid path is confined to the homotopy
  // its lattice picked, the visibility graph chooses among all of them.
  using Grid3 = ContinuousGrid<BoxWorld>;
  for (const char* name : {"single_box", "maze", "thin_walls", "tower", "window", "forest"}) {
    const auto m = shipped(name);
    const VisBox g(m.world, *m.start, *m.goal, env::bend_points(m.world, 0.5, 1e-5));
    const auto vis = shortest(g);
    const Grid3 grid(m.world, *m.start, *m.goal, {0.25});
    search::Options o;
    o.dense_keys = grid.vertex_count();
    const auto theta = search::lazy_theta_star<search::DenseThenHashPolicy>(
        grid, Grid3::kStart, Grid3::kGoal, EuclideanToGoal<Grid3>{&grid}, o);
    ASSERT_EQ(vis.status, search::Status::solved) << name;
    ASSERT_EQ(theta.status, search::Status::solved) << name;
    auto polish = [&](const auto& path) {
      return env::tighten_path(m.world, env::shortcut_path(m.world, path));
    };
    const auto vis_path = polish(points(g, vis.path));
    const auto theta_path = polish(points(grid, theta.path));
    expect_valid(m.world, vis_path, *m.start, *m.goal, name);
    EXPECT_LE(env::polyline_length<3>(vis_path), env::polyline_length<3>(theta_path) * 1.001)
        << name;
  }
}

}  // namespace
}  // namespace hpcplan
