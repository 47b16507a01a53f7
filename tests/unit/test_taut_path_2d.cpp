// The 2D taut path (env/taut_path_2d.hpp) on maps of independently drawn cells: valid by the
// exact walk and by dense sampling, never longer than its input, never shorter than the exact
// shortest path (a visibility-graph oracle), and taut by a test of its own: every bend sits on
// a blocked cell's corner and cannot be dropped.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "hpcplan/core/splitmix64.hpp"
#include "hpcplan/env/path_shortcut.hpp"
#include "hpcplan/env/taut_path_2d.hpp"
#include "hpcplan/env/voxel_walk.hpp"
#include "support/bitmap_dijkstra.hpp"
#include "support/path_checks.hpp"
#include "support/shortest_path_2d.hpp"

namespace {

using namespace hpcplan;
using P = env::Vec<2>;

// A square map of unit cells as a continuous world, its segments tested by the exact walk.
struct Bitmap2D {
  static constexpr int kDim = 2;
  int n = 0;
  std::vector<char> cells;

  bool blocked(int x, int y) const {
    return x >= 0 && y >= 0 && x < n && y < n && cells[static_cast<std::size_t>(y) * n + x];
  }
  bool point_free(const P& p) const {
    if (!(p[0] >= 0 && p[1] >= 0 && p[0] <= n && p[1] <= n)) return false;
    return !blocked(std::min(static_cast<int>(p[0]), n - 1),
                    std::min(static_cast<int>(p[1]), n - 1));
  }
  bool segment_free(const P& a, const P& b) const {
    const int extent[2] = {n, n};
    return env::voxel_walk(2, extent, a.data(), b.data(),
                           [&](const int* c) { return blocked(c[0], c[1]); })
        .free;
  }
};

// A shortest lattice path as cell centres; empty when the goal cell cannot be reached.
std::vector<P> lattice_path(const Bitmap2D& m, int sx, int sy, int gx, int gy) {
  const auto r = test_support::bitmap_dijkstra(
      m.n, [&m](int x, int y) { return m.blocked(x, y); }, sx, sy, gx, gy);
  std::vector<P> path;
  for (const auto& [x, y] : r.cells) path.push_back({x + 0.5, y + 0.5});
  return path;
}

double cross(const P& o, const P& u, const P& v) {
  return (u[0] - o[0]) * (v[1] - o[1]) - (u[1] - o[1]) * (v[0] - o[0]);
}

// Taut, checked without the algorithm's own step: each bend is a hair from a lattice corner
// with a blocked cell on the inside of the turn, and its neighbours cannot see each other.
void expect_taut(const Bitmap2D& m, const std::vector<P>& path, int trial) {
  for (std::size_t i = 1; i + 1 < path.size(); ++i) {
    const P& p = path[i - 1];
    const P& v = path[i];
    const P& s = path[i + 1];
    const P c{std::round(v[0]), std::round(v[1])};
    EXPECT_LT(env::distance<2>(v, c), 1e-6) << "trial " << trial << " bend " << i;
    bool wraps = false;
    for (int k = 0; k < 4; ++k) {
      const int x = static_cast<int>(c[0]) - 1 + (k & 1), y = static_cast<int>(c[1]) - 1 + (k >> 1);
      const P centre{x + 0.5, y + 0.5};
      // Inside the turn: on s's side of the incoming line and on p's side of the outgoing one.
      wraps = wraps || (m.blocked(x, y) && cross(p, v, centre) * cross(p, v, s) > 0 &&
                        cross(v, s, centre) * cross(v, s, p) > 0);
    }
    EXPECT_TRUE(wraps) << "trial " << trial << " bend " << i;
    EXPECT_FALSE(m.segment_free(p, s)) << "trial " << trial << " bend " << i;
  }
}

TEST(TautPath2D, ShortestOfItsClassOnRandomMaps) {
  SplitMix64 rng(20261126);
  int solved = 0, optimal = 0, bends = 0;
  for (int trial = 0; trial < 1500; ++trial) {
    Bitmap2D m;
    m.n = 3 + static_cast<int>(rng.next_below(22));
    const double density = 0.05 + 0.4 * rng.next_unit();
    m.cells.resize(static_cast<std::size_t>(m.n) * m.n);
    for (char& c : m.cells) c = rng.next_unit() < density;
    const auto cell = [&] { return static_cast<int>(rng.next_below(m.n)); };
    const int sx = cell(), sy = cell(), gx = cell(), gy = cell();
    if (m.blocked(sx, sy) || m.blocked(gx, gy)) continue;
    std::vector<P> path = lattice_path(m, sx, sy, gx, gy);
    if (path.empty()) continue;
    // Exact ends anywhere inside their cells.
    const P start{sx + rng.next_unit(), sy + rng.next_unit()};
    const P goal{gx + rng.next_unit(), gy + rng.next_unit()};
    if (path.size() == 1) path.push_back(goal);
    path.front() = start;
    path.back() = goal;
    const double before = env::polyline_length<2>(path);

    std::vector<P> taut = env::shortcut_path(m, path);
    const env::TautStats stats = env::taut_path_2d(
        m, [&m](int x, int y) { return m.blocked(x, y); }, taut);
    ++solved;
    ASSERT_TRUE(stats.converged) << "trial " << trial;
    test_support::expect_valid(m, taut, start, goal, "trial " + std::to_string(trial));
    const double length = env::polyline_length<2>(taut);
    EXPECT_LE(length, before + 1e-9) << "trial " << trial;
    const double oracle = test_support::shortest_length_2d(
        m, [&m](int x, int y) { return m.blocked(x, y); }, m.n, start, goal, 1e-7);
    EXPECT_GE(length, oracle - 1e-5) << "trial " << trial;
    expect_taut(m, taut, trial);
    optimal += length <= oracle + 1e-5;
    bends += static_cast<int>(taut.size()) - 2;

    // A fixed point: run again, nothing is replaced.
    std::vector<P> again = taut;
    const env::TautStats second = env::taut_path_2d(
        m, [&m](int x, int y) { return m.blocked(x, y); }, again);
    EXPECT_EQ(second.replacements, 0u) << "trial " << trial;
  }
  std::printf("%d solved, %d of them the shortest path overall, %d bends\n", solved, optimal,
              bends);
  EXPECT_GT(solved, 300);
  EXPECT_GT(bends, 300);  // the maps make the paths wrap corners, not only straight lines
  // The lattice path's class is the shortest one on most maps; where it is not, the taut path
  // is still the shortest of its own class.
  EXPECT_GT(optimal, solved / 2);
}

// One blocked cell between the ends: the path wraps its two upper corners.
TEST(TautPath2D, WrapsASingleCellExactly) {
  Bitmap2D m;
  m.n = 5;
  m.cells.assign(25, 0);
  m.cells[2 * 5 + 2] = 1;
  std::vector<P> path{{0.5, 2.5}, {1.5, 3.5}, {2.5, 3.5}, {3.5, 3.5}, {4.5, 2.5}};
  const env::TautStats stats = env::taut_path_2d(
      m, [&m](int x, int y) { return m.blocked(x, y); }, path);
  EXPECT_TRUE(stats.converged);
  ASSERT_EQ(path.size(), 4u);
  EXPECT_NEAR(path[1][0], 2.0, 1e-6);
  EXPECT_NEAR(path[1][1], 3.0, 1e-6);
  EXPECT_NEAR(path[2][0], 3.0, 1e-6);
  EXPECT_NEAR(path[2][1], 3.0, 1e-6);
  EXPECT_NEAR(env::polyline_length<2>(path), 2 * std::hypot(1.5, 0.5) + 1.0, 1e-6);
  test_support::expect_valid(m, path, P{0.5, 2.5}, P{4.5, 2.5}, "single cell");
}

// With nothing in the way the path is its chord; a stop already requested changes nothing.
TEST(TautPath2D, OpenSpaceIsAStraightLineAndAStopIsHonoured) {
  Bitmap2D m;
  m.n = 8;
  m.cells.assign(64, 0);
  const std::vector<P> input{{0.5, 0.5}, {3.5, 1.5}, {4.5, 6.5}, {7.5, 7.5}};
  std::vector<P> path = input;
  env::taut_path_2d(
      m, [&m](int x, int y) { return m.blocked(x, y); }, path);
  EXPECT_EQ(path, (std::vector<P>{{0.5, 0.5}, {7.5, 7.5}}));

  std::stop_source source;
  source.request_stop();
  env::TautOptions o;
  o.stop = Stop(source.get_token());
  path = input;
  const env::TautStats stats = env::taut_path_2d(
      m, [&m](int x, int y) { return m.blocked(x, y); }, path, o);
  EXPECT_EQ(stats.passes, 0);
  EXPECT_EQ(path, input);
}

}  // namespace
