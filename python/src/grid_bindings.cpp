// hpcplan.grid: the GOG lattice planner (hpcplan grid's options and answers) and the field
// itself for bulk queries.
#include <algorithm>
#include <cstdint>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "bridge.hpp"
#include "hpcplan/cli/grid_options.hpp"
#include "hpcplan/core/error.hpp"
#include "hpcplan/env/gog.hpp"
#include "hpcplan/plan/grid_planner.hpp"

namespace hpcplan::python {

namespace {

// A GOG field built once from hpcplan grid's field options, shared by every query and solve
// on it (immutable: any number of threads may use it at once).
struct Field {
  GridProblem problem;  // dims, extent and the field's parameters as given
  std::shared_ptr<const GogField> field;
};

Field make_field(const std::vector<std::string>& tokens) {
  cli::GridArgs a;
  CLI::App command("hpcplan grid");
  cli::add_grid_options(&command, a);
  parse_options(command, tokens);
  validate(a.problem, a.options);
  return {a.problem,
          std::make_shared<const GogField>(a.problem.dims, a.problem.extent, a.problem.gog)};
}

// The lattice states of an integer array: one state (shape (dims,)) or many (shape (n, dims)).
py::array_t<std::int64_t> states_of(const py::array& states, int dims) {
  const char kind = states.dtype().kind();
  if (kind != 'i' && kind != 'u')
    throw py::type_error("states must be an integer array, not of dtype " +
                         py::str(states.dtype()).cast<std::string>());
  auto s = py::array_t<std::int64_t, py::array::c_style | py::array::forcecast>::ensure(states);
  const bool one = s.ndim() == 1, many = s.ndim() == 2;
  if (!(one || many) || s.shape(s.ndim() - 1) != dims)
    throw InputError("states must have shape (" + std::to_string(dims) + ",) or (n, " +
                     std::to_string(dims) + ") for this " + std::to_string(dims) +
                     "-dimensional field");
  return s;
}

// Free or not, per state, from the field's per-axis level tables: a state is blocked when its
// levels summed over the axes reach the threshold; a state outside the box is not free.
py::object free_states(const Field& f, const py::array& states) {
  const GogField& field = *f.field;
  const int dims = field.dims();
  const py::array_t<std::int64_t> s = states_of(states, dims);
  const std::int64_t* in = s.data();
  const py::ssize_t n = s.ndim() == 1 ? 1 : s.shape(0);
  py::array_t<bool> out(n);
  bool* free = out.mutable_data();
  auto decide = [&] {
    std::vector<const std::uint8_t*> tables(dims);
    for (int k = 0; k < dims; ++k) tables[k] = field.level_table(k);
    const std::int64_t extent = field.extent();
    const int threshold = field.threshold();
    for (py::ssize_t i = 0; i < n; ++i) {
      const std::int64_t* c = in + i * dims;
      int sum = 0;
      bool inside = true;
      for (int k = 0; k < dims && inside; ++k) {
        inside = c[k] >= 0 && c[k] < extent;
        if (inside) sum += tables[k][c[k]];
      }
      free[i] = inside && sum < threshold;
    }
  };
  if (n >= 65536) {
    py::gil_scoped_release release;
    decide();
  } else {
    decide();
  }
  if (s.ndim() == 1) return py::bool_(free[0]);
  return out;
}

// The path's lattice states as an (n, dims) int32 array.
py::array path_array(const std::vector<std::vector<int>>& path, int dims) {
  py::array_t<std::int32_t> a(
      {static_cast<py::ssize_t>(path.size()), static_cast<py::ssize_t>(dims)});
  std::int32_t* out = a.mutable_data();
  for (const std::vector<int>& state : path) out = std::copy(state.begin(), state.end(), out);
  return a;
}

py::tuple solve(const std::vector<std::string>& tokens, const StopSource* stop,
                const Field* on_field) {
  auto a = std::make_shared<cli::GridArgs>(parse_cached<cli::GridArgs>(
      "hpcplan grid", tokens,
      [](CLI::App* c, cli::GridArgs& args) { cli::add_grid_options(c, args); }));
  if (on_field != nullptr) {
    const GridProblem& f = on_field->problem;
    const GogParams &x = f.gog, &y = a->problem.gog;
    if (f.dims != a->problem.dims || f.extent != a->problem.extent || x.seed != y.seed ||
        x.shift_p != y.shift_p || x.shift_v != y.shift_v || x.threshold != y.threshold ||
        x.density != y.density)
      throw InputError("the solve's field options differ from its Field's");
  }
  a->options.threads = call_threads(a->options.threads);
  // With a checkpoint, Ctrl-C ends the dense search at its next level or bucket with the
  // checkpoint written (then KeyboardInterrupt); without one it cancels the search.
  const OnCtrlC on_ctrl_c = a->options.checkpoint.empty() ? OnCtrlC::cancel : OnCtrlC::interrupt;
  struct Answer {
    GridReport report;
    nlohmann::json json;
  };
  Answer answer = call_released<Answer>(
      [&](const cli::RunControl& control) {
        cli::prepare_grid_run(*a, 0, 1, control);
        Answer r;
        r.report = on_field != nullptr ? solve_grid(*on_field->field, a->problem, a->options)
                                       : solve_grid(a->problem, a->options);
        r.json = cli::finish_grid_run(r.report, *a, control);
        r.json.erase("path");  // given as an array instead
        return r;
      },
      stop, on_ctrl_c);
  py::object path = py::none();
  if (a->options.keep_path && answer.report.result.status == Status::solved)
    path = path_array(answer.report.result.path, answer.report.problem.dims);
  return py::make_tuple(to_python(answer.json), path);
}

}  // namespace

void bind_grid(py::module_& m) {
  m.def("grid_options", [] {
    return describe_options<cli::GridArgs>(
        "hpcplan grid", [](CLI::App* c, cli::GridArgs& a) { cli::add_grid_options(c, a); });
  });
  m.def(
      "grid_solve",
      [](const std::vector<std::string>& tokens, const StopSource* stop) {
        return solve(tokens, stop, nullptr);
      },
      py::arg("tokens"), py::arg("stop") = nullptr);

  py::class_<Field>(m, "Field", "A GOG field built once (hpcplan.grid.Field wraps it)")
      .def(py::init(&make_field), py::arg("tokens"))
      .def_property_readonly("dims", [](const Field& f) { return f.field->dims(); })
      .def_property_readonly("extent", [](const Field& f) { return f.field->extent(); })
      .def_property_readonly("threshold", [](const Field& f) { return f.field->threshold(); })
      .def_property_readonly("blocked_fraction",
                             [](const Field& f) { return f.field->blocked_fraction(); })
      .def_property_readonly("seed", [](const Field& f) { return f.field->params().seed; })
      .def_property_readonly("gog_shift_p",
                             [](const Field& f) { return f.field->params().shift_p; })
      .def_property_readonly("gog_shift_v",
                             [](const Field& f) { return f.field->params().shift_v; })
      .def_property_readonly("density", [](const Field& f) { return f.field->params().density; })
      .def("free", &free_states, py::arg("states"))
      .def(
          "levels",
          [](py::object self, int axis) {
            const Field& f = self.cast<const Field&>();
            if (axis < 0 || axis >= f.field->dims())
              throw InputError("axis " + std::to_string(axis) + " is not in [0, " +
                               std::to_string(f.field->dims()) + ")");
            return read_only_view(f.field->level_table(axis), {f.field->extent()},
                                  {static_cast<py::ssize_t>(sizeof(std::uint8_t))}, self);
          },
          py::arg("axis"))
      .def(
          "solve",
          [](const Field& f, const std::vector<std::string>& tokens, const StopSource* stop) {
            return solve(tokens, stop, &f);
          },
          py::arg("tokens"), py::arg("stop") = nullptr);
}

}  // namespace hpcplan::python
