// The dense lattice engine against the independent oracle (textbook BFS and Dijkstra over
// coordinate vectors) and against the sparse engine, from 1D to 8D, extents that do not fill
// the 8 x 8 tiles, 1 to 4 threads (so paths cross sub-slab faces), both connectivities; and
// its kernel, its slab plan, its budget refusal, its progress line and its checkpoints.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>

#include <unistd.h>

#include "hpcplan/core/error.hpp"
#include "hpcplan/core/splitmix64.hpp"
#include "hpcplan/dense/dense_search.hpp"
#include "hpcplan/dense/slab_plan.hpp"
#include "hpcplan/dense/tile_moves.hpp"
#include "hpcplan/plan/grid_planner.hpp"
#include "lattice_oracle.hpp"

namespace {

using namespace hpcplan;

// Extents that leave the tiles partly padded (8 x 8 tiles on axes 0 and 1; rows of 64 in 1D),
// small enough for the oracle.
int extent_for(int d) {
  static const int extents[] = {0, 150, 37, 19, 11, 7, 5, 4, 3};
  return extents[d];
}

struct Instance {
  GogParams gog;
  int dims = 2, extent = 10;
  std::vector<int> start, goal;
};

Instance random_instance(std::uint64_t seed, int d) {
  SplitMix64 rng(seed);
  Instance in;
  in.dims = d;
  in.extent = extent_for(d);
  in.gog.seed = rng.next();
  in.gog.shift_v = static_cast<int>(rng.next_below(3));
  in.gog.shift_p = static_cast<int>(rng.next_below(5));
  // One in four dense enough to cut start from goal often (no_path against the oracle).
  in.gog.density = seed % 4 == 3 ? 0.6 + 0.2 * rng.next_unit() : 0.15 + 0.4 * rng.next_unit();
  const GogField field(d, in.extent, in.gog);
  auto draw_free = [&] {
    for (;;) {
      std::vector<int> s(d);
      for (auto& c : s) c = static_cast<int>(rng.next_below(in.extent));
      if (field.is_free(s)) return s;
    }
  };
  in.start = draw_free();
  in.goal = draw_free();
  return in;
}

dense::Result run_dense(const GogField& field, const Instance& in, dense::Algorithm a, int threads,
                        Connectivity c = Connectivity::seed_pairs) {
  dense::Query q;
  q.start = in.start;
  q.goal = in.goal;
  q.algorithm = a;
  q.connectivity = c;
  q.threads = threads;
  q.keep_path = true;
  dense::LocalTransport local;
  return dense::search(field, q, local);
}

void expect_same(const dense::Result& a, const dense::Result& b, const std::string& what) {
  EXPECT_EQ(a.status, b.status) << what;
  EXPECT_EQ(a.cost, b.cost) << what;
  EXPECT_EQ(a.hops, b.hops) << what;
  EXPECT_EQ(a.path, b.path) << what;
  EXPECT_EQ(a.counters.expanded, b.counters.expanded) << what;
  EXPECT_EQ(a.counters.generated, b.counters.generated) << what;
  EXPECT_EQ(a.figures.levels, b.figures.levels) << what;
}

class DenseOracle : public ::testing::TestWithParam<std::tuple<int, int, bool>> {};

TEST_P(DenseOracle, MatchesTheOracleForEveryThreadCount) {
  const auto [d, trial, full] = GetParam();
  if (full && d > kMaxFullConnectivityDims)
    GTEST_SKIP() << "full connectivity is limited to " << kMaxFullConnectivityDims << "D";
  const Instance in = random_instance(5000 * d + trial + (full ? 333 : 0), d);
  const GogField field(d, in.extent, in.gog);
  const oracle::Lattice o(field, full);
  const oracle::Answer best = o.dijkstra(in.start, in.goal);
  const oracle::Answer fewest = o.bfs(in.start, in.goal);
  const Connectivity c = full ? Connectivity::full : Connectivity::seed_pairs;
  const std::string what = std::to_string(d) + "D trial " + std::to_string(trial);

  const dense::Result bfs = run_dense(field, in, dense::Algorithm::bfs, 1, c);
  const dense::Result dij = run_dense(field, in, dense::Algorithm::dijkstra, 1, c);
  if (!fewest.reachable) {
    EXPECT_EQ(bfs.status, Status::no_path) << what;
    EXPECT_EQ(dij.status, Status::no_path) << what;
  } else {
    ASSERT_EQ(bfs.status, Status::solved) << what;
    ASSERT_EQ(dij.status, Status::solved) << what;
    EXPECT_EQ(static_cast<std::int64_t>(bfs.hops), fewest.hops) << what;
    EXPECT_NEAR(dij.cost, best.cost, 1e-9 * (1 + best.cost)) << what;
    for (const dense::Result* r : {&bfs, &dij}) {
      ASSERT_EQ(r->path.front(), in.start) << what;
      ASSERT_EQ(r->path.back(), in.goal) << what;
      EXPECT_EQ(r->path.size(), r->hops + 1) << what;
      std::size_t illegal = 0;
      const double length = o.path_length(r->path, &illegal);
      ASSERT_GE(length, 0) << what << ": illegal move at step " << illegal;
      EXPECT_NEAR(length, r->cost, 1e-9) << what;
    }
  }
  // The same answer, path and counts whatever the number of threads (sub-slab faces).
  for (int threads : {2, 3, 4}) {
    expect_same(run_dense(field, in, dense::Algorithm::bfs, threads, c), bfs,
                what + " bfs, threads " + std::to_string(threads));
    expect_same(run_dense(field, in, dense::Algorithm::dijkstra, threads, c), dij,
                what + " dijkstra, threads " + std::to_string(threads));
  }
}

INSTANTIATE_TEST_SUITE_P(SeedRule, DenseOracle,
                         ::testing::Combine(::testing::Range(1, 9), ::testing::Range(0, 6),
                                            ::testing::Values(false)));
INSTANTIATE_TEST_SUITE_P(FullConnectivity, DenseOracle,
                         ::testing::Combine(::testing::Range(1, 5), ::testing::Range(0, 3),
                                            ::testing::Values(true)));

// The dense and the sparse engine through the planner, on the default problems of the CLI:
// BFS hops and Dijkstra costs equal, counted states equal up to the sparse engine stopping
// inside the goal's level.
TEST(DenseEngine, AgreesWithTheSparseEngineThroughThePlanner) {
  for (const auto& [d, extent] :
       std::vector<std::pair<int, int>>{{2, 100}, {3, 40}, {4, 13}, {6, 6}})
    for (const GridAlgorithm a : {GridAlgorithm::bfs, GridAlgorithm::dijkstra}) {
      GridProblem p;
      p.dims = d;
      p.extent = extent;
      GridSearchOptions o;
      o.algorithm = a;
      o.keep_path = true;
      o.engine = GridEngine::sparse;
      const GridReport sparse = solve_grid(p, o);
      o.engine = GridEngine::dense;
      const GridReport dense = solve_grid(p, o);
      const std::string what = std::to_string(d) + "D " + std::string(to_string(a));
      ASSERT_EQ(dense.options.engine, "dense") << what;
      ASSERT_TRUE(dense.dense.has_value()) << what;
      ASSERT_EQ(sparse.result.status, Status::solved) << what;
      ASSERT_EQ(dense.result.status, Status::solved) << what;
      EXPECT_EQ(dense.result.hops, sparse.result.hops) << what;
      if (a == GridAlgorithm::dijkstra) {
        EXPECT_NEAR(dense.result.cost, sparse.result.cost, 1e-9 * sparse.result.cost) << what;
      }
      EXPECT_EQ(dense.result.path.front(), sparse.result.path.front()) << what;
      EXPECT_EQ(dense.result.path.back(), sparse.result.path.back()) << what;
      // The sparse BFS stops when it takes the goal; the dense one after the goal's level.
      EXPECT_GE(dense.result.counters.expanded + 64, sparse.result.counters.expanded) << what;
      EXPECT_LE(dense.result.counters.expanded, dense.dense->free_states) << what;
    }
}

// The unrolled seed-rule kernel and the move table give the same targets and move counts for
// every tile of a field (1D to 8D; rows and 8 x 8 tiles).
template <int D, int K>
void compare_kernels(int extent, std::uint64_t seed) {
  GogParams gp;
  gp.seed = seed;
  gp.density = 0.3;
  const GogField field(D, extent, gp);
  const dense::TileLayout layout(D, extent, K);
  const dense::FreeWindows windows(field, layout, 2);
  const dense::TableMoves table(layout, 2);
  std::int64_t W[kMaxDims];
  for (int a = 0; a < D; ++a) W[a] = layout.stride(a);
  SplitMix64 rng(seed);
  for (std::uint64_t tile = 0; tile < layout.tile_count(); ++tile) {
    int t[kMaxDims];
    layout.tile_coords(tile, t);
    dense::FreeWindows::At at;
    windows.locate(t, at);
    const dense::Word f = rng.next() & windows.mask(at, dense::FreeWindows::window(0, 0), at.tau);
    for (const bool split : {false, true}) {
      std::map<std::pair<std::int64_t, int>, dense::Word> a, b;
      auto into = [](auto& m) {
        return [&m](std::int64_t delta, dense::Word bits, int axes) { m[{delta, axes}] |= bits; };
      };
      const std::uint64_t ga =
          split
              ? dense::SeedMoves<D, K>::template expand<true>(f, at, windows.stride(), W, into(a))
              : dense::SeedMoves<D, K>::template expand<false>(f, at, windows.stride(), W, into(a));
      const std::uint64_t gb = split ? table.expand<K, true>(f, at, windows.stride(), W, into(b))
                                     : table.expand<K, false>(f, at, windows.stride(), W, into(b));
      ASSERT_EQ(ga, gb) << D << "D tile " << tile;
      ASSERT_EQ(a, b) << D << "D tile " << tile << (split ? " split" : "");
    }
  }
}

TEST(DenseKernel, SeedRuleEqualsTheMoveTable) {
  compare_kernels<1, 1>(150, 3);
  compare_kernels<2, 1>(70, 4);
  compare_kernels<2, 2>(21, 5);
  compare_kernels<3, 1>(70, 6);
  compare_kernels<3, 2>(13, 7);
  compare_kernels<4, 2>(9, 8);
  compare_kernels<5, 2>(6, 9);
  compare_kernels<8, 2>(3, 10);
}

// The kernel's move count is the number of legal moves out of the states given: counted here
// state by state with the field formula.
TEST(DenseKernel, CountsEveryLegalMoveOnce) {
  GogParams gp;
  gp.seed = 11;
  gp.density = 0.35;
  const GogField field(4, 10, gp);
  const oracle::Lattice o(field, false);
  const dense::TileLayout layout(4, 10, 2);
  const dense::FreeWindows windows(field, layout, 2);
  std::int64_t W[kMaxDims];
  for (int a = 0; a < 4; ++a) W[a] = layout.stride(a);
  std::uint64_t kernel = 0, counted = 0;
  for (std::uint64_t tile = 0; tile < layout.tile_count(); ++tile) {
    int t[kMaxDims];
    layout.tile_coords(tile, t);
    dense::FreeWindows::At at;
    windows.locate(t, at);
    const dense::Word f = windows.mask(at, dense::FreeWindows::window(0, 0), at.tau);
    kernel += dense::SeedMoves<4, 2>::expand<false>(f, at, windows.stride(), W,
                                                    [](std::int64_t, dense::Word, int) {});
    for (dense::Word w = f; w; w &= w - 1) {
      int c[kMaxDims];
      layout.cell(tile, std::countr_zero(w), c);
      o.neighbours(std::vector<int>(c, c + 4), [&](std::span<const int>, double) { ++counted; });
    }
  }
  EXPECT_GT(counted, 1000u);
  EXPECT_EQ(kernel, counted);
}

// Tile masks agree with the field formula cell by cell, padding cells included (never free).
TEST(DenseKernel, WindowMasksAreTheFieldFormula) {
  for (const auto& [d, extent, k] : std::vector<std::tuple<int, int, int>>{
           {1, 100, 1}, {2, 21, 2}, {2, 70, 1}, {3, 11, 2}, {5, 5, 2}}) {
    GogParams gp;
    gp.seed = 17;
    const GogField field(d, extent, gp);
    const dense::TileLayout layout(d, extent, k);
    const dense::FreeWindows windows(field, layout, 2);
    for (std::uint64_t tile = 0; tile < layout.tile_count(); ++tile) {
      int t[kMaxDims];
      layout.tile_coords(tile, t);
      const dense::Word m = windows.free_mask(t);
      for (int bit = 0; bit < 64; ++bit) {
        int c[kMaxDims];
        layout.cell(tile, bit, c);
        bool inside = true;
        for (int a = 0; a < d; ++a) inside = inside && c[a] < extent;
        const bool free = inside && field.is_free(std::span<const int>(c, d));
        ASSERT_EQ(((m >> bit) & 1) != 0, free) << d << "D tile " << tile << " bit " << bit;
        if (inside) {
          ASSERT_EQ(layout.tile_of(std::span<const int>(c, d)), tile);
        }
      }
    }
  }
}

// Slabs: free states per layer are the exact counts, and balanced cuts are contiguous,
// cover every layer and give each part at least one layer while there are enough.
TEST(DenseSlabs, FreeStatesPerLayerAreExactAndCutsBalance) {
  GogParams gp;
  gp.seed = 23;
  const GogField field(3, 17, gp);
  const dense::TileLayout layout(3, 17, 2);
  const std::vector<double> layers = dense::free_states_per_layer(field, layout);
  ASSERT_EQ(layers.size(), 17u);
  for (int z = 0; z < 17; ++z) {
    double count = 0;
    for (int x = 0; x < 17; ++x)
      for (int y = 0; y < 17; ++y) count += field.is_free(std::vector<int>{x, y, z});
    EXPECT_EQ(layers[z], count) << "layer " << z;
  }
  for (int parts : {1, 2, 3, 4, 17, 20}) {
    const std::vector<int> b = dense::balanced_slabs(layers, parts);
    ASSERT_EQ(b.size(), static_cast<std::size_t>(parts + 1));
    EXPECT_EQ(b.front(), 0);
    EXPECT_EQ(b.back(), 17);
    for (int j = 0; j < parts; ++j) {
      EXPECT_LE(b[j], b[j + 1]);
      if (parts <= 17) {
        EXPECT_LT(b[j], b[j + 1]) << parts << " parts";
      }
    }
  }
  // Two parts of a uniform weight split in the middle.
  EXPECT_EQ(dense::balanced_slabs(std::vector<double>(10, 1.0), 2), (std::vector<int>{0, 5, 10}));
}

// A goal walled off from the start: no_path, proved by exhausting the reachable set.
TEST(DenseEngine, AWalledOffGoalIsNoPath) {
  for (std::uint64_t seed = 1; seed < 200; ++seed) {
    Instance in = random_instance(seed * 4 + 3, 3);
    const GogField field(3, in.extent, in.gog);
    const oracle::Lattice o(field, false);
    if (o.bfs(in.start, in.goal).reachable) continue;
    for (const dense::Algorithm a : {dense::Algorithm::bfs, dense::Algorithm::dijkstra}) {
      const dense::Result r = run_dense(field, in, a, 2);
      EXPECT_EQ(r.status, Status::no_path);
      EXPECT_TRUE(r.path.empty());
      EXPECT_GT(r.counters.expanded, 0u);
    }
    return;
  }
  FAIL() << "no walled-off instance found";
}

// Start = goal: solved with no move.
TEST(DenseEngine, StartAtTheGoalIsZeroMoves) {
  const GogField field(3, 10, {});
  Instance in;
  in.dims = 3;
  in.extent = 10;
  in.start = in.goal = {0, 0, 0};
  ASSERT_TRUE(field.is_free(in.start));
  for (const dense::Algorithm a : {dense::Algorithm::bfs, dense::Algorithm::dijkstra}) {
    const dense::Result r = run_dense(field, in, a, 1);
    EXPECT_EQ(r.status, Status::solved);
    EXPECT_EQ(r.hops, 0u);
    EXPECT_EQ(r.cost, 0.0);
  }
}

// Over the budget: refused before allocating, one line naming the bytes needed and the budget.
TEST(DenseEngine, RefusesAQueryOverItsBudget) {
  const GogField field(5, 30, {});
  dense::Query q;
  q.start.assign(5, 0);
  q.goal.assign(5, 0);
  for (long s = 0; !field.is_free(q.start); ++s) ++q.start[s % 5];
  q.goal = q.start;
  q.memory_budget = 1'000'000;
  const std::uint64_t needed = dense::planned_bytes(field, q, 1);
  ASSERT_GT(needed, q.memory_budget);
  dense::LocalTransport local;
  try {
    dense::search(field, q, local);
    FAIL() << "no refusal";
  } catch (const InputError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find(std::to_string(needed) + " bytes"), std::string::npos) << m;
    EXPECT_NE(m.find("1000000 bytes"), std::string::npos) << m;
    EXPECT_EQ(m.find('\n'), std::string::npos) << m;
  }
  // A budget it fits runs; the bytes it used stay within the plan and its frontier lists.
  q.memory_budget = needed + 1;
  const dense::Result r = dense::search(field, q, local);
  EXPECT_EQ(r.status, Status::solved);
  EXPECT_GE(r.figures.bytes_per_rank, r.figures.bytes_needed);
  EXPECT_LE(r.figures.bytes_needed, needed);
}

// The progress line: level, states reached of the lattice's free states, rate, time left.
TEST(DenseEngine, ShowsAProgressLineWhenAsked) {
  ::setenv("HPCPLAN_PROGRESS", "1", 1);
  const GogField field(4, 20, {});
  Instance in;
  in.start.assign(4, 0);
  in.goal.assign(4, 19);
  for (long s = 0; !field.is_free(in.start); ++s) ++in.start[s % 4];
  for (long s = 0; !field.is_free(in.goal); ++s) --in.goal[s % 4];
  dense::Query q;
  q.start = in.start;
  q.goal = in.goal;
  q.progress_label = "test bfs";
  q.progress_after_s = 0.0;
  dense::LocalTransport local;
  ::testing::internal::CaptureStderr();
  const dense::Result r = dense::search(field, q, local);
  const std::string err = ::testing::internal::GetCapturedStderr();
  ::unsetenv("HPCPLAN_PROGRESS");
  EXPECT_EQ(r.status, Status::solved);
  EXPECT_NE(err.find("test bfs: level 1,"), std::string::npos) << err;
  EXPECT_NE(err.find("free states reached"), std::string::npos) << err;
  EXPECT_NE(err.find("states/s"), std::string::npos) << err;
  EXPECT_NE(err.find("s left"), std::string::npos) << err;
  // Without the request: silent.
  ::testing::internal::CaptureStderr();
  dense::search(field, q, local);
  EXPECT_EQ(::testing::internal::GetCapturedStderr(), "");
}

// A stop request ends a run at the next chunk of a level: cancelled, no path.
TEST(DenseEngine, StopsWhenCancelled) {
  const GogField field(5, 24, {});
  Instance in;
  in.start.assign(5, 0);
  in.goal.assign(5, 23);
  for (long s = 0; !field.is_free(in.start); ++s) ++in.start[s % 5];
  for (long s = 0; !field.is_free(in.goal); ++s) --in.goal[s % 5];
  std::stop_source source;
  source.request_stop();
  dense::Query q;
  q.start = in.start;
  q.goal = in.goal;
  q.stop = Stop(source.get_token());
  dense::LocalTransport local;
  for (const dense::Algorithm a : {dense::Algorithm::bfs, dense::Algorithm::dijkstra}) {
    q.algorithm = a;
    const dense::Result r = dense::search(field, q, local);
    EXPECT_EQ(r.status, Status::cancelled);
    EXPECT_TRUE(r.path.empty());
  }
}

// Checkpoints (dense_checkpoint.hpp): a run interrupted after k levels or buckets, with its
// checkpoint written there, and restarted from it, ends with the uninterrupted run's answer,
// path and counts; so does a chain of such restarts, for every k until the run ends.
class DenseCheckpoint : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           ("hpcplan-dense-ckpt-" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  std::string file(const std::string& name) const { return (dir_ / name).string(); }
  std::filesystem::path dir_;
};

// Asks for the end at its `at`-th call (once per level or bucket).
std::function<bool()> interrupt_at(int at) {
  auto calls = std::make_shared<int>(0);
  return [calls, at] { return ++*calls == at; };
}

TEST_F(DenseCheckpoint, AnInterruptedRunRestartsToTheSameAnswer) {
  int interrupted = 0, compared = 0;
  for (int d = 2; d <= 4; ++d)
    for (std::uint64_t seed = 1; seed <= 2; ++seed) {
      const Instance in = random_instance(seed * 7919 + static_cast<std::uint64_t>(d), d);
      const GogField field(d, in.extent, in.gog);
      for (const dense::Algorithm a : {dense::Algorithm::bfs, dense::Algorithm::dijkstra})
        for (int threads : {1, 3}) {
          const dense::Result whole = run_dense(field, in, a, threads);
          SCOPED_TRACE(::testing::Message() << "d=" << d << " seed=" << seed << " "
                                            << (a == dense::Algorithm::bfs ? "bfs" : "dijkstra")
                                            << " threads=" << threads);
          // Interrupted at the k-th boundary of each restart, until a restart ends the run.
          for (int k : {1, 2, 5}) {
            dense::Query q;
            q.start = in.start;
            q.goal = in.goal;
            q.algorithm = a;
            q.threads = threads;
            q.keep_path = true;
            dense::LocalTransport local;
            dense::Result r;
            const std::string one = file("a"), two = file("b");
            std::filesystem::remove(one);
            for (int leg = 0; leg < 1000; ++leg) {
              q.checkpointing.path = leg % 2 ? two : one;
              q.checkpointing.restart = leg == 0 ? "" : leg % 2 ? one : two;
              q.checkpointing.interrupted = interrupt_at(k);
              r = dense::search(field, q, local);
              if (r.status != Status::interrupted) break;
              ++interrupted;
              ASSERT_TRUE(std::filesystem::exists(q.checkpointing.path));
            }
            ++compared;
            expect_same(r, whole, "restarted every " + std::to_string(k) + " boundaries");
            EXPECT_EQ(r.figures.buckets, whole.figures.buckets);
            EXPECT_EQ(r.counters.peak_open, whole.counters.peak_open);
            EXPECT_EQ(r.counters.peak_states, whole.counters.peak_states);
          }
        }
    }
  EXPECT_EQ(compared, 72);
  EXPECT_GT(interrupted, 200);  // the runs were cut, many times
}

// A periodic checkpoint (every boundary here) is the state a killed run left: restarted from
// the last one written, the run ends as the uninterrupted one.
TEST_F(DenseCheckpoint, APeriodicCheckpointRestartsToTheSameAnswer) {
  const Instance in = random_instance(11, 3);
  const GogField field(3, in.extent, in.gog);
  for (const dense::Algorithm a : {dense::Algorithm::bfs, dense::Algorithm::dijkstra}) {
    const dense::Result whole = run_dense(field, in, a, 2);
    dense::Query q;
    q.start = in.start;
    q.goal = in.goal;
    q.algorithm = a;
    q.threads = 2;
    q.keep_path = true;
    q.checkpointing.path = file("periodic");
    q.checkpointing.every_s = 1e-9;
    dense::LocalTransport local;
    ASSERT_EQ(dense::search(field, q, local).status, whole.status);
    ASSERT_TRUE(std::filesystem::exists(q.checkpointing.path));
    q.checkpointing = {};
    q.checkpointing.restart = file("periodic");
    expect_same(dense::search(field, q, local), whole, "from the last periodic checkpoint");
  }
}

// A checkpoint of another problem, layout or kind, or a damaged one, is refused with one line
// naming the file and what differs.
TEST_F(DenseCheckpoint, ForeignOrDamagedCheckpointsAreRefused) {
  const Instance in = random_instance(5, 3);
  const GogField field(3, in.extent, in.gog);
  dense::Query q;
  q.start = in.start;
  q.goal = in.goal;
  q.algorithm = dense::Algorithm::dijkstra;
  q.threads = 2;
  q.checkpointing.path = file("ck");
  q.checkpointing.interrupted = interrupt_at(2);
  dense::LocalTransport local;
  ASSERT_EQ(dense::search(field, q, local).status, Status::interrupted);
  auto refusal = [&](dense::Query r, const GogField& f) -> std::string {
    r.checkpointing = {};
    r.checkpointing.restart = file("ck");
    try {
      dense::search(f, r, local);
    } catch (const InputError& e) {
      return e.what();
    }
    return "accepted";
  };
  const std::string prefix = "--restart '" + file("ck") + "': ";
  dense::Query other = q;
  other.threads = 1;
  EXPECT_EQ(refusal(other, field),
            prefix + "was written for another run (threads = 2; this run has threads = 1)");
  other = q;
  other.algorithm = dense::Algorithm::bfs;
  EXPECT_EQ(refusal(other, field),
            prefix + "was written for another run (engine = dijkstra; this run has engine = bfs)");
  other = q;
  other.keep_path = true;
  EXPECT_EQ(refusal(other, field),
            prefix + "was written for another run (path = no; this run has path = yes)");
  GogParams g = in.gog;
  g.seed += 1;
  const GogField another(3, in.extent, g);
  if (another.is_free(q.start) && another.is_free(q.goal)) {
    EXPECT_NE(refusal(q, another).find("(seed = "), std::string::npos);
  }
  // One byte changed in the middle: the checksum.
  std::string bytes;
  {
    std::ifstream f(file("ck"), std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(f), {});
  }
  ASSERT_GT(bytes.size(), 200u);
  std::string bad = bytes;
  bad[bad.size() / 2] ^= 0x20;
  std::ofstream(file("ck"), std::ios::binary) << bad;
  EXPECT_EQ(refusal(q, field), prefix + "fails its checksum (a damaged checkpoint)");
  std::ofstream(file("ck"), std::ios::binary) << bytes.substr(0, bytes.size() - 9);
  EXPECT_EQ(refusal(q, field), prefix + "is cut short (a damaged or incomplete checkpoint)");
  std::ofstream(file("ck"), std::ios::binary) << "hpcplan fluid checkpoint\n";
  EXPECT_NE(refusal(q, field).find("is not an hpcplan dense lattice checkpoint"),
            std::string::npos);
  std::filesystem::remove(file("ck"));
  EXPECT_EQ(refusal(q, field), prefix + "is not a readable regular file");
  // The intact file is accepted again.
  std::ofstream(file("ck"), std::ios::binary) << bytes;
  EXPECT_EQ(refusal(q, field), "accepted");
}

// A checkpoint that cannot be written is a run failure naming the file, not an answer.
TEST_F(DenseCheckpoint, AnUnwritableCheckpointIsARunFailure) {
  const Instance in = random_instance(5, 3);
  const GogField field(3, in.extent, in.gog);
  dense::Query q;
  q.start = in.start;
  q.goal = in.goal;
  q.threads = 2;
  q.checkpointing.path = file("missing-dir/ck");
  q.checkpointing.interrupted = interrupt_at(1);
  dense::LocalTransport local;
  for (const dense::Algorithm a : {dense::Algorithm::bfs, dense::Algorithm::dijkstra}) {
    q.algorithm = a;
    q.checkpointing.interrupted = interrupt_at(1);
    try {
      const dense::Result r = dense::search(field, q, local);
      ADD_FAILURE() << "an unwritable checkpoint was accepted: " << to_string(r.status);
    } catch (const RunError& e) {
      EXPECT_NE(std::string(e.what()).find(file("missing-dir/ck")), std::string::npos) << e.what();
    }
  }
}

}  // namespace
