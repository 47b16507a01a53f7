#include "hpcplan/plan/grid_planner.hpp"
#include "hpcplan/plan/cspace_planner.hpp"

#include <algorithm>
#include <cmath>
#include <thread>

#include "hpcplan/core/error.hpp"
#include "hpcplan/core/format.hpp"
#include "hpcplan/core/memory.hpp"
#include "hpcplan/plan/grid_planner_impl.hpp"

namespace hpcplan {

// The instantiations grid_planner_impl.hpp declares extern.
template GridReport solve_grid_with<search::DefaultVisitedMap>(const ObstacleSource&,
                                                               const GridProblem&,
                                                               const GridSearchOptions&, double);
template GridReport solve_grid_with<search::StampedDensePolicy>(const ObstacleSource&,
                                                                const GridProblem&,
                                                                const GridSearchOptions&, double);

bool dense_visited_fits(int dims, int extent) {
  // Out-of-range problems are refused by validate(); they must not reach a key layout here.
  if (dims < 1 || dims > kMaxDims || extent < 2 || extent > kMaxExtent) return false;
  const KeyLayout layout(dims, extent);
  return layout.words() == 1 && layout.bits() * dims <= kDenseVisitedBits;
}

ObstacleSource obstacles_of(const GridProblem& problem, std::optional<GogField>& gog) {
  if (problem.occupancy) return *problem.occupancy;
  return gog.emplace(problem.dims, problem.extent, problem.gog);
}

GridReport solve_grid(const GridProblem& problem, const GridSearchOptions& options) {
  if (problem.cspace) return solve_cspace(problem, options);
  validate(problem, options);
  if (problem.occupancy) return solve_grid(*problem.occupancy, problem, options);
  Stopwatch setup;
  const GogField field(problem.dims, problem.extent, problem.gog);
  const double field_ms = setup.milliseconds();
  GridReport report = solve_grid(field, problem, options);
  report.result.setup_ms += field_ms;
  return report;
}

GridReport solve_grid(const ObstacleSource& field, const GridProblem& problem,
                      const GridSearchOptions& options) {
  validate(problem, options);
  {
    Stopwatch setup;
    GridReport report = prepare_grid_report(problem, options, field, 1);
    const bool dense = uses_dense_engine(field, problem, options, report, 1);
    require_dense_for_checkpoints(options, field.dims(), dense);
    if (dense) {
      report.result.setup_ms = setup.milliseconds();
      dense::LocalTransport local;
      run_dense(field, problem, options, local, 1, report);
      finish_grid_report(report);
      return report;
    }
  }
  if (dense_visited_fits(problem.dims, problem.extent))
    return solve_grid_with<search::StampedDensePolicy>(field, problem, options);
  return solve_grid_with<search::DefaultVisitedMap>(field, problem, options);
}

std::uint64_t dense_memory_budget(const GridSearchOptions& options, const GridReport& report) {
  if (options.memory_budget > 0) return options.memory_budget;
  return report.options.max_states * bytes_per_state(report.options.key_words);
}

int dense_threads(const GridSearchOptions& options, int ranks_sharing_cpus) {
  if (options.threads > 0) return options.threads;
  return std::max(1, dense::usable_cpus() / std::max(1, ranks_sharing_cpus));
}

int dense_threads(const ObstacleSource& field, const GridSearchOptions& o, int ranks_sharing_cpus) {
  if (o.threads > 0) return o.threads;
  const int most = dense_threads(o, ranks_sharing_cpus);
  double free = 1.0 - field.blocked_fraction();
  for (int a = 0; a < field.dims(); ++a) free *= field.size(a);
  const double per_level = free / std::max(1, field.extent());
  const double wanted = std::floor(per_level / kDenseStatesPerThreadLevel);
  return static_cast<int>(std::clamp(wanted, 1.0, static_cast<double>(std::max(1, most))));
}

dense::Query dense_query(const ObstacleSource& field, const GridProblem& problem,
                         const GridSearchOptions& o, const GridReport& report,
                         int ranks_sharing_cpus) {
  dense::Query q;
  q.start = report.problem.start;
  q.goal = report.problem.goal;
  q.algorithm =
      o.algorithm == GridAlgorithm::bfs ? dense::Algorithm::bfs : dense::Algorithm::dijkstra;
  q.connectivity = problem.connectivity;
  q.threads = dense_threads(field, o, ranks_sharing_cpus);
  q.keep_path = o.keep_path;
  q.block_sections = o.contiguous_slabs ? 0 : o.slab_layers > 0 ? o.slab_layers : -1;
  q.memory_budget = dense_memory_budget(o, report);
  q.stop = Stop::after(o.time_limit_s, o.cancel);
  if (o.stop_when) q.stop.also_when(o.stop_when);
  q.progress_label = "hpcplan grid " + report.options.algorithm + " (dense)";
  // The job's files: the engine names each rank's (dense::rank_file).
  q.checkpointing.path = o.checkpoint;
  q.checkpointing.restart = o.restart;
  q.checkpointing.every_s = o.checkpoint_every_s;
  q.checkpointing.interrupted = o.interrupted;
  return q;
}

namespace {

// Re-validates a returned path move by move with the lattice graph (the field formula, not the
// dense engine's tables) and returns its length.
template <int W>
double validated_dense_path(const ObstacleSource& field, const GridProblem& problem,
                            const std::vector<std::vector<int>>& path) {
  const LatticeGraph<W> graph(field, problem.connectivity);
  std::vector<typename LatticeGraph<W>::State> states;
  states.reserve(path.size());
  for (const auto& c : path) states.push_back(graph.pack(c));
  return search::validated_length(graph, states);
}

}  // namespace

namespace {

// The bytes a dense run of these options would plan for, per rank (the query of a process
// that shares its node with no other rank, as the check has always assumed).
std::uint64_t planned_dense_bytes(const ObstacleSource& field, const GridProblem& problem,
                                  const GridSearchOptions& options, const GridReport& report,
                                  int ranks) {
  return dense::planned_bytes(field, dense_query(field, problem, options, report, 1), ranks);
}

}  // namespace

bool dense_fits(const ObstacleSource& field, const GridProblem& problem,
                const GridSearchOptions& options, const GridReport& report, int ranks) {
  return planned_dense_bytes(field, problem, options, report, ranks) <=
         dense_memory_budget(options, report);
}

bool uses_dense_engine(const ObstacleSource& field, const GridProblem& problem,
                       const GridSearchOptions& options, const GridReport& report, int ranks) {
  if (options.engine == GridEngine::sparse) return false;
  if (options.algorithm != GridAlgorithm::bfs && options.algorithm != GridAlgorithm::dijkstra)
    return false;
  if (options.engine == GridEngine::dense) return true;  // refused in one line if not compiled
  if (field.dims() > dense::compiled_dims()) return false;
  // The dense engine works on the array's bounding hypercube in 8 x 8 tiles padded by one on
  // every axis: for an elongated array (a 1 x 65535 line: 5.9 GB) or many short axes (3^11
  // cells: 1.4 GB) that is far more than the array. Auto takes it only while it plans at most
  // 8 bytes per cell of the array (a 512 x 512 map plans about 2 bytes per cell).
  if (field.is_occupancy() && planned_dense_bytes(field, problem, options, report, ranks) >
                                  8 * field.occupancy().cells() + (std::uint64_t{1} << 20))
    return false;
  return dense_fits(field, problem, options, report, ranks);
}

void run_dense(const ObstacleSource& field, const GridProblem& problem,
               const GridSearchOptions& options, dense::SlabTransport& transport,
               int ranks_sharing_cpus, GridReport& report) {
  dense::Query q = dense_query(field, problem, options, report, ranks_sharing_cpus);
  if (transport.rank() != 0) q.progress_label.clear();  // one progress line per job
  dense::Result r = dense::search(field, q, transport);
  GridResult& out = report.result;
  out.status = r.status;
  out.cost = r.cost;
  out.hops = r.hops;
  out.counters = r.counters;
  out.path = std::move(r.path);
  report.options.engine = "dense";
  report.options.visited_map = "dense_bitmap";
  report.dense = std::move(r.figures);
  if (!out.path.empty()) {
    const double length =
        report.options.key_words == 1   ? validated_dense_path<1>(field, problem, out.path)
        : report.options.key_words == 2 ? validated_dense_path<2>(field, problem, out.path)
                                        : validated_dense_path<4>(field, problem, out.path);
    if (std::abs(length - out.cost) > 1e-9 * (1.0 + out.cost))
      throw RunError("internal error: the dense engine's path is " + std::to_string(length) +
                     " long, not its cost " + std::to_string(out.cost));
    if (!options.keep_path) out.path.clear();
  }
}

GridReport prepare_grid_report(const GridProblem& problem, const GridSearchOptions& options,
                               const ObstacleSource& field, int ranks_sharing_memory) {
  GridReport report;
  GridProblemReport& pr = report.problem;
  pr.dims = problem.dims;
  pr.extent = problem.extent;
  pr.blocked_fraction = field.blocked_fraction();
  if (field.is_gog()) {
    pr.seed = problem.gog.seed;
    pr.threshold = field.gog().threshold();
    pr.shift_p = problem.gog.shift_p;
    pr.shift_v = problem.gog.shift_v;
  } else {
    const OccupancyGrid& grid = field.occupancy();
    pr.obstacles = grid.format;
    pr.map = grid.name;
    pr.shape = grid.shape();
    pr.map_checksum = grid.checksum();
  }
  pr.connectivity = std::string(to_string(problem.connectivity));
  GridOptionsReport& op = report.options;
  op.algorithm = std::string(to_string(options.algorithm));
  op.heuristic =
      options.algorithm == GridAlgorithm::dijkstra || options.algorithm == GridAlgorithm::bfs
          ? "none"
          : std::string(to_string(options.heuristic));
  op.weight = options.algorithm == GridAlgorithm::wastar ? options.weight.value_or(2.0) : 1.0;

  auto endpoint = [&](const std::optional<std::vector<int>>& given, int corner, int direction,
                      const char* what, bool& adjusted) {
    if (given) {
      if (!field.is_free(*given)) {
        throw InputError(std::string("--") + what + " (" + join_coordinates(*given) +
                         ") is inside an obstacle");
      }
      return *given;
    }
    // The nominal corner: all zeros, or each axis's last cell (a map's own sides).
    std::vector<int> nominal(problem.dims, corner);
    if (corner > 0)
      for (int a = 0; a < problem.dims; ++a) nominal[a] = field.size(a) - 1;
    auto free = adjust_to_free(field, nominal, direction, what);
    adjusted = free != nominal;
    return free;
  };
  pr.start = endpoint(problem.start, 0, +1, "start", pr.start_adjusted);
  pr.goal = endpoint(problem.goal, problem.extent - 1, -1, "goal", pr.goal_adjusted);

  double sq = 0.0;
  for (int i = 0; i < problem.dims; ++i) {
    const double d = pr.goal[i] - pr.start[i];
    sq += d * d;
  }
  pr.straight_line = std::sqrt(sq);

  const KeyLayout layout(problem.dims, problem.extent);
  op.key_words = layout.words() <= 1 ? 1 : layout.words() <= 2 ? 2 : 4;
  op.max_states = options.max_states;
  if (op.max_states == 0) {
    // Stop with budget_exceeded well before the kernel's OOM killer would.
    const std::uint64_t avail = available_memory_bytes();
    op.max_states =
        avail ? avail / 2 / std::max(1, ranks_sharing_memory) / bytes_per_state(op.key_words)
              : 100'000'000;
  }
  return report;
}

void finish_grid_report(GridReport& report) {
  GridResult& r = report.result;
  if (r.status == search::Status::solved)
    r.quality = report.problem.straight_line > 0 ? r.cost / report.problem.straight_line : 1.0;
}

double workload_deviation_percent(const std::vector<search::RankCounters>& per_rank) {
  std::uint64_t total = 0;
  for (const auto& r : per_rank) total += r.expanded;
  if (per_rank.size() < 2 || total == 0) return 0.0;
  double lo = 100.0, hi = 0.0;
  for (const auto& r : per_rank) {
    const double share = 100.0 * static_cast<double>(r.expanded) / static_cast<double>(total);
    lo = std::min(lo, share);
    hi = std::max(hi, share);
  }
  return hi - lo;
}

}  // namespace hpcplan
