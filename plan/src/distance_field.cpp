#include "hpcplan/plan/distance_field.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <optional>

#include "hpcplan/core/atomic_file.hpp"
#include "hpcplan/core/error.hpp"
#include "hpcplan/core/stopwatch.hpp"
#include "hpcplan/dense/dense_search.hpp"
#include "hpcplan/env/occupancy_io.hpp"

namespace hpcplan {
namespace {

static_assert(std::endian::native == std::endian::little, ".npy data is written little-endian");

// One rank's part as bytes: the run count, the runs, then the values (4 bytes each).
std::vector<std::byte> pack(const dense::Distances& part, bool hops) {
  const std::uint64_t n = part.runs.size();
  const std::size_t values = hops ? part.levels.size() : part.costs.size();
  std::vector<std::byte> out(sizeof n + n * sizeof(dense::Distances::Run) + values * 4);
  std::byte* at = out.data();
  std::memcpy(at, &n, sizeof n);
  at += sizeof n;
  if (n) std::memcpy(at, part.runs.data(), n * sizeof(dense::Distances::Run));
  at += n * sizeof(dense::Distances::Run);
  if (values)
    std::memcpy(at, hops ? static_cast<const void*>(part.levels.data()) : part.costs.data(),
                values * 4);
  return out;
}

// Copies a rank's packed part into the whole field.
template <class V>
void unpack(const std::vector<std::byte>& bytes, std::vector<V>& whole) {
  std::uint64_t n = 0;
  if (bytes.size() < sizeof n) throw RunError("distance field: a rank sent no part");
  std::memcpy(&n, bytes.data(), sizeof n);
  std::size_t at = sizeof n;
  std::vector<dense::Distances::Run> runs(n);
  if (bytes.size() < at + n * sizeof(dense::Distances::Run))
    throw RunError("distance field: a rank's part is cut short");
  if (n) std::memcpy(runs.data(), bytes.data() + at, n * sizeof(dense::Distances::Run));
  at += n * sizeof(dense::Distances::Run);
  for (const dense::Distances::Run& r : runs) {
    if (r.first + r.count > whole.size() || at + r.count * sizeof(V) > bytes.size())
      throw RunError("distance field: a rank's part lies outside the grid");
    std::memcpy(whole.data() + r.first, bytes.data() + at, r.count * sizeof(V));
    at += r.count * sizeof(V);
  }
}

}  // namespace

int distance_field_threads(const ObstacleSource& field, const GridSearchOptions& o,
                           int ranks_sharing_cpus) {
  return dense_threads(field, o, ranks_sharing_cpus);
}

std::uint64_t DistanceField::cells() const {
  std::uint64_t n = 1;
  for (int s : shape) n *= static_cast<std::uint64_t>(s);
  return n;
}

std::vector<std::int64_t> DistanceField::numpy_shape() const {
  return {shape.rbegin(), shape.rend()};
}

double DistanceField::at(std::span<const int> cell) const {
  std::uint64_t i = 0, stride = 1;
  for (std::size_t a = 0; a < shape.size(); ++a) {
    if (cell[a] < 0 || cell[a] >= shape[a]) return -1.0;
    i += static_cast<std::uint64_t>(cell[a]) * stride;
    stride *= static_cast<std::uint64_t>(shape[a]);
  }
  return hops ? static_cast<double>(levels[i]) : static_cast<double>(costs[i]);
}

void validate_distance_field(const GridProblem&, const GridSearchOptions& options) {
  if (options.algorithm != GridAlgorithm::bfs && options.algorithm != GridAlgorithm::dijkstra)
    throw InputError("--field-out needs --algo bfs or dijkstra (hop counts or path costs), not " +
                     std::string(to_string(options.algorithm)));
  if (options.engine == GridEngine::sparse)
    throw InputError("--field-out runs on the dense engine; drop --engine sparse");
  if (!options.checkpoint.empty() || !options.restart.empty())
    throw InputError("--field-out takes no --checkpoint or --restart");
}

GridProblem distance_field_problem(const ObstacleSource& field, const GridProblem& asked) {
  // Without a goal the field's query is start to start (its report: cost 0).
  GridProblem problem = asked;
  if (!problem.goal)
    problem.goal = problem.start
                       ? *problem.start
                       : adjust_to_free(field, std::vector<int>(problem.dims, 0), +1, "start");
  return problem;
}

DistanceFieldRun distance_field(const GridProblem& problem, const GridSearchOptions& options) {
  validate(problem, options);
  validate_distance_field(problem, options);
  std::optional<GogField> gog;
  const ObstacleSource field = obstacles_of(problem, gog);
  dense::LocalTransport local;
  return distance_field(field, problem, options, local, 1);
}

DistanceFieldRun distance_field(const ObstacleSource& field, const GridProblem& asked,
                                const GridSearchOptions& o, dense::SlabTransport& tr,
                                int ranks_sharing_memory) {
  validate_distance_field(asked, o);
  Stopwatch setup;
  DistanceFieldRun run;
  run.goal_given = asked.goal.has_value();
  const GridProblem problem = distance_field_problem(field, asked);
  GridReport& report = run.report;
  report = prepare_grid_report(problem, o, field, ranks_sharing_memory);
  dense::require_compiled(field.dims());

  const bool hops = o.algorithm == GridAlgorithm::bfs;
  dense::Query q = dense_query(field, problem, o, report, ranks_sharing_memory);
  q.progress_label = tr.rank() == 0 ? "hpcplan grid " + report.options.algorithm + " (field)" : "";
  dense::Distances part;
  q.distances = &part;
  report.result.setup_ms = setup.milliseconds();
  dense::Result r = dense::search(field, q, tr);

  GridResult& out = report.result;
  out.status = r.status;
  out.cost = r.cost;
  out.hops = r.hops;
  out.counters = r.counters;
  if (o.keep_path) out.path = std::move(r.path);
  report.options.engine = "dense";
  report.options.visited_map = "dense_bitmap";
  report.dense = std::move(r.figures);
  finish_grid_report(report);

  DistanceField& f = run.field;
  f.hops = hops;
  f.complete = r.status == Status::solved || r.status == Status::no_path;
  for (int a = 0; a < field.dims(); ++a) f.shape.push_back(field.size(a));
  const std::vector<std::vector<std::byte>> parts = tr.gather_to_root(pack(part, hops));
  if (tr.rank() != 0) return run;
  if (hops) {
    f.levels.assign(f.cells(), -1);
    for (const auto& p : parts) unpack(p, f.levels);
    f.reached = static_cast<std::uint64_t>(
        std::count_if(f.levels.begin(), f.levels.end(), [](std::int32_t v) { return v >= 0; }));
  } else {
    f.costs.assign(f.cells(), -1.0f);
    for (const auto& p : parts) unpack(p, f.costs);
    f.reached = static_cast<std::uint64_t>(
        std::count_if(f.costs.begin(), f.costs.end(), [](float v) { return v >= 0; }));
  }
  return run;
}

std::string distance_field_npy(const DistanceField& f) {
  const std::vector<std::int64_t> shape = f.numpy_shape();
  std::string out = env::npy_header(f.hops ? "<i4" : "<f4", shape);
  const std::size_t header = out.size();
  out.resize(header + f.cells() * 4);
  if (f.cells())
    std::memcpy(out.data() + header,
                f.hops ? static_cast<const void*>(f.levels.data()) : f.costs.data(), f.cells() * 4);
  return out;
}

void write_distance_field(const std::string& path, const DistanceField& f) {
  write_file_atomically(path, distance_field_npy(f));
}

}  // namespace hpcplan
