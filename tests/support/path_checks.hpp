#pragma once
// Checks every continuous-world planner test applies to a returned path, independently of the
// planner: exact ends, the exact segment test on every segment, and dense point sampling.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "hpcplan/env/point.hpp"

namespace hpcplan::test_support {

// Exact re-check plus a dense-sampling check that no point of the path is in collision.
template <class W>
void expect_valid(const W& w, const std::vector<env::Vec<W::kDim>>& path,
                  const env::Vec<W::kDim>& start, const env::Vec<W::kDim>& goal,
                  const std::string& what) {
  ASSERT_FALSE(path.empty()) << what;
  EXPECT_EQ(path.front(), start) << what;
  EXPECT_EQ(path.back(), goal) << what;
  for (std::size_t i = 1; i < path.size(); ++i) {
    ASSERT_TRUE(w.segment_free(path[i - 1], path[i])) << what << " segment " << i;
    for (int s = 0; s <= 50; ++s)
      ASSERT_TRUE(w.point_free(env::lerp<W::kDim>(path[i - 1], path[i], s / 50.0)))
          << what << " segment " << i << " " << env::format_point<W::kDim>(path[i - 1]) << " "
          << env::format_point<W::kDim>(path[i]) << " at " << s;
  }
}

}  // namespace hpcplan::test_support
