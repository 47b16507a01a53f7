// hpcplan.sim: seed 000's simulator from Python (hpcplan sim's options, run and answers).
#include <string>
#include <variant>
#include <vector>

#include "bridge.hpp"
#include "hpcplan/cli/sim_options.hpp"
#include "hpcplan/io/sim_report.hpp"
#include "hpcplan/io/table.hpp"

namespace hpcplan::python {

namespace {

// A table's rows as dicts, column name to value (None for an empty cell).
py::list rows_of(const io::Table& t) {
  py::list rows;
  for (const std::vector<io::Cell>& row : t.rows) {
    py::dict d;
    for (std::size_t k = 0; k < row.size(); ++k)
      d[py::str(t.columns[k])] = std::visit(
          [](const auto& v) -> py::object {
            using T = std::decay_t<decltype(v)>;
            if constexpr (std::is_same_v<T, std::monostate>)
              return py::none();
            else
              return py::cast(v);
          },
          row[k]);
    rows.append(std::move(d));
  }
  return rows;
}

py::tuple run(const std::vector<std::string>& tokens, const StopSource* stop) {
  cli::SimArgs a;
  CLI::App command("hpcplan sim");
  cli::add_sim_options(&command, a);
  parse_options(command, tokens);
  a.threads = call_threads(a.threads);
  const io::SimInvocation inv = call_released<io::SimInvocation>(
      [&](const cli::RunControl& control) {
        const OmpThreads threads(a.threads);  // run_sim sets --threads on this thread: put back
        return cli::run_sim(a, control);
      },
      stop, OnCtrlC::interrupt);
  const bool timings = !a.no_timings;
  return py::make_tuple(to_python(io::to_json(inv)),
                        rows_of(io::sim_runs_table(inv.result.runs, timings)),
                        rows_of(io::sim_replans_table(inv.result.replans, timings)));
}

}  // namespace

void bind_sim(py::module_& m) {
  m.def("sim_options", [] {
    return describe_options<cli::SimArgs>(
        "hpcplan sim", [](CLI::App* c, cli::SimArgs& a) { cli::add_sim_options(c, a); });
  });
  m.def("sim_run", &run, py::arg("tokens"), py::arg("stop") = nullptr);
}

}  // namespace hpcplan::python
