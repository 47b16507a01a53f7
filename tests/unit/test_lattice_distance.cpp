#include <gtest/gtest.h>

#include <random>

#include "hpcplan/core/splitmix64.hpp"
#include "hpcplan/env/gog.hpp"
#include "hpcplan/graph/lattice_distance.hpp"
#include "hpcplan/graph/lattice_graph.hpp"
#include "lattice_oracle.hpp"

namespace {

using namespace hpcplan;

// The lattice heuristic must equal the true free-space distance (so it is exact, admissible
// and consistent); the oracle's Dijkstra on an obstacle-free field is the reference.
TEST(LatticeDistance, EqualsFreeSpaceDijkstra) {
  SplitMix64 rng(11);
  for (bool full : {false, true}) {
    for (int d = 1; d <= 4; ++d) {
      const int extent = d <= 2 ? 12 : 7;
      GogParams p;
      p.threshold = 3 * d + 1;
      const GogField f(d, extent, p);
      oracle::Lattice o(f, full);
      for (int trial = 0; trial < 8; ++trial) {
        std::vector<int> a(d), b(d), delta(d);
        for (int i = 0; i < d; ++i) {
          a[i] = static_cast<int>(rng.next_below(extent));
          b[i] = static_cast<int>(rng.next_below(extent));
          delta[i] = std::abs(a[i] - b[i]);
        }
        const double h = full ? full_connectivity_free_distance(delta).value()
                              : seed_rule_free_distance(delta).value();
        EXPECT_NEAR(h, o.dijkstra(a, b).cost, 1e-9) << "d=" << d << " full=" << full;
      }
    }
  }
}

TEST(LatticeDistance, ConsistentAcrossEveryMoveInHighDimensions) {
  // h(x) <= c(x,y) + h(y) for every seed-rule move, checked on random states up to 16D.
  SplitMix64 rng(3);
  for (int d = 2; d <= 16; ++d) {
    for (int trial = 0; trial < 50; ++trial) {
      std::vector<int> delta(d);
      for (auto& v : delta) v = static_cast<int>(rng.next_below(40)) + 1;
      const double hx = seed_rule_free_distance(delta).value();
      for (int i = 0; i < d; ++i)
        for (int si : {-1, 1}) {
          auto one = delta;
          one[i] = std::abs(one[i] + si);
          ASSERT_LE(hx, 1.0 + seed_rule_free_distance(one).value() + 1e-9);
          for (int k = i + 1; k < d; ++k)
            for (int sk : {-1, 1}) {
              auto two = one;
              two[k] = std::abs(two[k] + sk);
              ASSERT_LE(hx, std::sqrt(2.0) + seed_rule_free_distance(two).value() + 1e-9);
            }
        }
    }
  }
}

TEST(LatticeDistance, DiagonalQualityLimitIsSqrtHalfD) {
  // Corner to corner, the lattice cannot beat sqrt(d/2) times the straight line (d even).
  for (int d = 2; d <= 16; d += 2) {
    std::vector<int> delta(d, 99);
    const double q = seed_rule_free_distance(delta).value() / (99 * std::sqrt(double(d)));
    EXPECT_NEAR(q, std::sqrt(d / 2.0), 1e-12);
  }
}

TEST(LatticeCost, EqualCostsAreBitwiseEqualWhateverTheOrder) {
  LatticeCost a, b;
  for (int i = 0; i < 1000; ++i) a = a + LatticeCost::for_axes(1 + i % 2);
  for (int i = 0; i < 500; ++i) b = b + LatticeCost::for_axes(2);
  for (int i = 0; i < 500; ++i) b = b + LatticeCost::for_axes(1);
  EXPECT_EQ(a.value(), b.value());
}

}  // namespace
