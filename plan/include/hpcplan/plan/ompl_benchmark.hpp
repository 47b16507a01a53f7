#pragma once
// Seed 002's comparison in one harness: the grid planner and OMPL's sampling planners run
// inside ompl::tools::Benchmark on one problem (same space, checker, motion validator and
// start/goal states), and every run becomes a row with the seed's metrics. The problem is the
// GOG field (world "gog", sampling/gog_space.hpp) or one of OMPL's own dimension-scalable
// benchmarks as a configuration space (worlds "chain" and "hypercube",
// env/benchmark_spaces.hpp, through sampling/cspace_ompl.hpp): there the grid planner is the
// c-space lattice planner (plan/cspace_grid_planner.hpp), the query is the benchmark's own
// (KinematicChainBenchmark's, HypercubeBenchmark's), the log's experiment is "chain-<n>" /
// "hypercube-<d>" with the benchmark's parameter (num_links / num_dims), and on the hypercube
// every planner with a "range" gets half the corridor's width, as HypercubeBenchmark sets.
//
// Per run the harness records, besides Benchmark's own properties (which go to the OMPL log):
//  - every solution improvement (time, length) through the ProblemDefinition's intermediate
//    solution callback; anytime planners (BIT*, RRT*, ...) report each one, and the grid
//    planner reports its one answer the same way;
//  - first solution: the first report, or the planner's end for planners that report none
//    (FMT*, RRT-Connect). The end is Benchmark's "time REAL", which includes the join of
//    OMPL's termination-polling thread: it sleeps in 1 ms slices, so a solve shorter than
//    about a millisecond reads as the next slice;
//  - "best" solution (seed 002 §V-D), for optimizing planners that reported improvements: the first
//    moment the quality reaches the midpoint
//    between the first quality and the reference quality, the best final quality any run of
//    any planner reached in this invocation;
//  - final quality at the time limit; collision checks (the shared world's count);
//  - path validity, re-checked independently of OMPL: on GOG with the field's own look-ups
//    (sampling/gog_space.hpp), on a configuration space every motion's samples with the
//    space's one-state test (sampling/cspace_ompl.hpp), and the path's ends must be the
//    query's.
// Quality is length / straight-line distance (seed 002 eq. 2); on a configuration space both
// in the space's metric (joint-space Euclidean, periodic axes the short way).
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "hpcplan/env/gog.hpp"

namespace hpcplan::plan {

struct OmplBenchOptions {
  std::string world = "gog";  // gog | chain | hypercube
  int dims = 2;               // gog: 2..10; chain (links) and hypercube: 2..16
  // GOG only: the field.
  int extent = 100;
  GogParams gog;
  // chain and hypercube only: the lattice's cells per axis (0: the benchmark's default,
  // env/benchmark_spaces.hpp) and the motion-check resolution as a fraction of the space's
  // bounds diagonal (0: the benchmark's, as OMPL's demos set it: 0.01 chain, 0.001 hypercube).
  int cells = 0;
  double resolution_fraction = 0.0;
  std::vector<std::string> planners{"gridastar", "bitstar", "fmt"};
  double time_s = 5.0;  // per run
  int runs = 10;
  // Untimed solves of each planner before the timed runs (each at most 1 s), so the first
  // planner listed does not pay alone for the process's first searches.
  int warmup = 0;
  std::uint64_t seed = 1;         // GOG field and OMPL's random generator
  double resolution_cells = 0.1;  // GOG: discrete motion checks' spacing, in cell widths
  std::string motion = "exact";   // GOG: exact | discrete (sampling/gog_space.hpp)
  bool shortcut = true;           // grid planner: shorten its path in continuous space
  double grid_weight = 1.0;       // grid planner: 1 = A*
  double smoothing_budget = 1.0;  // grid planner: smoothing time / search time (0 = converge)
  double memory_mb = 8192.0;      // Benchmark's per-run memory limit
  std::string experiment;  // name in the log; default "gog-<d>d", "chain-<n>", "hypercube-<d>"
};

// Whether a world is a configuration space (chain, hypercube) rather than the GOG field.
bool is_cspace_world(const std::string& world);

struct OmplRunRow {
  std::string planner;  // the name the user asked for (gridastar, bitstar, fmt, ...)
  int dims = 0;
  int run = 0;
  std::uint64_t seed = 0;
  bool solved = false;
  double time_s = 0.0;  // the whole run, as Benchmark measured it
  double time_first_s = -1.0, length_first = -1.0, quality_first = -1.0;
  double time_best_s = -1.0, quality_best = -1.0;
  double length_final = -1.0, quality_final = -1.0;
  std::uint64_t collision_checks = 0;
  // The grid planner's smoothing (-1 for other planners): its seconds in this run, so the
  // smoothed answer's cost over the lattice answer is measured within one run.
  double smoothing_s = -1.0;
  bool path_valid = true;
  bool anytime = false;  // optimizing and reported improvements; only these have a "best"
  std::vector<std::pair<double, double>> improvements;  // (s, length)
};

struct OmplBenchResult {
  std::vector<OmplRunRow> rows;
  double straight_line = 0.0;
  double reference_quality = -1.0;  // best final quality of any run (-1 if none solved)
  std::vector<double> start, goal;  // the continuous start and goal (GOG: cell centres)
  int cells = 0;                    // c-space worlds: the lattice's cells per axis as run
  std::string ompl_log;             // Benchmark's own log, for ompl_benchmark_statistics.py
};

// Names accepted in OmplBenchOptions::planners on every world (the registry's "ompl" setting).
const std::vector<std::string>& known_planners();
// Names accepted besides on chain and hypercube only: kpiece, stride, prm, est, the planners of
// OMPL's own benchmarks of those spaces that sampling's table lacks (KPIECE1's default
// projection aborts on a 2D real vector space, sampling/ompl_planners.cpp).
const std::vector<std::string>& cspace_only_planners();

// FMT*'s sample count for dimension d (seed 002 eq. 1): 2000 + 1500 (d - 2)^2.
unsigned fmt_samples(int dims);

// Throws InputError for anything a user could have got wrong.
void validate(const OmplBenchOptions& options);

// Runs the benchmark (io/ompl_bench_csv.hpp formats its rows).
OmplBenchResult run_ompl_benchmark(const OmplBenchOptions& options);

}  // namespace hpcplan::plan
