#include <gtest/gtest.h>

#include <set>
#include <vector>

#include "hpcplan/env/gog.hpp"
#include "hpcplan/graph/lattice_graph.hpp"

namespace {

using namespace hpcplan;

GogField open_field(int d, int extent) {
  GogParams p;
  p.threshold = 3 * d + 1;  // nothing blocked
  return GogField(d, extent, p);
}

template <int W>
std::vector<std::vector<int>> successors(const LatticeGraph<W>& g, std::vector<int> x) {
  std::vector<std::vector<int>> out;
  g.for_each_successor(g.pack(x), [&](const PackedKey<W>& t, LatticeCost, std::uint16_t m) {
    out.push_back(g.unpack(t));
    EXPECT_TRUE(g.predecessor(t, m) == g.pack(x));  // a move id undoes exactly
  });
  return out;
}

TEST(LatticeGraph, FreeSpaceNeighbourCountIsTwoDPlusTwoDDMinusOne) {
  for (int d = 1; d <= 16; ++d) {
    const GogField f = open_field(d, 100);
    const std::vector<int> centre(d, 50);
    std::size_t n = 0;
    if (KeyLayout(d, 100).words() == 1)
      n = successors(LatticeGraph<1>(f, Connectivity::seed_pairs), centre).size();
    else
      n = successors(LatticeGraph<2>(f, Connectivity::seed_pairs), centre).size();
    EXPECT_EQ(n, static_cast<std::size_t>(2 * d + 2 * d * (d - 1))) << "d=" << d;
  }
}

TEST(LatticeGraph, CornerHasOnlyInwardMoves) {
  const GogField f = open_field(3, 10);
  LatticeGraph<1> g(f, Connectivity::seed_pairs);
  // From the corner: 3 one-axis moves and 3 pairs, all +1.
  auto s = successors(g, {0, 0, 0});
  EXPECT_EQ(s.size(), 6u);
  for (auto& t : s)
    for (int c : t) EXPECT_GE(c, 0);
  EXPECT_EQ(successors(g, {9, 9, 9}).size(), 6u);
}

TEST(LatticeGraph, FullConnectivityHasThreeToTheDMinusOneMoves) {
  for (int d = 1; d <= 4; ++d) {
    const GogField f = open_field(d, 10);
    LatticeGraph<1> g(f, Connectivity::full);
    int expected = 1;
    for (int i = 0; i < d; ++i) expected *= 3;
    EXPECT_EQ(successors(g, std::vector<int>(d, 5)).size(), static_cast<std::size_t>(expected - 1));
  }
}

TEST(LatticeGraph, WideKeysRoundTripAtMaximumSize) {
  const GogField f = open_field(16, 65535);
  LatticeGraph<4> g(f, Connectivity::seed_pairs);
  std::vector<int> x(16);
  for (int i = 0; i < 16; ++i) x[i] = (i * 4099) % 65535;
  x[3] = 65534;
  x[4] = 0;
  EXPECT_EQ(g.unpack(g.pack(x)), x);
  const auto next = successors(g, x);
  ASSERT_FALSE(next.empty());  // an open field: every move is legal
  for (auto& t : next) {
    int changed = 0;
    for (int i = 0; i < 16; ++i) {
      EXPECT_LE(std::abs(t[i] - x[i]), 1);
      changed += t[i] != x[i];
    }
    EXPECT_TRUE(changed == 1 || changed == 2);
  }
}

// In a real GOG field, every generated move is legal, and a two-axis move appears exactly
// when the target and both one-axis intermediates are free.
TEST(LatticeGraph, TwoAxisMovesRequireBothIntermediatesFree) {
  GogParams p;
  p.seed = 5;
  p.shift_v = 1;
  p.density = 0.4;
  const GogField f(3, 24, p);
  LatticeGraph<1> g(f, Connectivity::seed_pairs);
  int blocked_by_intermediate = 0;
  for (int x = 0; x < 24; ++x)
    for (int y = 0; y < 24; ++y)
      for (int z = 0; z < 24; ++z) {
        const std::vector<int> a{x, y, z};
        if (!f.is_free(a)) continue;
        std::set<std::vector<int>> got;
        const std::uint64_t before = g.collision_checks();
        for (auto& t : successors(g, a)) got.insert(t);
        std::uint64_t expected_checks = 0;
        for (int i = 0; i < 3; ++i)
          for (int si : {-1, 1}) {
            std::vector<int> b = a;
            b[i] += si;
            if (b[i] < 0 || b[i] >= 24) continue;
            ++expected_checks;
            EXPECT_EQ(got.count(b), f.is_free(b) ? 1u : 0u);
            for (int k = i + 1; k < 3; ++k)
              for (int sk : {-1, 1}) {
                std::vector<int> c = b, other = a;
                c[k] += sk;
                other[k] += sk;
                if (c[k] < 0 || c[k] >= 24) continue;
                const bool both = f.is_free(b) && f.is_free(other);
                expected_checks += both;
                const bool legal = both && f.is_free(c);
                EXPECT_EQ(got.count(c), legal ? 1u : 0u);
                blocked_by_intermediate += f.is_free(c) && !both;
              }
          }
        // Each one-axis state is evaluated once, each pair target only if both are free.
        EXPECT_EQ(g.collision_checks() - before, expected_checks);
      }
  EXPECT_GT(blocked_by_intermediate, 100);  // the case really occurs in this field
}

TEST(LatticeGraph, CheckedEdgeLengthRejectsIllegalMoves) {
  const GogField f = open_field(3, 10);
  LatticeGraph<1> seed(f, Connectivity::seed_pairs), full(f, Connectivity::full);
  auto s = [&](std::vector<int> c) { return seed.pack(c); };
  EXPECT_DOUBLE_EQ(seed.checked_edge_length(s({1, 1, 1}), s({2, 1, 1})), 1.0);
  EXPECT_DOUBLE_EQ(seed.checked_edge_length(s({1, 1, 1}), s({2, 0, 1})), std::sqrt(2.0));
  EXPECT_LT(seed.checked_edge_length(s({1, 1, 1}), s({2, 2, 2})), 0);  // three axes
  EXPECT_DOUBLE_EQ(full.checked_edge_length(s({1, 1, 1}), s({2, 2, 2})), std::sqrt(3.0));
  EXPECT_LT(seed.checked_edge_length(s({1, 1, 1}), s({3, 1, 1})), 0);  // two steps
  EXPECT_LT(seed.checked_edge_length(s({1, 1, 1}), s({1, 1, 1})), 0);  // no move
}

}  // namespace
