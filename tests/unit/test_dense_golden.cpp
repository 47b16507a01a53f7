// The dense engine's answers, paths and counts on random cases, against the figures the engine
// gave before its superstep driver was written (tests/unit/data/dense_golden.txt, recorded by
// the engine of commit f75f05e): random GOG fields and random occupancy arrays, 1D to 8D, BFS
// and Dijkstra, both connectivities, point queries and distance fields, each run on 1 rank of
// 1 thread and on a drawn 1 to 4 ranks (threads of this process over a paired transport) of 1
// to 3 threads with a drawn block size. Every run must give the recorded line: the engine's
// results do not depend on its ranks, threads or blocks, and a rewrite must not change them.
//
// HPCPLAN_DENSE_GOLDEN_WRITE=FILE writes the lines instead (to record a deliberate change).
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <mutex>
#include <sstream>
#include <string>

#include "hpcplan/core/splitmix64.hpp"
#include "hpcplan/dense/dense_search.hpp"
#include "hpcplan/env/gog.hpp"
#include "hpcplan/env/occupancy_grid.hpp"
#include "support/dense_cases.hpp"

namespace {

using namespace hpcplan;
using test_support::Case;
using test_support::run_case;

constexpr int kCases = 96;

// Case i: its field, query and the second layout it runs on (ranks, threads, block sections).
Case draw_case(int i, int& ranks, int& threads, int& block_sections) {
  SplitMix64 rng(0xD0C5EED + static_cast<std::uint64_t>(i) * 7919);
  static const int extents[] = {0, 150, 37, 19, 11, 7, 5, 4, 3};
  const int d = 1 + static_cast<int>(rng.next_below(8));
  Case c;
  const bool occupancy = i % 2 == 1;
  const double density = i % 5 == 4 ? 0.55 + 0.2 * rng.next_unit() : 0.1 + 0.35 * rng.next_unit();
  if (!occupancy) {
    GogParams g;
    g.seed = rng.next();
    g.shift_v = static_cast<int>(rng.next_below(3));
    g.shift_p = static_cast<int>(rng.next_below(5));
    g.density = density;
    c.gog = std::make_unique<GogField>(d, extents[d], g);
  } else {
    // Sides that differ per axis (the engine pads the array to its bounding hypercube).
    std::vector<int> shape(d);
    for (int& s : shape) s = 2 + static_cast<int>(rng.next_below(extents[d] - 1));
    c.grid = std::make_unique<OccupancyGrid>(shape);
    std::vector<int> x(d, 0);
    for (std::uint64_t k = 0; k < c.grid->cells(); ++k) {
      std::uint64_t rest = k;
      for (int a = 0; a < d; ++a) {
        x[a] = static_cast<int>(rest % shape[a]);
        rest /= shape[a];
      }
      if (rng.next_unit() < density) c.grid->set_free(x, false);
    }
    c.grid->seal();
  }
  const ObstacleSource field = c.source();
  auto draw_free = [&](std::vector<int>& s) {
    s.assign(d, 0);
    for (int tries = 0; tries < 100000; ++tries) {
      for (int a = 0; a < d; ++a) s[a] = static_cast<int>(rng.next_below(field.size(a)));
      if (field.is_free(s)) return true;
    }
    return false;
  };
  dense::Query& q = c.query;
  if (!draw_free(q.start) || !draw_free(q.goal)) {
    q.start.clear();  // a field with no free cell: skipped (and recorded as such)
    return c;
  }
  q.algorithm = rng.next_below(2) ? dense::Algorithm::dijkstra : dense::Algorithm::bfs;
  q.connectivity = d <= kMaxFullConnectivityDims && rng.next_below(3) == 0
                       ? Connectivity::full
                       : Connectivity::seed_pairs;
  q.keep_path = true;
  ranks = 1 + static_cast<int>(rng.next_below(4));
  threads = 1 + static_cast<int>(rng.next_below(3));
  const int blocks = static_cast<int>(rng.next_below(4));
  block_sections = blocks == 0 ? -1 : blocks == 1 ? 0 : blocks - 1;
  return c;
}

TEST(DenseGolden, AnswersPathsAndCountsAreTheRecordedOnesOnEveryLayout) {
  const char* write = std::getenv("HPCPLAN_DENSE_GOLDEN_WRITE");
  std::vector<std::string> expected;
  if (!write) {
    std::ifstream in(HPCPLAN_DENSE_GOLDEN);
    ASSERT_TRUE(in) << "cannot read " << HPCPLAN_DENSE_GOLDEN;
    for (std::string l; std::getline(in, l);) expected.push_back(l);
    ASSERT_EQ(expected.size(), static_cast<std::size_t>(kCases));
  }
  std::ostringstream written;
  int compared = 0;
  for (int i = 0; i < kCases; ++i) {
    int ranks = 1, threads = 1, block_sections = -1;
    const Case c = draw_case(i, ranks, threads, block_sections);
    std::string line = "case " + std::to_string(i) + ": ";
    if (c.query.start.empty()) {
      line += "no free cell";
    } else {
      // Every fourth case a distance field (the goal still reported).
      const bool field_run = i % 4 == 2;
      const std::string one = run_case(c, 1, 1, -1, field_run);
      const std::string other = run_case(c, ranks, threads, block_sections, field_run);
      EXPECT_EQ(other, one) << "case " << i << " on " << ranks << " ranks x " << threads
                            << " threads, block sections " << block_sections;
      line += one;
      ++compared;
    }
    if (write) {
      written << line << "\n";
    } else {
      EXPECT_EQ(line, expected[i]);
    }
  }
  EXPECT_GT(compared, kCases * 3 / 4);  // nearly every case has free cells to run
  if (write) {
    std::ofstream out(write);
    out << written.str();
    ASSERT_TRUE(out.good()) << "cannot write " << write;
  }
}

}  // namespace
