// The engine is generic: the same best_first_search runs on a dense 2D grid.
#include <gtest/gtest.h>

#include <queue>

#include "hpcplan/core/splitmix64.hpp"
#include "hpcplan/graph/dense_grid2d.hpp"
#include "hpcplan/search/best_first.hpp"

namespace {

using namespace hpcplan;

struct Octile {
  const DenseGrid2D& g;
  DenseGrid2D::State goal;
  LatticeCost operator()(DenseGrid2D::State s) const {
    const int dx = std::abs(g.x_of(s) - g.x_of(goal)), dy = std::abs(g.y_of(s) - g.y_of(goal));
    return {std::max(dx, dy) - std::min(dx, dy), std::min(dx, dy), 0};
  }
};

double reference_dijkstra(const DenseGrid2D& g, int sx, int sy, int gx, int gy) {
  std::vector<double> dist(g.width() * g.height(), INFINITY);
  using Item = std::pair<double, int>;
  std::priority_queue<Item, std::vector<Item>, std::greater<>> pq;
  dist[g.at(sx, sy)] = 0;
  pq.push({0, static_cast<int>(g.at(sx, sy))});
  while (!pq.empty()) {
    auto [d, u] = pq.top();
    pq.pop();
    if (d > dist[u]) continue;
    const int x = u % g.width(), y = u / g.width();
    if (x == gx && y == gy) return d;
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy) {
        if (!dx && !dy) continue;
        if (!g.is_free(x + dx, y + dy)) continue;
        if (dx && dy && (!g.is_free(x + dx, y) || !g.is_free(x, y + dy))) continue;
        const double nd = d + ((dx && dy) ? std::sqrt(2.0) : 1.0);
        const int v = g.at(x + dx, y + dy);
        if (nd < dist[v] - 1e-12) pq.push({dist[v] = nd, v});
      }
  }
  return -1;
}

TEST(DenseGrid, AStarAndDijkstraMatchReferenceOnRandomGrids) {
  SplitMix64 rng(42);
  int solvable = 0, unsolvable = 0;
  for (int trial = 0; trial < 30; ++trial) {
    DenseGrid2D g(40, 30);
    for (int y = 0; y < 30; ++y)
      for (int x = 0; x < 40; ++x) g.set_blocked(x, y, rng.next_unit() < 0.3);
    g.set_blocked(0, 0, false);
    g.set_blocked(39, 29, false);
    const double ref = reference_dijkstra(g, 0, 0, 39, 29);
    search::Options opt;
    auto astar =
        search::best_first_search(g, g.at(0, 0), g.at(39, 29), Octile{g, g.at(39, 29)}, opt);
    auto dijk =
        search::best_first_search(g, g.at(0, 0), g.at(39, 29), search::ZeroHeuristic{}, opt);
    if (ref < 0) {
      ++unsolvable;
      EXPECT_EQ(astar.status, search::Status::no_path);
      EXPECT_EQ(dijk.status, search::Status::no_path);
      continue;
    }
    ++solvable;
    ASSERT_EQ(astar.status, search::Status::solved);
    EXPECT_NEAR(astar.cost, ref, 1e-9);
    EXPECT_NEAR(dijk.cost, ref, 1e-9);
    EXPECT_LE(astar.counters.expanded, dijk.counters.expanded);
  }
  // The oracle comparison means something only if most grids have a path (and the no-path
  // branch is exercised too).
  EXPECT_GE(solvable, 10);
  EXPECT_GE(unsolvable, 1);
}

TEST(DenseGrid, WalledInStartHasNoPath) {
  DenseGrid2D g(20, 20);
  for (int i = 3; i <= 7; ++i) {
    g.set_blocked(i, 3, true);
    g.set_blocked(i, 7, true);
    g.set_blocked(3, i, true);
    g.set_blocked(7, i, true);
  }
  auto r = search::best_first_search(g, g.at(5, 5), g.at(15, 15), search::ZeroHeuristic{},
                                     search::Options{});
  EXPECT_EQ(r.status, search::Status::no_path);
  EXPECT_EQ(r.counters.expanded, 9u);  // exactly the 3x3 pocket
}

TEST(DenseGrid, DiagonalsDoNotCutCorners) {
  DenseGrid2D g(2, 2);
  g.set_blocked(1, 0, true);
  g.set_blocked(0, 1, true);
  auto r = search::best_first_search(g, g.at(0, 0), g.at(1, 1), search::ZeroHeuristic{},
                                     search::Options{});
  EXPECT_EQ(r.status, search::Status::no_path);
}

TEST(DenseGrid, BudgetAndTimeLimitStopTheSearch) {
  DenseGrid2D g(200, 200);
  search::Options opt;
  opt.max_states = 50;
  auto r = search::best_first_search(g, g.at(0, 0), g.at(199, 199), search::ZeroHeuristic{}, opt);
  EXPECT_EQ(r.status, search::Status::budget_exceeded);
  EXPECT_LE(r.counters.peak_states, 51u);
  EXPECT_TRUE(r.path.empty());

  // The clock is read every 64 expansions; a 40,000-cell search passes that many.
  search::Options timed;
  timed.stop = Stop::after(1e-9);
  auto t = search::best_first_search(g, g.at(0, 0), g.at(199, 199), search::ZeroHeuristic{}, timed);
  EXPECT_EQ(t.status, search::Status::timeout);
  EXPECT_TRUE(t.path.empty());
}

}  // namespace
