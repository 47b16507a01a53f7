// The dense engine's OpenMP threads, for ThreadSanitizer (scripts/test.sh builds this file
// with clang and LLVM's OpenMP runtime, whose Archer tool tells TSan about OpenMP's barriers):
// several threads share one slab's store and hand each other outboxes between barriers, and a
// stop requested from another thread ends the run. Every thread count must give the one-thread
// answer, path and counts.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <functional>
#include <mutex>
#include <set>
#include <string>
#include <thread>

#include "hpcplan/core/error.hpp"
#include "hpcplan/dense/dense_search.hpp"
#include "hpcplan/plan/grid_planner.hpp"
#include "support/cancel_handshake.hpp"
#include "support/in_process_ranks.hpp"

namespace {

using namespace hpcplan;

dense::Query corner_query(const GogField& field, dense::Algorithm a, int threads) {
  const int d = field.dims(), e = field.extent();
  dense::Query q;
  q.start.assign(d, 0);
  q.goal.assign(d, e - 1);
  for (long s = 0; !field.is_free(q.start); ++s) ++q.start[s % d];
  for (long s = 0; !field.is_free(q.goal); ++s) --q.goal[s % d];
  q.algorithm = a;
  q.threads = threads;
  q.keep_path = true;
  return q;
}

// The answer, path and counts that must not depend on threads or ranks.
void expect_same_answer(const dense::Result& got, const dense::Result& want) {
  EXPECT_EQ(got.status, want.status);
  EXPECT_EQ(got.cost, want.cost);
  EXPECT_EQ(got.path, want.path);
  EXPECT_EQ(got.counters.expanded, want.counters.expanded);
  EXPECT_EQ(got.counters.generated, want.counters.generated);
}

// Each rank's result of `field` searched on `ranks` in-process ranks (support/
// in_process_ranks.hpp) with the query `query(rank)`, and each rank's error ("" if none).
struct RankRuns {
  std::vector<dense::Result> results;
  std::vector<std::string> errors;
};
RankRuns run_ranks(const GogField& field, int ranks,
                   const std::function<dense::Query(int)>& query) {
  test_support::InProcessRanks hub(ranks);
  RankRuns runs{std::vector<dense::Result>(ranks), std::vector<std::string>(ranks)};
  hub.run([&](int rank) {
    try {
      test_support::InProcessTransport tr(hub, rank);
      runs.results[rank] = dense::search(field, query(rank), tr);
    } catch (const std::exception& e) {
      runs.errors[rank] = e.what();
    }
  });
  return runs;
}

// Checkpoints are written by the master thread between two barriers while the others wait,
// and read before the threads start: an interrupted run restarted on 3 threads, from a
// checkpoint written at every boundary until it ends, gives the uninterrupted answer.
TEST(DenseThreads, CheckpointsAreWrittenBetweenBarriers) {
  GogParams gp;
  gp.seed = 12;
  const GogField field(3, 24, gp);
  dense::LocalTransport local;
  const std::string file = ::testing::TempDir() + "hpcplan-dense-thread-ckpt";
  for (const dense::Algorithm a : {dense::Algorithm::bfs, dense::Algorithm::dijkstra}) {
    const dense::Result whole = dense::search(field, corner_query(field, a, 3), local);
    dense::Query q = corner_query(field, a, 3);
    q.checkpointing.path = file;
    q.checkpointing.interrupted = [] { return true; };
    dense::Result r;
    int legs = 0;
    for (; legs < 1000; ++legs) {
      r = dense::search(field, q, local);
      if (r.status != Status::interrupted) break;
      // The next leg reads what this one wrote and writes the other file.
      q.checkpointing.restart = q.checkpointing.path;
      q.checkpointing.path = legs % 2 ? file : file + ".b";
    }
    EXPECT_GT(legs, 5);
    EXPECT_EQ(r.status, whole.status);
    EXPECT_EQ(r.path, whole.path);
    EXPECT_EQ(r.counters.expanded, whole.counters.expanded);
    EXPECT_EQ(r.counters.generated, whole.counters.generated);
  }
  std::remove(file.c_str());
  std::remove((file + ".b").c_str());
}

TEST(DenseThreads, EveryThreadCountGivesTheOneThreadAnswer) {
  for (const auto& [d, extent] : std::vector<std::pair<int, int>>{{2, 90}, {3, 24}, {4, 12}})
    for (const dense::Algorithm a : {dense::Algorithm::bfs, dense::Algorithm::dijkstra}) {
      GogParams gp;
      gp.seed = 7 + d;
      const GogField field(d, extent, gp);
      dense::LocalTransport local;
      const dense::Result one = dense::search(field, corner_query(field, a, 1), local);
      ASSERT_EQ(one.status, Status::solved);
      for (int threads : {2, 3, 4})
        for (int block_sections : {-1, 0, 1}) {
          dense::Query q = corner_query(field, a, threads);
          q.block_sections = block_sections;
          const dense::Result r = dense::search(field, q, local);
          SCOPED_TRACE(::testing::Message()
                       << d << "D threads " << threads << " blocks " << block_sections);
          expect_same_answer(r, one);
          EXPECT_GE(r.figures.threads, 1);
        }
    }
}

// The superstep driver's rank protocol with threads inside each rank: two ranks of two
// threads each (threads of this process over the paired test transport, so ThreadSanitizer
// sees the halo swap, the reductions and the barriers together) give the one-rank answer,
// path and counts; and an interrupted two-rank run restarts from its two files (one per rank,
// named by the engine) to the same answer.
TEST(DenseThreads, TwoInProcessRanksOfTwoThreadsGiveTheOneRankAnswer) {
  GogParams gp;
  gp.seed = 5;
  const GogField field(3, 28, gp);
  const std::string file = ::testing::TempDir() + "hpcplan-dense-two-ranks";
  for (const dense::Algorithm a : {dense::Algorithm::bfs, dense::Algorithm::dijkstra}) {
    dense::LocalTransport local;
    const dense::Result one = dense::search(field, corner_query(field, a, 1), local);
    ASSERT_EQ(one.status, Status::solved);
    auto run_two = [&](const std::function<void(dense::Query&)>& edit) {
      const RankRuns runs = run_ranks(field, 2, [&](int) {
        dense::Query q = corner_query(field, a, 2);
        q.block_sections = 2;  // several blocks per rank: faces between threads and ranks
        edit(q);
        return q;
      });
      EXPECT_EQ(runs.errors[0] + runs.errors[1], "");
      EXPECT_EQ(runs.results[0].status, runs.results[1].status);
      return runs.results[0];
    };
    const dense::Result two = run_two([](dense::Query&) {});
    EXPECT_EQ(two.figures.ranks, 2);
    EXPECT_GT(two.figures.halo_bytes, 0u);
    expect_same_answer(two, one);
    EXPECT_EQ(two.figures.levels, one.figures.levels);
    // Interrupted at its first boundary, then restarted from FILE.r0 and FILE.r1.
    const dense::Result stopped = run_two([&](dense::Query& q) {
      q.checkpointing.path = file;
      q.checkpointing.interrupted = [] { return true; };
    });
    ASSERT_EQ(stopped.status, Status::interrupted);
    for (const char* r : {".r0", ".r1"})
      ASSERT_TRUE(std::filesystem::exists(file + r)) << file << r;
    const dense::Result restarted =
        run_two([&](dense::Query& q) { q.checkpointing.restart = file; });
    EXPECT_EQ(restarted.status, one.status);
    EXPECT_EQ(restarted.path, one.path);
    EXPECT_EQ(restarted.counters.expanded, one.counters.expanded);
    EXPECT_EQ(restarted.counters.generated, one.counters.generated);
    std::remove((file + ".r0").c_str());
    std::remove((file + ".r1").c_str());
  }
  // One rank cannot write the checkpoint that ends an interrupted run (its file is a folder):
  // every rank learns of it and throws, none waits for the failed one.
  const std::string blocked = file + "-blocked";
  std::filesystem::create_directories(blocked + ".r1");
  auto interrupted = [&](int) {
    dense::Query q = corner_query(field, dense::Algorithm::bfs, 2);
    q.checkpointing.path = blocked;
    q.checkpointing.interrupted = [] { return true; };
    return q;
  };
  const std::vector<std::string> errors = run_ranks(field, 2, interrupted).errors;
  EXPECT_NE(errors[1].find(blocked + ".r1"), std::string::npos) << errors[1];
  EXPECT_NE(errors[0].find("another rank failed"), std::string::npos) << errors[0];
  std::filesystem::remove_all(blocked + ".r1");
  std::remove((blocked + ".r0").c_str());
}

// Blocks that are pieces of layers (3 ranks x 2 threads outnumber the 10 layers' 16 per worker,
// so the cut moves down an axis): the threads' merged outboxes to several peers, and the swap
// over the peer list, under ThreadSanitizer; the one-rank answer, path and counts.
TEST(DenseThreads, ThreeInProcessRanksOfTwoThreadsOnPiecesOfLayers) {
  GogParams gp;
  gp.seed = 9;
  const GogField field(4, 10, gp);
  for (const dense::Algorithm a : {dense::Algorithm::bfs, dense::Algorithm::dijkstra}) {
    dense::LocalTransport local;
    const dense::Result one = dense::search(field, corner_query(field, a, 1), local);
    ASSERT_EQ(one.status, Status::solved);
    const RankRuns runs = run_ranks(field, 3, [&](int) { return corner_query(field, a, 2); });
    EXPECT_EQ(runs.errors[0] + runs.errors[1] + runs.errors[2], "");
    const dense::Result& three = runs.results[0];
    EXPECT_LT(three.figures.cut_axis, 3);
    EXPECT_GT(three.figures.halo_bytes, 0u);
    expect_same_answer(three, one);
  }
}

// The run's stop condition (asked on the calling thread once per level) says the run is under
// way and holds it until another thread has cancelled: the run is then stopped mid-search on
// any machine, at the next poll of the token by any thread.
TEST(DenseThreads, AnotherThreadCancelsARun) {
  GogParams gp;
  const GogField field(4, 48, gp);
  for (const dense::Algorithm a : {dense::Algorithm::bfs, dense::Algorithm::dijkstra}) {
    test_support::CancelHandshake handshake;
    dense::Query q = corner_query(field, a, 2);
    q.stop = Stop(handshake.token());
    q.stop.also_when(handshake.condition());
    const std::jthread canceller = handshake.canceller();
    dense::LocalTransport local;
    const dense::Result r = dense::search(field, q, local);
    EXPECT_EQ(r.status, Status::cancelled);
    EXPECT_TRUE(r.path.empty());
  }
}

// A stop condition (OMPL's termination condition, say) runs on one thread only, as Stop's
// contract says: the OpenMP threads poll the token and deadline, the calling thread alone the
// condition. Recorded under a mutex, so the test itself is race-free either way.
TEST(DenseThreads, TheStopConditionRunsOnTheCallingThreadOnly) {
  GogParams gp;
  // Wide enough that each thread expands more than 1,024 entries in a level: the threads
  // poll once per 1,024.
  const GogField field(4, 48, gp);
  for (const dense::Algorithm a : {dense::Algorithm::bfs, dense::Algorithm::dijkstra}) {
    std::mutex m;
    std::set<std::thread::id> callers;
    int calls = 0;
    dense::Query q = corner_query(field, a, 2);
    q.block_sections = 1;  // both threads busy every level
    q.stop.also_when([&] {
      const std::lock_guard lock(m);
      callers.insert(std::this_thread::get_id());
      ++calls;
      return false;
    });
    dense::LocalTransport local;
    const dense::Result r = dense::search(field, q, local);
    EXPECT_EQ(r.status, Status::solved);
    EXPECT_GT(calls, 0);
    EXPECT_EQ(callers, std::set<std::thread::id>{std::this_thread::get_id()});
  }
}

// A build compiled for fewer dimensions (-DHPCPLAN_DENSE_DIMS; the ThreadSanitizer tree has 4)
// refuses the next one in one line (validate(), before any rank communicates), and the
// planner's automatic choice runs it on the sparse engine instead. In a full build (16) there is no
// such dimension: skipped.
TEST(DenseBuild, ADimensionNotCompiledIsRefusedAndAutoPicksTheSparseEngine) {
  const int compiled = dense::compiled_dims();
  if (compiled >= 16) GTEST_SKIP() << "every dimension is compiled in this build";
  GridProblem p;
  p.dims = compiled + 1;
  p.extent = 5;
  GridSearchOptions o;
  o.algorithm = GridAlgorithm::bfs;
  o.engine = GridEngine::dense;
  try {
    solve_grid(p, o);
    FAIL() << "the dense engine ran " << p.dims << "D in a build compiled for " << compiled;
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), "this build compiles the dense engine for 1 to " +
                                         std::to_string(compiled) +
                                         " dimensions (HPCPLAN_DENSE_DIMS), not " +
                                         std::to_string(p.dims) + "; use --engine sparse");
  }
  o.engine = GridEngine::sparse;
  const GridReport sparse = solve_grid(p, o);
  o.engine = GridEngine::automatic;
  const GridReport automatic = solve_grid(p, o);
  EXPECT_EQ(automatic.options.engine, "sparse");
  EXPECT_EQ(automatic.result.status, sparse.result.status);
  EXPECT_EQ(automatic.result.hops, sparse.result.hops);
  // A checkpoint needs the dense engine: the refusal names the build, not the budget.
  o.checkpoint = ::testing::TempDir() + "hpcplan-dense-build-ckpt";
  try {
    solve_grid(p, o);
    FAIL() << "a checkpointed run was accepted on the sparse engine";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("which this build compiles for 1 to " +
                                         std::to_string(compiled) + " dimensions"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
