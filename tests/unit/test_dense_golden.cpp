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
#include "support/in_process_ranks.hpp"

namespace {

using namespace hpcplan;

constexpr int kCases = 96;

struct Case {
  std::unique_ptr<GogField> gog;
  std::unique_ptr<OccupancyGrid> grid;
  dense::Query query;
  ObstacleSource source() const { return gog ? ObstacleSource(*gog) : ObstacleSource(*grid); }
};

// Case i: its field, query and the second layout it runs on (ranks, threads, block layers).
Case draw_case(int i, int& ranks, int& threads, int& block_layers) {
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
  block_layers = blocks == 0 ? -1 : blocks == 1 ? 0 : blocks - 1;
  return c;
}

std::uint64_t fnv(std::uint64_t h, std::uint64_t v) {
  for (int b = 0; b < 8; ++b) h = (h ^ ((v >> (8 * b)) & 0xFF)) * 0x100000001B3ULL;
  return h;
}

// The run's line: everything that must not depend on ranks, threads or blocks.
std::string line_of(const dense::Result& r, const std::map<std::uint64_t, double>* field) {
  std::uint64_t path = 0xCBF29CE484222325ULL;
  for (const auto& s : r.path)
    for (int c : s) path = fnv(path, static_cast<std::uint64_t>(c));
  char buf[512];
  std::snprintf(buf, sizeof buf,
                "%s cost=%.12g hops=%llu path=%016llx expanded=%llu generated=%llu "
                "peak_states=%llu levels=%llu reached=%llu free=%llu tiles=%llu checks=%llu",
                std::string(to_string(r.status)).c_str(), r.cost,
                static_cast<unsigned long long>(r.hops), static_cast<unsigned long long>(path),
                static_cast<unsigned long long>(r.counters.expanded),
                static_cast<unsigned long long>(r.counters.generated),
                static_cast<unsigned long long>(r.counters.peak_states),
                static_cast<unsigned long long>(r.figures.levels),
                static_cast<unsigned long long>(r.figures.reached),
                static_cast<unsigned long long>(r.figures.free_states),
                static_cast<unsigned long long>(r.figures.tiles),
                static_cast<unsigned long long>(r.counters.collision_checks));
  std::string out = buf;
  if (field) {
    std::uint64_t h = 0xCBF29CE484222325ULL;
    for (const auto& [cell, v] : *field) {
      h = fnv(h, cell);
      h = fnv(h, static_cast<std::uint64_t>(static_cast<std::int64_t>(v * 1e6)));
    }
    std::snprintf(buf, sizeof buf, " cells=%zu field=%016llx", field->size(),
                  static_cast<unsigned long long>(h));
    out += buf;
  }
  return out;
}

// Runs the case on `ranks` in-process ranks; rank 0's result, and the distance field's cells
// merged from every rank's part when `field_run`.
std::string run_case(const Case& c, int ranks, int threads, int block_layers, bool field_run) {
  test_support::InProcessRanks hub(ranks);
  std::vector<dense::Result> results(ranks);
  std::vector<dense::Distances> parts(ranks);
  std::vector<std::string> errors(ranks);
  const ObstacleSource field = c.source();
  hub.run([&](int rank) {
    try {
      test_support::InProcessTransport tr(hub, rank);
      dense::Query q = c.query;
      q.threads = threads;
      q.block_layers = block_layers;
      if (field_run) q.distances = &parts[rank];
      results[rank] = dense::search(field, q, tr);
    } catch (const std::exception& e) {
      errors[rank] = e.what();
    }
  });
  for (const std::string& e : errors)
    if (!e.empty()) return "error: " + e;
  std::map<std::uint64_t, double> cells;
  if (field_run) {
    const bool hops = c.query.algorithm == dense::Algorithm::bfs;
    for (const dense::Distances& p : parts) {
      std::size_t at = 0;
      for (const dense::Distances::Run& run : p.runs)
        for (std::uint64_t k = 0; k < run.count; ++k, ++at) {
          const double v = hops ? p.levels[at] : p.costs[at];
          if (v >= 0) cells[run.first + k] = v;
        }
    }
  }
  return line_of(results[0], field_run ? &cells : nullptr);
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
    int ranks = 1, threads = 1, block_layers = -1;
    const Case c = draw_case(i, ranks, threads, block_layers);
    std::string line = "case " + std::to_string(i) + ": ";
    if (c.query.start.empty()) {
      line += "no free cell";
    } else {
      // Every fourth case a distance field (the goal still reported).
      const bool field_run = i % 4 == 2;
      const std::string one = run_case(c, 1, 1, -1, field_run);
      const std::string other = run_case(c, ranks, threads, block_layers, field_run);
      EXPECT_EQ(other, one) << "case " << i << " on " << ranks << " ranks x " << threads
                            << " threads, block layers " << block_layers;
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
