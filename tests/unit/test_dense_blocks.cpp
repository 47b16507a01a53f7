// The dense engine's blocks over many ranks: when the ranks (times their threads) outnumber
// the layers of the last axis, the cut moves down an axis (slab_plan.hpp), blocks become pieces
// of layers, and a rank trades halos with every rank holding a section next to its own, over
// several axes. On 1 to 16 ranks (threads of this process over the paired test transport, which
// fails a run whose ranks do not name each other back as peers), every answer, path, count and
// distance field must be the one-rank one, for GOG fields and occupancy arrays, BFS and
// Dijkstra, both connectivities, dealt and contiguous blocks.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "hpcplan/core/splitmix64.hpp"
#include "support/dense_cases.hpp"

namespace {

using namespace hpcplan;
using test_support::Case;
using test_support::run_case;

Case gog_case(int d, int extent, std::uint64_t seed, dense::Algorithm a, Connectivity c) {
  Case k;
  GogParams g;
  g.seed = seed;
  k.gog = std::make_unique<GogField>(d, extent, g);
  dense::Query& q = k.query;
  q.start.assign(d, 0);
  q.goal.assign(d, extent - 1);
  for (long s = 0; !k.gog->is_free(q.start); ++s) ++q.start[s % d];
  for (long s = 0; !k.gog->is_free(q.goal); ++s) --q.goal[s % d];
  q.algorithm = a;
  q.connectivity = c;
  q.keep_path = true;
  return k;
}

// An array of uneven sides (the engine pads it to its bounding hypercube), a quarter blocked.
Case occupancy_case(std::vector<int> shape, std::uint64_t seed, dense::Algorithm a,
                    Connectivity c) {
  Case k;
  const int d = static_cast<int>(shape.size());
  k.grid = std::make_unique<OccupancyGrid>(shape);
  SplitMix64 rng(seed);
  std::vector<int> x(d, 0);
  for (std::uint64_t i = 0; i < k.grid->cells(); ++i) {
    std::uint64_t rest = i;
    for (int ax = 0; ax < d; ++ax) {
      x[ax] = static_cast<int>(rest % shape[ax]);
      rest /= shape[ax];
    }
    const bool corner =
        std::all_of(x.begin(), x.end(), [](int v) { return v == 0; }) ||
        std::equal(x.begin(), x.end(), shape.begin(), [](int v, int s) { return v == s - 1; });
    if (!corner && rng.next_unit() < 0.25) k.grid->set_free(x, false);
  }
  k.grid->seal();
  k.query.start.assign(d, 0);
  for (int ax = 0; ax < d; ++ax) k.query.goal.push_back(shape[ax] - 1);
  k.query.algorithm = a;
  k.query.connectivity = c;
  k.query.keep_path = true;
  return k;
}

TEST(DenseBlocks, SixteenRanksOutnumberTheLayersAndEveryRankHoldsAPieceOfALayer) {
  // 5D extent 8: 8 layers, 16 ranks; the cut must go down two axes (64 sections are fewer than
  // 16 per rank), and the ranks trade over several axes.
  const Case c = gog_case(5, 8, 3, dense::Algorithm::bfs, Connectivity::seed_pairs);
  dense::Result one, many;
  const std::string a = run_case(c, 1, 1, -1, false, &one);
  const std::string b = run_case(c, 16, 1, -1, false, &many);
  EXPECT_EQ(b, a);
  ASSERT_EQ(one.status, Status::solved);
  EXPECT_EQ(one.figures.cut_axis, 4);  // one worker: layers
  EXPECT_EQ(many.figures.cut_axis, 2);
  ASSERT_EQ(many.figures.rank_sections.size(), 16u);
  for (int s : many.figures.rank_sections) EXPECT_GT(s, 0);
  ASSERT_EQ(many.figures.rank_peers.size(), 16u);
  EXPECT_GT(*std::max_element(many.figures.rank_peers.begin(), many.figures.rank_peers.end()), 2)
      << "blocks cut over several axes have peers beyond the two slab neighbours";
  EXPECT_GT(many.figures.halo_bytes, 0u);
}

TEST(DenseBlocks, OneToSixteenRanksGiveTheOneRankAnswer) {
  using A = dense::Algorithm;
  using C = Connectivity;
  std::vector<std::pair<std::string, Case>> cases;
  cases.emplace_back("4D GOG BFS", gog_case(4, 12, 11, A::bfs, C::seed_pairs));
  cases.emplace_back("5D GOG Dijkstra", gog_case(5, 7, 5, A::dijkstra, C::seed_pairs));
  cases.emplace_back("4D GOG BFS full", gog_case(4, 9, 2, A::bfs, C::full));
  cases.emplace_back("6D GOG BFS", gog_case(6, 5, 8, A::bfs, C::seed_pairs));
  cases.emplace_back("4D array Dijkstra full",
                     occupancy_case({9, 11, 7, 10}, 21, A::dijkstra, C::full));
  cases.emplace_back("5D array BFS", occupancy_case({6, 5, 7, 4, 6}, 4, A::bfs, C::seed_pairs));
  SplitMix64 rng(0xB10C5);
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const auto& [name, c] = cases[i];
    for (const bool field_run : {false, true}) {
      if (field_run && i % 2) continue;  // a distance field on every other case
      const std::string one = run_case(c, 1, 1, -1, field_run);
      ASSERT_EQ(one.rfind("solved", 0), 0u) << name << ": " << one;
      for (int ranks = 2; ranks <= 16; ++ranks) {
        // Mostly one thread a rank (the deepest cuts); a drawn layout every third run.
        int threads = 1, blocks = -1;
        if (ranks % 3 == 0) {
          threads = 1 + static_cast<int>(rng.next_below(2));
          blocks = static_cast<int>(rng.next_below(3));  // dealt by default or of 1, contiguous
        }
        EXPECT_EQ(run_case(c, ranks, threads, blocks, field_run), one)
            << name << (field_run ? " (distance field)" : "") << " on " << ranks << " ranks x "
            << threads << " threads, block sections " << blocks;
      }
    }
  }
}

}  // namespace
