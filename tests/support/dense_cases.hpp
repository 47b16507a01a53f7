#pragma once
// Dense-engine cases for tests that compare layouts: a field (GOG or occupancy array) with its
// query, run on P in-process ranks (support/in_process_ranks.hpp) and summed up as one line of
// everything that must not depend on ranks, threads or blocks (answer, path, counts, and a
// distance field's cells merged from every rank's part).
#include <cstdint>
#include <cstdio>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "hpcplan/dense/dense_search.hpp"
#include "hpcplan/env/gog.hpp"
#include "hpcplan/env/occupancy_grid.hpp"
#include "support/in_process_ranks.hpp"

namespace hpcplan::test_support {

struct Case {
  std::unique_ptr<GogField> gog;
  std::unique_ptr<OccupancyGrid> grid;
  dense::Query query;
  ObstacleSource source() const { return gog ? ObstacleSource(*gog) : ObstacleSource(*grid); }
};

inline std::uint64_t fnv(std::uint64_t h, std::uint64_t v) {
  for (int b = 0; b < 8; ++b) h = (h ^ ((v >> (8 * b)) & 0xFF)) * 0x100000001B3ULL;
  return h;
}

// The run's line: everything that must not depend on ranks, threads or blocks.
inline std::string line_of(const dense::Result& r, const std::map<std::uint64_t, double>* field) {
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
// (rank0: rank 0's result, when given.)
inline std::string run_case(const Case& c, int ranks, int threads, int block_sections,
                            bool field_run, dense::Result* rank0 = nullptr) {
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
      q.block_sections = block_sections;
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
  if (rank0) *rank0 = results[0];
  return line_of(results[0], field_run ? &cells : nullptr);
}

}  // namespace hpcplan::test_support
