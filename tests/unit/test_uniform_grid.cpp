// The uniform-grid helper against brute force: index/coordinate round trips, box iteration,
// neighbour offsets, the cells a closed box touches (faces on cell boundaries included), and
// counting-sort buckets equal to per-cell lists.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <set>
#include <vector>

#include "hpcplan/core/uniform_grid.hpp"

namespace hpcplan {
namespace {

TEST(GridShape, IndexAndCoordinatesRoundTripAndIterationVisitsEachCellOnce) {
  const GridShape<3> g({4, 3, 5});
  EXPECT_EQ(g.size(), 60u);
  std::set<std::uint64_t> seen;
  GridShape<3>::for_each_in({0, 0, 0}, {3, 2, 4}, [&](const auto& c) {
    const auto i = g.index(c);
    EXPECT_EQ(g.coords(i), c);
    EXPECT_TRUE(g.contains(c));
    seen.insert(i);
  });
  EXPECT_EQ(seen.size(), 60u);
  EXPECT_EQ(*seen.rbegin(), 59u);
  EXPECT_FALSE(g.contains({4, 0, 0}));
  EXPECT_FALSE(g.contains({0, -1, 0}));
  int n = 0;
  GridShape<3>::for_each_in({1, 1, 1}, {0, 2, 2}, [&](const auto&) { ++n; });  // empty range
  EXPECT_EQ(n, 0);
  GridShape<3>::for_each_in({0, 0, 0}, {3, 2, 4}, [&](const auto&) { return ++n < 7; });
  EXPECT_EQ(n, 7);  // a bool-returning visitor stops the walk
}

TEST(GridShape, NeighbourOffsetsAreTheDistinctNonZeroUnitSteps) {
  for (int d : {1, 2, 3, 4}) {
    std::size_t count = 0, expected = 1;
    for (int k = 0; k < d; ++k) expected *= 3;
    if (d == 1) count = GridShape<1>::neighbour_offsets().size();
    if (d == 2) count = GridShape<2>::neighbour_offsets().size();
    if (d == 3) {
      const auto o = GridShape<3>::neighbour_offsets();
      count = o.size();
      const std::set<std::array<int, 3>> distinct(o.begin(), o.end());
      EXPECT_EQ(distinct.size(), o.size());
      for (const auto& v : o) EXPECT_TRUE(v[0] != 0 || v[1] != 0 || v[2] != 0);
    }
    if (d == 4) count = GridShape<4>::neighbour_offsets().size();
    EXPECT_EQ(count, expected - 1) << d;
  }
}

TEST(UniformGrid, CellsTouchingABoxEqualBruteForceIncludingFaces) {
  UniformGrid<2> g;
  g.origin = {-1.0, 2.0};
  g.cell = {0.5, 0.25};
  g.shape = GridShape<2>({8, 12});
  std::mt19937_64 rng(7);
  std::uniform_int_distribution<int> q(-4, 40);  // multiples of 1/8: many exact faces
  int exact_faces = 0, missed = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    std::array<double, 2> lo, hi;
    for (int k = 0; k < 2; ++k) {
      double a = g.origin[k] + q(rng) / 8.0 * g.cell[k] * 2,
             b = g.origin[k] + q(rng) / 8.0 * g.cell[k] * 2;
      if (a > b) std::swap(a, b);
      lo[k] = a, hi[k] = b;
      exact_faces += std::fmod((a - g.origin[k]) / g.cell[k], 1.0) == 0.0;
    }
    // Brute force: cell c touches [lo, hi] when the closed intervals overlap on every axis.
    std::set<std::uint64_t> expected;
    GridShape<2>::for_each_in({0, 0}, {7, 11}, [&](const auto& c) {
      bool overlap = true;
      for (int k = 0; k < 2; ++k) {
        const double c_lo = g.origin[k] + c[k] * g.cell[k], c_hi = c_lo + g.cell[k];
        overlap = overlap && hi[k] >= c_lo && lo[k] <= c_hi;
      }
      if (overlap) expected.insert(g.shape.index(c));
    });
    GridShape<2>::Coords first, last;
    std::set<std::uint64_t> got;
    if (g.cells_touching(lo, hi, first, last))
      GridShape<2>::for_each_in(first, last, [&](const auto& c) { got.insert(g.shape.index(c)); });
    else
      ++missed;
    EXPECT_EQ(got, expected) << lo[0] << "," << lo[1] << " " << hi[0] << "," << hi[1];
  }
  EXPECT_GT(exact_faces, 500);
  EXPECT_GT(missed, 10);
  // The cell of a point: clamped into the grid.
  EXPECT_EQ(g.cell_of({-1.0, 2.0}), (GridShape<2>::Coords{0, 0}));
  EXPECT_EQ(g.cell_of({-0.5, 2.25}), (GridShape<2>::Coords{1, 1}));
  EXPECT_EQ(g.cell_of({100, -100}), (GridShape<2>::Coords{7, 0}));
}

TEST(CsrBuckets, EqualPerCellListsInItemOrder) {
  std::mt19937_64 rng(11);
  const std::size_t cells = 97, items = 2000;
  std::vector<std::vector<std::size_t>> memberships(items);
  std::vector<std::vector<std::uint32_t>> lists(cells);
  for (std::size_t i = 0; i < items; ++i) {
    const int n = static_cast<int>(rng() % 4);  // 0 to 3 cells, some items in none
    std::set<std::size_t> cs;
    for (int m = 0; m < n; ++m) cs.insert(rng() % cells);
    for (std::size_t c : cs) {
      memberships[i].push_back(c);
      lists[c].push_back(static_cast<std::uint32_t>(i));
    }
  }
  CsrBuckets b;
  b.build(cells, items, [&](std::size_t i, auto&& add) {
    for (std::size_t c : memberships[i]) add(c);
  });
  ASSERT_EQ(b.cells(), cells);
  std::size_t total = 0;
  for (std::size_t c = 0; c < cells; ++c) {
    const auto got = b.items_in(c);
    EXPECT_EQ(std::vector<std::uint32_t>(got.begin(), got.end()), lists[c]) << c;
    total += got.size();
  }
  EXPECT_EQ(total, b.entries());
  EXPECT_GT(total, items);
}

}  // namespace
}  // namespace hpcplan
