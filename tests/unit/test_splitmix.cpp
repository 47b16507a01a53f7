#include <gtest/gtest.h>

#include "hpcplan/core/splitmix64.hpp"

namespace {

TEST(SplitMix64, MatchesPublishedReferenceStream) {
  // Reference outputs of Vigna's splitmix64.c for seed 1234567.
  hpcplan::SplitMix64 rng(1234567);
  EXPECT_EQ(rng.next(), 6457827717110365317ULL);
  EXPECT_EQ(rng.next(), 3203168211198807973ULL);
  EXPECT_EQ(rng.next(), 9817491932198370423ULL);
}

TEST(SplitMix64, FinaliserIsABijectionOnSamples) {
  // Distinct inputs must give distinct hashes (it is invertible); check a dense block.
  std::vector<std::uint64_t> seen;
  for (std::uint64_t x = 0; x < 4096; ++x) seen.push_back(hpcplan::splitmix64_mix(x));
  std::sort(seen.begin(), seen.end());
  EXPECT_EQ(std::adjacent_find(seen.begin(), seen.end()), seen.end());
}

TEST(SplitMix64, UnitAndBoundedDrawsStayInRange) {
  hpcplan::SplitMix64 rng(7);
  for (int i = 0; i < 10000; ++i) {
    const double u = rng.next_unit();
    ASSERT_GE(u, 0.0);
    ASSERT_LT(u, 1.0);
    ASSERT_LT(rng.next_below(13), 13u);
  }
}

}  // namespace
