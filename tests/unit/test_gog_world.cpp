// The GOG field as a continuous world (env/gog_world.hpp): point tests against the lattice's
// own is_free, the exact voxel walk against dense sampling, and the world-generic planners
// (RRT-Connect, RRT*, the tightener) on it, their paths re-validated independently.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <random>
#include <stop_token>
#include <string>
#include <vector>

#include "hpcplan/core/error.hpp"
#include "hpcplan/env/gog_world.hpp"
#include "hpcplan/env/path_shortcut.hpp"
#include "hpcplan/plan/grid_planner.hpp"
#include "hpcplan/plan/grid_problem.hpp"
#include "hpcplan/tree/rrt_connect.hpp"
#include "hpcplan/tree/rrt_star.hpp"
#include "support/path_checks.hpp"

namespace hpcplan::env {
namespace {

std::shared_ptr<const GogField> field_for(int dims, int extent, std::uint64_t seed = 1) {
  GogParams p;
  p.seed = seed;
  return std::make_shared<const GogField>(dims, extent, p);
}

class GogPoints : public ::testing::TestWithParam<int> {};

TEST_P(GogPoints, MatchTheLatticeIncludingCellFacesAndTheUpperBound) {
  const int d = GetParam();
  const int extent = 40;
  const auto field = field_for(d, extent);
  std::mt19937_64 rng(1234 + d);
  std::uniform_real_distribution<double> u(0.0, extent);
  int free = 0;
  std::vector<double> x(d);
  for (int i = 0; i < 20000; ++i) {
    std::vector<int> cell(d);
    for (int a = 0; a < d; ++a) {
      x[a] = i % 5 == 0 ? std::floor(u(rng) + 0.5) : u(rng);  // every fifth on a face
      cell[a] = std::min(static_cast<int>(std::floor(x[a])), extent - 1);
    }
    const bool native = field->is_free(cell);
    ASSERT_EQ(gog_point_free(*field, x.data()), native) << "point " << i;
    EXPECT_EQ(gog_cell_of(*field, x.data()), cell);
    EXPECT_EQ(gog_why_not_free(*field, x.data()).empty(), native);
    free += native;
  }
  EXPECT_GT(free, 1000);  // both outcomes exercised
  EXPECT_LT(free, 19000);
}

INSTANTIATE_TEST_SUITE_P(Dims, GogPoints, ::testing::Values(2, 4, 7, 10));

TEST(GogWorld, OutsideTheBoxIsBlockedAndEveryQueryIsCounted) {
  const GogWorld<2> w(field_for(2, 20));
  EXPECT_FALSE(w.point_free({-0.001, 1.0}));
  EXPECT_FALSE(w.point_free({20.001, 1.0}));
  EXPECT_FALSE(w.point_free({std::nan(""), 1.0}));
  EXPECT_EQ(w.collision_checks(), 3u);
  EXPECT_EQ(w.why_not_free({-1.0, 1.0}), "outside the box [0, 20]");
  EXPECT_FALSE(w.segment_free({1.0, 1.0}, {21.0, 1.0}));  // leaves the box: blocked at t = 0
  EXPECT_EQ(w.first_contact({1.0, 1.0}, {21.0, 1.0}), 0.0);
  EXPECT_EQ(w.bounds().hi[1], 20.0);
  EXPECT_NEAR(w.free_volume(), 400.0 * (1.0 - w.field().blocked_fraction()), 1e-9);
  EXPECT_THROW(GogWorld<3>(field_for(2, 20)), InputError);
}

// The walk against dense sampling: what it accepts has every sampled point free, and what has
// a blocked sample it rejects. It may reject a segment whose samples are all free (one that
// touches a blocked cell at an edge, a corner, or between samples), rarely.
class GogSegments : public ::testing::TestWithParam<int> {};

TEST_P(GogSegments, AgreeWithDenseSampling) {
  const int d = GetParam();
  const int extent = 24;
  const auto field = field_for(d, extent);
  std::mt19937_64 rng(99 + d);
  std::uniform_real_distribution<double> u(0.0, extent);
  std::uniform_real_distribution<double> step(-3.0, 3.0);
  int accepted = 0, rejected = 0, rejected_but_sampled_free = 0;
  for (int n = 0; n < 4000; ++n) {
    std::vector<double> a(d), b(d);
    for (int i = 0; i < d; ++i) {
      a[i] = u(rng);
      // Short and long segments, some starting on cell faces or along exact diagonals.
      b[i] = a[i] + (n % 3 == 0 ? step(rng) * 4 : step(rng));
      if (n % 7 == 0) a[i] = std::floor(a[i]);
      if (n % 11 == 0) b[i] = a[i] + (i < 2 ? 1.0 : 0.0);
      b[i] = std::clamp(b[i], 0.0, double(extent));
    }
    if (!gog_point_free(*field, a.data())) continue;
    const GogSegmentWalk walk = gog_walk_segment(*field, a.data(), b.data());
    bool sampled_ok = true;
    std::vector<double> p(d);
    double first_blocked = 2.0;
    for (int s = 0; s <= 2000 && sampled_ok; ++s) {
      for (int i = 0; i < d; ++i) p[i] = s == 2000 ? b[i] : a[i] + (b[i] - a[i]) * s / 2000.0;
      sampled_ok = gog_point_free(*field, p.data());
      if (!sampled_ok) first_blocked = s / 2000.0;
    }
    EXPECT_GT(walk.cells, 0u);
    if (walk.free) {
      ++accepted;
      ASSERT_TRUE(sampled_ok) << "the walk accepted a segment with a blocked point, n=" << n;
    } else {
      ++rejected;
      if (sampled_ok) ++rejected_but_sampled_free;
      // The first touch is never after the first blocked sample.
      EXPECT_LE(walk.blocked_at, first_blocked + 1e-9) << "n=" << n;
    }
  }
  EXPECT_GT(accepted, 100);
  EXPECT_GT(rejected, 100);
  EXPECT_LE(rejected_but_sampled_free, rejected / 20) << "the walk rejects free segments";
}

INSTANTIATE_TEST_SUITE_P(Dims, GogSegments, ::testing::Values(2, 3, 5, 8));

TEST(GogWorld, ADiagonalThroughACornerOfABlockedCellIsBlocked) {
  // Free (x, y) and (x+1, y+1) with (x+1, y) blocked: the centre-to-centre diagonal touches
  // the blocked cell at one corner point only. Point sampling accepts it (that point lies in a
  // free cell by the floor rule); the walk, like the lattice, does not.
  const GogWorld<2> w(field_for(2, 100));
  const GogField& f = w.field();
  for (int x = 0; x + 1 < 100; ++x)
    for (int y = 0; y + 1 < 100; ++y) {
      if (f.is_free(std::vector<int>{x, y}) && f.is_free(std::vector<int>{x + 1, y + 1}) &&
          !f.is_free(std::vector<int>{x + 1, y})) {
        const auto contact = w.first_contact({x + 0.5, y + 0.5}, {x + 1.5, y + 1.5});
        ASSERT_TRUE(contact.has_value());
        EXPECT_NEAR(*contact, 0.5, 1e-9);
        EXPECT_TRUE(w.segment_free({x + 0.5, y + 0.6}, {x + 1.4, y + 1.5}));  // clear of it
        return;
      }
    }
  FAIL() << "no such corner in this field";
}

// The planners written once for every world run on GOG unchanged.
TEST(GogWorld, TreePlannersAndTheTightenerReturnValidPaths) {
  const auto field = field_for(3, 30, 7);
  const GogWorld<3> w(field);
  const auto s = adjust_to_free(*field, {0, 0, 0}, +1, "start");
  const auto g = adjust_to_free(*field, {29, 29, 29}, -1, "goal");
  const Vec<3> start{s[0] + 0.5, s[1] + 0.5, s[2] + 0.5};
  const Vec<3> goal{g[0] + 0.5, g[1] + 0.5, g[2] + 0.5};
  tree::TreeOptions o;
  o.seed = 3;
  o.max_samples = 20000;
  o.stop = Stop::after(60.0);  // a guard against a hang only
  const auto a = tree::rrt_connect(w, start, goal, o);
  ASSERT_EQ(a.status, Status::solved);
  test_support::expect_valid(w, a.path, start, goal, "gog rrtconnect");
  const auto tight = env::tighten_path(w, env::shortcut_path(w, a.path));
  test_support::expect_valid(w, tight, start, goal, "gog tightened");
  EXPECT_LE(polyline_length<3>(tight), a.cost + 1e-9);
  EXPECT_GE(polyline_length<3>(tight), distance<3>(start, goal) - 1e-9);
  const auto b = tree::rrt_star(w, start, goal, o);
  ASSERT_EQ(b.status, Status::solved);
  test_support::expect_valid(w, b.path, start, goal, "gog rrtstar");
  EXPECT_GT(w.collision_checks(), 0u);
}

// A GOG world whose segment tests trigger a stop after a set number: the tightener is then
// interrupted wherever that falls, mid-pass included.
struct StoppingWorld {
  static constexpr int kDim = 4;
  const GogWorld<4>& world;
  std::stop_source& source;
  mutable long left;  // worlds are const to their users; this one counts down regardless
  bool point_free(const Vec<4>& p) const { return world.point_free(p); }
  bool segment_free(const Vec<4>& a, const Vec<4>& b) const {
    if (--left == 0) source.request_stop();
    return world.segment_free(a, b);
  }
};

// Stopped anywhere, the tightener leaves a valid path no longer than it was, and the points a
// stopped pass put in and did not move go again.
TEST(GogWorld, TheTightenerStoppedMidPassLeavesAValidLeanPath) {
  const auto field = field_for(4, 20, 3);
  const GogWorld<4> w(field);
  const auto s = adjust_to_free(*field, {0, 0, 0, 0}, +1, "start");
  const auto g = adjust_to_free(*field, {19, 19, 19, 19}, -1, "goal");
  const Vec<4> start{s[0] + 0.5, s[1] + 0.5, s[2] + 0.5, s[3] + 0.5};
  const Vec<4> goal{g[0] + 0.5, g[1] + 0.5, g[2] + 0.5, g[3] + 0.5};
  // The lattice path itself: many bends, all with slack.
  GridProblem problem;
  problem.dims = 4;
  problem.extent = 20;
  problem.gog = field->params();
  problem.gog.threshold = field->threshold();
  problem.start = s;
  problem.goal = g;
  GridSearchOptions search;
  search.keep_path = true;
  const GridReport lattice = solve_grid(*field, problem, search);
  ASSERT_EQ(lattice.result.status, search::Status::solved);
  std::vector<Vec<4>> input;
  for (const auto& c : lattice.result.path)
    input.push_back({c[0] + 0.5, c[1] + 0.5, c[2] + 0.5, c[3] + 0.5});
  ASSERT_GT(input.size(), 10u);
  const double before = polyline_length<4>(input);
  int improved = 0;
  for (const long after : {1L, 7L, 40L, 200L, 1000L, 5000L}) {
    std::stop_source source;
    StoppingWorld stopping{w, source, after};
    TightenOptions t;
    t.max_segment = 0.5;  // many points per segment: a lazy stop would keep them all
    t.time_limit_s = 60.0;
    t.stop = Stop(source.get_token());
    std::vector<Vec<4>> path = input;
    tighten_in_place(stopping, path, t);
    const std::string what = "stopped after " + std::to_string(after) + " tests";
    test_support::expect_valid(w, path, start, goal, what);
    EXPECT_LE(polyline_length<4>(path), before + 1e-9) << what;
    // Stopped before the first sweep got going, the subdivision's points all go again (kept,
    // they would triple the count here).
    if (after <= 7) {
      EXPECT_LE(path.size(), input.size() + 1) << what;
    }
    improved += polyline_length<4>(path) < before - 1e-6;
  }
  EXPECT_GE(improved, 3);  // the later stops come after real progress
}

}  // namespace
}  // namespace hpcplan::env
