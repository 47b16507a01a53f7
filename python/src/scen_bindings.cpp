// hpcplan.scen: a MovingAI scenario file run from Python (hpcplan scen's options, its rows and
// its summary).
#include <cstdint>
#include <string>
#include <vector>

#include "bridge.hpp"
#include "hpcplan/cli/scen_options.hpp"
#include "hpcplan/core/stopwatch.hpp"
#include "hpcplan/io/scenario_report.hpp"
#include "hpcplan/plan/scenario_run.hpp"

namespace hpcplan::python {

namespace {

py::tuple coordinates(const std::vector<int>& c) {
  py::tuple t(c.size());
  for (std::size_t a = 0; a < c.size(); ++a) t[a] = py::int_(c[a]);
  return t;
}

// One row as the CSV's columns (`hpcplan scen --csv`), start and goal as tuples (x first), the
// numbers at full precision.
py::dict row_of(const ScenarioRowResult& r) {
  py::dict d;
  d["row"] = r.row;
  d["bucket"] = r.bucket;
  d["start"] = coordinates(r.start);
  d["goal"] = coordinates(r.goal);
  d["optimal"] = r.optimal;
  d["cost"] = r.cost;
  d["status"] = std::string(to_string(r.status));
  d["expanded"] = r.expanded;
  d["hops"] = r.hops;
  d["time_us"] = r.time_us;
  d["mismatch"] = r.mismatch;
  return d;
}

// Runs the scenario as `hpcplan scen` does (serially). Returns the summary (`--json`'s object),
// the rows, and whether a stop ended it early: then the rows are those finished before it (the
// row under way, cancelled, is dropped, as it says nothing about the planner), and the summary
// and the files (csv=, output=) are theirs.
py::tuple run(const std::vector<std::string>& tokens, const StopSource* stop) {
  cli::ScenArgs a;
  CLI::App command("hpcplan scen");
  cli::add_scen_options(&command, a);
  parse_options(command, tokens);
  a.options.threads = call_threads(a.options.threads);
  struct Answer {
    nlohmann::json report;
    std::vector<ScenarioRowResult> rows;
    bool cancelled = false;
  };
  Answer answer = call_released<Answer>(
      [&](const cli::RunControl& control) {
        cli::PreparedScen prepared = cli::prepare_scen_run(a, control);
        prepared.info.ranks = 1;
        prepared.info.split = "serial";
        Answer r;
        Stopwatch wall;
        r.rows = run_scenario_rows(prepared.grid, prepared.connectivity, prepared.scenario,
                                   prepared.rows, a.options);
        prepared.info.wall_ms = wall.milliseconds();
        if (control.cancel.stop_requested() && !r.rows.empty() &&
            r.rows.back().status == Status::cancelled)
          r.rows.pop_back();
        r.cancelled = r.rows.size() < prepared.rows.size();
        const ScenarioSummary summary = cli::finish_scen_run(a, prepared, r.rows);
        r.report = to_json(prepared.info, summary);
        return r;
      },
      stop, OnCtrlC::cancel);
  py::list rows;
  for (const ScenarioRowResult& r : answer.rows) rows.append(row_of(r));
  return py::make_tuple(to_python(answer.report), std::move(rows), answer.cancelled);
}

}  // namespace

void bind_scen(py::module_& m) {
  m.def("scen_options", [] {
    return describe_options<cli::ScenArgs>(
        "hpcplan scen", [](CLI::App* c, cli::ScenArgs& a) { cli::add_scen_options(c, a); });
  });
  m.def("scen_run", &run, py::arg("tokens"), py::arg("stop") = nullptr);
}

}  // namespace hpcplan::python
