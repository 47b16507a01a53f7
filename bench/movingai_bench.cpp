// hpcplan_movingai_bench: one MovingAI map's scenario rows solved, in one process and on the same
// rows, by hpcplan's grid planner (A* with jump points, A* on every lattice state, weighted A*)
// and by the textbook A* of textbook_astar.hpp, each answer checked against the published
// optimum. Per row the engines run one after another, in the order J L W T on even rows and
// T W L J on odd ones, so drift and cache warmth from the previous call fall on every engine
// alike. Reports, per group of buckets (buckets dealt into --groups groups by path length), the
// median time per query of each engine and the ratios textbook / ours; and the map's load time
// (ours: hpcplan's parser into the bit grid; textbook: its own parser), separately.
//
//   hpcplan_movingai_bench SCEN [--map FILE] [--rows N] [--groups G] [--weight W]
//                          [--loads K] [--csv FILE] [--rows-csv FILE]
//
// --rows N: N rows spread evenly over the file (every bucket alike; 0: all rows; default 1000).
// --tolerance REL: the relative tolerance of the optimum checks (default 1e-6, as `hpcplan scen`;
// a scenario file that prints its lengths to 6 significant digits needs about 1e-5).
// Exits 1 at the first answer that breaks its promise against the published optimum L (A* and the
// textbook within the tolerance, weighted A* within [L, W L]); 2 on bad input.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "hpcplan/core/atomic_file.hpp"
#include "hpcplan/core/error.hpp"
#include "hpcplan/core/memory.hpp"
#include "hpcplan/core/stopwatch.hpp"
#include "hpcplan/env/occupancy_io.hpp"
#include "hpcplan/plan/scenario_run.hpp"
#include "textbook_astar.hpp"

namespace {

using hpcplan::GridAlgorithm;
using hpcplan::GridSearchOptions;

struct Args {
  std::string scen, map, csv, rows_csv;
  std::size_t rows = 1000;
  int groups = 10;
  int loads = 5;
  double weight = 1.5;
  double tolerance = hpcplan::kScenarioTolerance;
};

[[noreturn]] void usage_error(const std::string& what) {
  std::fprintf(stderr, "hpcplan_movingai_bench: error: %s\n", what.c_str());
  std::exit(2);
}

Args parse_args(int argc, char** argv) {
  Args a;
  auto value = [&](int& i) -> std::string {
    if (i + 1 >= argc) usage_error(std::string(argv[i]) + " needs a value");
    return argv[++i];
  };
  auto number = [&](int& i) -> double {
    const std::string text = value(i);
    char* end = nullptr;
    const double v = std::strtod(text.c_str(), &end);
    if (end == text.c_str() || *end != '\0' || !(v >= 0))
      usage_error(std::string(argv[i - 1]) + " takes a number >= 0, not '" + text + "'");
    return v;
  };
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--map")
      a.map = value(i);
    else if (arg == "--csv")
      a.csv = value(i);
    else if (arg == "--rows-csv")
      a.rows_csv = value(i);
    else if (arg == "--rows")
      a.rows = static_cast<std::size_t>(number(i));
    else if (arg == "--groups")
      a.groups = std::max(1, static_cast<int>(number(i)));
    else if (arg == "--loads")
      a.loads = std::max(1, static_cast<int>(number(i)));
    else if (arg == "--weight")
      a.weight = number(i);
    else if (arg == "--tolerance")
      a.tolerance = number(i);
    else if (arg == "-h" || arg == "--help") {
      std::printf(
          "usage: hpcplan_movingai_bench SCEN [--map FILE] [--rows N (default 1000, 0: all)] "
          "[--groups G (10)] [--weight W (1.5)] [--loads K (5)] [--tolerance REL (1e-6)] "
          "[--csv FILE] [--rows-csv FILE]\n");
      std::exit(0);
    } else if (!arg.empty() && arg[0] == '-')
      usage_error("unknown option " + arg);
    else if (a.scen.empty())
      a.scen = arg;
    else
      usage_error("one scenario file only");
  }
  if (a.scen.empty()) usage_error("no scenario file (.scen)");
  if (a.weight < 1.0) usage_error("--weight must be >= 1");
  return a;
}

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

enum Engine { jps, lattice, wastar, textbook_astar, kEngines };
constexpr const char* kEngineName[kEngines] = {"astar_jps", "astar_lattice", "wastar", "textbook"};

struct RowTimes {
  std::size_t row = 0;
  int bucket = 0, group = 0;
  double optimal = 0;
  double us[kEngines] = {};
  double cost[kEngines] = {};
  std::uint64_t expanded[kEngines] = {};
};

}  // namespace

int main(int argc, char** argv) {
  const Args args = parse_args(argc, argv);
  try {
    const hpcplan::env::Scenario scenario = hpcplan::env::load_scenario(args.scen);
    if (scenario.voxel || scenario.rows.empty())
      throw hpcplan::InputError(args.scen + ": not a 2D scenario with rows");
    std::string map_path = args.map;
    if (map_path.empty())
      map_path = (std::filesystem::path(args.scen).parent_path() /
                  std::filesystem::path(scenario.rows.front().map).filename())
                     .string();

    // Load times, each parser `loads` times (medians), the textbook's and ours alternating.
    std::vector<double> load_ours, load_textbook;
    std::shared_ptr<const hpcplan::OccupancyGrid> grid;
    textbook::Map tmap;
    for (int k = 0; k < args.loads; ++k) {
      hpcplan::Stopwatch clock;
      tmap = textbook::read_map(map_path);
      load_textbook.push_back(clock.milliseconds());
      clock.restart();
      grid = std::make_shared<const hpcplan::OccupancyGrid>(hpcplan::env::load_occupancy(map_path));
      load_ours.push_back(clock.milliseconds());
    }

    // The rows: N spread evenly over the file; groups by bucket.
    std::vector<std::size_t> rows;
    const std::size_t total = scenario.rows.size();
    const std::size_t n = args.rows == 0 ? total : std::min(args.rows, total);
    for (std::size_t k = 0; k < n; ++k) rows.push_back(k * total / n);
    int max_bucket = 0;
    for (const auto& r : scenario.rows) max_bucket = std::max(max_bucket, r.bucket);

    GridSearchOptions base;
    const std::uint64_t avail = hpcplan::available_memory_bytes();
    base.max_states = avail ? avail / 2 / hpcplan::bytes_per_state(1) : 100'000'000;
    GridSearchOptions opt[3] = {base, base, base};
    opt[lattice].jump_points = false;
    opt[wastar].algorithm = GridAlgorithm::wastar;
    opt[wastar].weight = args.weight;

    textbook::AStar astar(tmap);
    // The textbook's per-query reset alone: a query whose start is its goal (fill + one pop).
    std::vector<double> reset_us;
    {
      const hpcplan::env::ScenarioRow& r0 = scenario.rows[rows.front()];
      for (int k = 0; k < 51; ++k) {
        hpcplan::Stopwatch clock;
        astar.search(r0.start[0], r0.start[1], r0.start[0], r0.start[1]);
        reset_us.push_back(clock.milliseconds() * 1000.0);
      }
    }
    std::vector<RowTimes> out;
    out.reserve(rows.size());
    // A wrong answer ends the run at once: its times would compare unlike work.
    auto check = [&](bool bad, std::size_t row, const char* engine, double cost, double optimal) {
      if (!bad) return;
      std::fprintf(stderr,
                   "hpcplan_movingai_bench: error: row %zu: %s found %.9f, published %.9f\n", row,
                   engine, cost, optimal);
      std::exit(1);
    };
    for (std::size_t k = 0; k < rows.size(); ++k) {
      const std::size_t i = rows[k];
      const hpcplan::env::ScenarioRow& row = scenario.rows[i];
      RowTimes t;
      t.row = i;
      t.bucket = row.bucket;
      t.group = static_cast<int>(static_cast<long>(row.bucket) * args.groups / (max_bucket + 1));
      t.optimal = row.optimal;
      const double tol = args.tolerance * std::max(1.0, row.optimal);
      const int order_even[kEngines] = {jps, lattice, wastar, textbook_astar};
      const int order_odd[kEngines] = {textbook_astar, wastar, lattice, jps};
      for (int e : (k % 2 ? order_odd : order_even)) {
        if (e == textbook_astar) {
          hpcplan::Stopwatch clock;
          const textbook::Answer a =
              astar.search(row.start[0], row.start[1], row.goal[0], row.goal[1]);
          t.us[e] = clock.milliseconds() * 1000.0;
          t.cost[e] = a.length;
          t.expanded[e] = a.expanded;
          check(a.length < 0 || std::abs(a.length - row.optimal) > tol, i, kEngineName[e], a.length,
                row.optimal);
        } else {
          const auto r = hpcplan::run_scenario_rows(grid, hpcplan::Connectivity::seed_pairs,
                                                    scenario, {i}, opt[e]);
          t.us[e] = r.front().time_us;
          t.cost[e] = r.front().cost;
          t.expanded[e] = r.front().expanded;
          const double c = r.front().cost;
          const bool bad =
              r.front().status != hpcplan::Status::solved ||
              (e == wastar ? c < row.optimal - tol || c > args.weight * row.optimal + tol
                           : std::abs(c - row.optimal) > tol);
          check(bad, i, kEngineName[e], c, row.optimal);
        }
      }
      out.push_back(t);
    }

    // Per group: rows, buckets, median time of each engine, ratios textbook / ours.
    const std::string map_name = std::filesystem::path(map_path).filename().string();
    std::ostringstream csv;
    csv << "map,group,first_bucket,last_bucket,rows,median_optimal";
    for (const char* e : kEngineName) csv << ",p50_us_" << e;
    for (const char* e : kEngineName) csv << ",mean_expanded_" << e;
    csv << ",ratio_textbook_jps,ratio_textbook_lattice,ratio_textbook_wastar,"
           "wastar_mean_subopt,wastar_max_subopt\n";
    std::printf("%s: %d x %d, %zu of %zu rows, weighted A* w = %g\n", map_name.c_str(), tmap.width,
                tmap.height, out.size(), total, args.weight);
    std::printf(
        "load (median of %d): ours %.2f ms, textbook %.2f ms; textbook's per-query reset "
        "%.1f µs\n",
        args.loads, median(load_ours), median(load_textbook), median(reset_us));
    std::printf(
        "| group | buckets | rows | median L | A* JPS µs | A* lattice µs | wA* µs | "
        "textbook µs | textbook/JPS | textbook/lattice | textbook/wA* | wA* cost/L "
        "mean (max) |\n|---|---|---|---|---|---|---|---|---|---|---|---|\n");
    auto report = [&](const std::string& label, const std::vector<const RowTimes*>& members) {
      if (members.empty()) return;
      std::vector<double> us[kEngines], optimal;
      double expanded[kEngines] = {};
      double sub_sum = 0, sub_max = 0;
      int first = 1 << 30, last = 0;
      for (const RowTimes* t : members) {
        for (int e = 0; e < kEngines; ++e) {
          us[e].push_back(t->us[e]);
          expanded[e] += static_cast<double>(t->expanded[e]);
        }
        optimal.push_back(t->optimal);
        const double sub = t->optimal > 0 ? t->cost[wastar] / t->optimal : 1.0;
        sub_sum += sub;
        sub_max = std::max(sub_max, sub);
        first = std::min(first, t->bucket);
        last = std::max(last, t->bucket);
      }
      const double m = static_cast<double>(members.size());
      double p50[kEngines];
      for (int e = 0; e < kEngines; ++e) p50[e] = median(us[e]);
      auto ratio = [&](int e) { return p50[e] > 0 ? p50[textbook_astar] / p50[e] : 0.0; };
      std::printf(
          "| %s | %d-%d | %zu | %.1f | %.1f | %.1f | %.1f | %.1f | %.1f | %.1f | %.1f | "
          "%.4f (%.4f) |\n",
          label.c_str(), first, last, members.size(), median(optimal), p50[jps], p50[lattice],
          p50[wastar], p50[textbook_astar], ratio(jps), ratio(lattice), ratio(wastar), sub_sum / m,
          sub_max);
      csv << map_name << ',' << label << ',' << first << ',' << last << ',' << members.size() << ','
          << median(optimal);
      for (double v : p50) csv << ',' << v;
      for (double v : expanded) csv << ',' << v / m;
      csv << ',' << ratio(jps) << ',' << ratio(lattice) << ',' << ratio(wastar) << ','
          << sub_sum / m << ',' << sub_max << '\n';
    };
    for (int g = 0; g < args.groups; ++g) {
      std::vector<const RowTimes*> members;
      for (const RowTimes& t : out)
        if (t.group == g) members.push_back(&t);
      report(std::to_string(g), members);
    }
    std::vector<const RowTimes*> all;
    for (const RowTimes& t : out) all.push_back(&t);
    report("all", all);
    csv << "# load_ms_ours=" << median(load_ours) << " load_ms_textbook=" << median(load_textbook)
        << " textbook_reset_us=" << median(reset_us) << '\n';
    if (!args.csv.empty()) hpcplan::write_file_atomically(args.csv, csv.str());
    if (!args.rows_csv.empty()) {
      std::ostringstream r;
      r << "map,row,bucket,group,optimal";
      for (const char* e : kEngineName) r << ",us_" << e << ",cost_" << e << ",expanded_" << e;
      r << '\n';
      r.precision(10);
      for (const RowTimes& t : out) {
        r << map_name << ',' << t.row << ',' << t.bucket << ',' << t.group << ',' << t.optimal;
        for (int e = 0; e < kEngines; ++e)
          r << ',' << t.us[e] << ',' << t.cost[e] << ',' << t.expanded[e];
        r << '\n';
      }
      hpcplan::write_file_atomically(args.rows_csv, r.str());
    }
    return 0;
  } catch (const hpcplan::InputError& e) {
    usage_error(e.what());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "hpcplan_movingai_bench: error: %s\n", e.what());
    return 2;
  }
}
