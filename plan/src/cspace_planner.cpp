#include "hpcplan/plan/cspace_planner.hpp"

#include <charconv>
#include <cmath>
#include <string>

#include "hpcplan/core/error.hpp"
#include "hpcplan/core/memory.hpp"
#include "hpcplan/core/stopwatch.hpp"
#include "hpcplan/plan/grid_planner_impl.hpp"
#include "hpcplan/search/best_first.hpp"

namespace hpcplan {
namespace {

// The values as typed back: the shortest text that reads back to each double, so a refusal
// quotes the very value at fault (1.0000001, not 1).
std::string join(const std::vector<double>& q) {
  std::string s;
  for (std::size_t i = 0; i < q.size(); ++i) {
    if (i) s += ',';
    char buf[32];
    const auto r = std::to_chars(buf, buf + sizeof buf, q[i]);
    s.append(buf, r.ptr);
  }
  return s;
}

// A periodic value wrapped into [lower, upper).
std::vector<double> wrapped(const ConfigSpace& space, std::vector<double> q) {
  for (int a = 0; a < space.dims(); ++a) {
    const auto& ax = space.axes()[a];
    if (!ax.periodic) continue;
    const double period = ax.upper - ax.lower;
    q[a] = ax.lower + std::fmod(std::fmod(q[a] - ax.lower, period) + period, period);
    if (q[a] >= ax.upper) q[a] = ax.lower;
  }
  return q;
}

void check_end(const ConfigSpace& space, const std::vector<double>& q, const char* what) {
  if (q.size() != static_cast<std::size_t>(space.dims()))
    throw InputError(std::string("--") + what + " needs " + std::to_string(space.dims()) +
                     " values for " + space.name() + ", got " + std::to_string(q.size()));
  for (double v : q)
    if (!std::isfinite(v)) throw InputError(std::string("--") + what + " is not finite");
  // A periodic axis takes any angle: it is wrapped; a bounded one must hold it.
  for (int a = 0; a < space.dims(); ++a) {
    const auto& ax = space.axes()[a];
    if (!ax.periodic && (q[a] < ax.lower || q[a] > ax.upper))
      throw InputError(std::string("--") + what + " (" + join(q) +
                       ") is outside the bounds on axis " + std::to_string(a));
  }
  // Tested as planned from: wrapped into the bounds (an angle of 1e300 is some angle in
  // [-pi, pi), and the chain's trigonometry is exact only there).
  const std::vector<double> w = wrapped(space, q);
  if (!space.is_valid(w.data()))
    throw InputError(std::string("--") + what + " (" + join(q) + ") is in collision in " +
                     space.name());
}

// The nearest vertex the end joins by a valid motion (end -> vertex for the start, vertex -> end
// for the goal: the same states either way). False if none of the candidates does.
bool join_lattice(const CSpaceGraph& graph, const std::vector<double>& end, bool is_goal,
                  std::vector<int>& vertex, std::vector<double>& vertex_q, double& length) {
  vertex_q.resize(graph.dims());
  for (auto& c : graph.vertices_near(end, kCSpaceEndCandidates)) {
    graph.vertex(c.data(), vertex_q.data());
    double d = graph.distance(end, vertex_q);
    // An end within round-off of a vertex is that vertex (the chain's start angles pi/n, read
    // back as decimals): no motion of 1e-15 and no extra hop.
    if (d <= 1e-12 * (1.0 + graph.space().maximum_extent())) d = 0.0;
    const bool ok = d == 0.0 || (is_goal ? motion_valid(graph.space(), vertex_q, end)
                                         : motion_valid(graph.space(), end, vertex_q));
    if (ok && graph.space().is_valid(vertex_q.data())) {
      vertex = std::move(c);
      length = d;
      return true;
    }
  }
  return false;
}

}  // namespace

void validate_cspace(const GridProblem& problem, const GridSearchOptions& options) {
  if (!problem.cspace || !problem.cspace->space)
    throw InputError("internal: a configuration-space problem without its space");
  const ConfigSpace& space = *problem.cspace->space;
  if (problem.dims != space.dims())
    throw InputError("--dims " + std::to_string(problem.dims) + " disagrees with " + space.name() +
                     "'s " + std::to_string(space.dims()) + " axes");
  if (options.engine == GridEngine::dense)
    throw InputError(
        "--engine dense plans on GOG and occupancy grids, not on a configuration space; use "
        "--engine sparse (or auto)");
  if (!options.checkpoint.empty() || !options.restart.empty())
    throw InputError(
        "--checkpoint/--restart are the dense engine's; a configuration space runs "
        "the sparse one");
  if (options.algorithm == GridAlgorithm::wastar && options.weight && !(*options.weight >= 1.0))
    throw InputError("--weight must be at least 1");
  check_end(space, problem.cspace->start, "start");
  check_end(space, problem.cspace->goal, "goal");
}

bool begin_cspace_run(const GridProblem& problem, const GridSearchOptions& options,
                      const CSpaceGraph& graph, int ranks_sharing_memory, CSpaceRun& run) {
  const ConfigSpace& space = graph.space();
  GridReport& report = run.report;
  run.keep_path = options.keep_path;
  GridProblemReport& pr = report.problem;
  pr.obstacles = "cspace";
  pr.map = space.name();
  pr.dims = graph.dims();
  pr.extent = graph.cells();
  pr.connectivity = std::string(to_string(graph.moves()));
  GridOptionsReport& op = report.options;
  op.algorithm = std::string(to_string(options.algorithm));
  op.heuristic =
      options.algorithm == GridAlgorithm::dijkstra || options.algorithm == GridAlgorithm::bfs
          ? "none"
          : "euclidean";
  op.weight = options.algorithm == GridAlgorithm::wastar ? options.weight.value_or(2.0) : 1.0;
  op.engine = "sparse";
  op.key_words = CSpaceGraph::kWords;
  op.visited_map = "hash";
  op.max_states = options.max_states;
  if (op.max_states == 0) {
    const std::uint64_t avail = available_memory_bytes();
    op.max_states =
        avail ? avail / 2 / std::max(1, ranks_sharing_memory) / bytes_per_state(CSpaceGraph::kWords)
              : 100'000'000;
  }

  CSpaceReport& cs = report.cspace.emplace();
  cs.world = space.name();
  cs.cells = graph.cells();
  cs.moves = pr.connectivity;
  cs.resolution = space.resolution();
  for (const auto& a : space.axes()) cs.periodic.push_back(a.periodic);
  cs.start = wrapped(space, problem.cspace->start);
  cs.goal = wrapped(space, problem.cspace->goal);
  pr.straight_line = graph.distance(cs.start, cs.goal);

  // Start and goal the same state: the answer is that state, at no cost (joining a vertex and
  // coming back would report a round trip).
  if (graph.distance(cs.start, cs.goal) == 0.0) {
    report.result.status = search::Status::solved;
    report.result.cost = 0.0;
    report.result.hops = 0;
    cs.path_rechecked = true;  // its one state was tested in validate_cspace
    if (run.keep_path) cs.path = {cs.start};
    return false;
  }
  std::vector<int> sv, gv;
  const bool start_joined =
      join_lattice(graph, cs.start, false, sv, cs.start_vertex, cs.start_connection);
  const bool goal_joined =
      start_joined && join_lattice(graph, cs.goal, true, gv, cs.goal_vertex, cs.goal_connection);
  if (!start_joined || !goal_joined) {
    cs.unconnected = start_joined ? "goal" : "start";
    report.result.status = search::Status::no_path;
    return false;
  }
  pr.start = sv;
  pr.goal = gv;
  run.start = graph.pack(sv);
  run.goal = graph.pack(gv);
  return true;
}

void finish_cspace_run(const search::Result<CSpaceGraph::State>& r, const CSpaceGraph& graph,
                       CSpaceRun& run) {
  GridReport& report = run.report;
  CSpaceReport& cs = *report.cspace;
  GridResult& out = report.result;
  out.status = r.status;
  out.counters = r.counters;
  cs.batches = graph.batches();
  if (r.status != search::Status::solved) {
    finish_grid_report(report);
    return;
  }
  if (run.keep_path)
    for (const auto& s : r.path) out.path.push_back(graph.unpack(s));
  // The whole path in the space's coordinates, each motion re-checked one state at a time.
  std::vector<std::vector<double>> path;
  if (cs.start_connection > 0.0) path.push_back(cs.start);
  for (const auto& s : r.path) path.push_back(graph.vertex(s));
  if (cs.goal_connection > 0.0) path.push_back(cs.goal);
  double length = 0.0;
  std::vector<double> samples;
  const ConfigSpace& space = graph.space();
  const std::size_t d = static_cast<std::size_t>(space.dims());
  for (std::size_t i = 0; i < path.size(); ++i) {
    if (i == 0) {
      if (!space.is_valid(path[0].data()))
        throw RunError("internal error: the path's first state is in collision");
      continue;
    }
    const Motion motion(space, path[i - 1], path[i]);
    const std::size_t m = motion.samples(samples);
    for (std::size_t k = 0; k < m; ++k)
      if (!space.is_valid(samples.data() + k * d))
        throw RunError("internal error: motion " + std::to_string(i) +
                       " of the returned path is in collision");
    length += motion.length();
  }
  out.cost = r.cost + cs.start_connection + cs.goal_connection;
  if (std::abs(length - out.cost) > 1e-9 * (1.0 + out.cost))
    throw RunError("internal error: the path's length disagrees with the search's cost");
  out.hops = path.size() - 1;
  cs.path_rechecked = true;
  cs.batches = graph.batches();
  if (run.keep_path) cs.path = std::move(path);
  finish_grid_report(report);
}

GridReport solve_cspace(const GridProblem& problem, const GridSearchOptions& options) {
  validate_cspace(problem, options);
  Stopwatch setup;
  CSpaceGraph graph(*problem.cspace->space, problem.extent, problem.cspace->moves);
  graph.set_batch_checks(problem.cspace->batch_checks);
  CSpaceRun run;
  if (!begin_cspace_run(problem, options, graph, 1, run)) {
    run.report.result.setup_ms = setup.milliseconds();
    finish_grid_report(run.report);
    return run.report;
  }
  run.report.result.setup_ms = setup.milliseconds();
  auto eo =
      detail::engine_options(options, run.report.options.weight, run.report.options.max_states);
  search::Result<CSpaceGraph::State> r;
  if (options.algorithm == GridAlgorithm::dijkstra || options.algorithm == GridAlgorithm::bfs)
    r = search::best_first_search(graph, run.start, run.goal, search::ZeroHeuristic{}, eo);
  else
    r = search::best_first_search(graph, run.start, run.goal, CSpaceHeuristic(graph, run.goal), eo);
  finish_cspace_run(r, graph, run);
  return run.report;
}

}  // namespace hpcplan
