#include <gtest/gtest.h>

#include <vector>

#include "hpcplan/core/error.hpp"
#include "hpcplan/core/splitmix64.hpp"
#include "hpcplan/env/gog.hpp"

namespace {

using hpcplan::GogField;
using hpcplan::GogParams;

// Seed 002 Algorithm 1, restated independently of the library.
int reference_level(std::uint64_t x, std::uint64_t h, int bp, int bv) {
  std::uint64_t v = x ^ h;
  v = ((x >> bp) + v) >> bv;
  return static_cast<int>(v & 3);
}

TEST(Gog, LevelsFollowAlgorithmOneWithSeedsFromSplitMix) {
  GogParams p;
  p.seed = 99;
  p.shift_p = 2;
  p.shift_v = 3;
  GogField f(5, 100, p);
  hpcplan::SplitMix64 rng(99);
  for (int axis = 0; axis < 5; ++axis) {
    const std::uint64_t h = rng.next();
    EXPECT_EQ(f.axis_seed(axis), h);
    for (int c = 0; c < 100; ++c) {
      ASSERT_EQ(f.level(axis, c), reference_level(c, h, 2, 3));
      ASSERT_EQ(f.level_table(axis)[c], f.level(axis, c));
    }
  }
}

TEST(Gog, DeterministicAndSeedSensitive) {
  GogParams p;
  GogField a(3, 50, p), b(3, 50, p);
  p.seed = 2;
  GogField c(3, 50, p);
  int differ = 0;
  for (int x = 0; x < 50; ++x)
    for (int y = 0; y < 50; ++y)
      for (int z = 0; z < 50; ++z) {
        const std::vector<int> s{x, y, z};
        ASSERT_EQ(a.is_free(s), b.is_free(s));
        differ += a.is_free(s) != c.is_free(s);
      }
  EXPECT_GT(differ, 1000);
}

TEST(Gog, LowerDimensionalAxesAreSharedAcrossDimensions) {
  // Seed 002 V-A: growing d extends the same field rather than redrawing it.
  GogField f4(4, 100, GogParams{}), f8(8, 100, GogParams{});
  for (int axis = 0; axis < 4; ++axis) EXPECT_EQ(f4.axis_seed(axis), f8.axis_seed(axis));
}

TEST(Gog, BlockedFractionIsExactAndMonotoneInThreshold) {
  for (int d = 1; d <= 3; ++d) {
    GogParams p;
    p.shift_v = 2;
    for (int thr = 1; thr <= 3 * d + 1; ++thr) {
      p.threshold = thr;
      GogField f(d, 20, p);
      long total = 1, blocked = 0;
      for (int i = 0; i < d; ++i) total *= 20;
      for (long idx = 0; idx < total; ++idx) {
        std::vector<int> s(d);
        for (int i = 0, q = idx; i < d; ++i, q /= 20) s[i] = q % 20;
        blocked += !f.is_free(s);
      }
      EXPECT_NEAR(f.blocked_fraction(), static_cast<double>(blocked) / total, 1e-12);
      if (thr > 1) {
        EXPECT_LE(f.blocked_fraction(), f.blocked_fraction_for(thr - 1));
      }
    }
    p.threshold = 3 * d + 1;
    EXPECT_EQ(GogField(d, 20, p).blocked_fraction(), 0.0);
  }
}

TEST(Gog, AutomaticThresholdIsTheDensestNotAboveTarget) {
  for (double density : {0.1, 0.3, 0.5, 0.8}) {
    GogParams p;
    p.density = density;
    for (int d = 2; d <= 10; d += 2) {
      GogField f(d, 100, p);
      EXPECT_LE(f.blocked_fraction(), density + 1e-12);
      if (f.threshold() > 1) {
        EXPECT_GT(f.blocked_fraction_for(f.threshold() - 1), density);
      }
    }
  }
}

TEST(Gog, ShiftVControlsRunLength) {
  // With b_p large the level is constant on aligned runs of 2^b_v coordinates.
  GogParams p;
  p.shift_p = 40;
  for (int bv : {1, 3, 5}) {
    p.shift_v = bv;
    GogField f(1, 256, p);
    for (int c = 0; c < 256; ++c) ASSERT_EQ(f.level(0, c), f.level(0, c & ~((1 << bv) - 1)));
  }
}

TEST(Gog, RejectsImpossibleParameters) {
  GogParams p;
  p.threshold = 8;
  EXPECT_THROW(GogField(2, 10, p), hpcplan::InputError);  // > 3d + 1
  p.threshold = 0;
  p.density = 1.5;
  EXPECT_THROW(GogField(2, 10, p), hpcplan::InputError);
  p.density = 0.3;
  p.shift_v = 70;
  EXPECT_THROW(GogField(2, 10, p), hpcplan::InputError);
}

}  // namespace
