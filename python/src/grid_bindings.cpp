// hpcplan.grid: the lattice planner (hpcplan grid's options and answers) on the GOG field or on
// an occupancy array the caller brings (read in place), the field itself for bulk queries, and
// the map files as NumPy arrays.
#include <algorithm>
#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "bridge.hpp"
#include "hpcplan/cli/grid_options.hpp"
#include "hpcplan/core/error.hpp"
#include "hpcplan/env/config_space.hpp"
#include "hpcplan/env/gog.hpp"
#include "hpcplan/env/occupancy_grid.hpp"
#include "hpcplan/env/occupancy_io.hpp"
#include "hpcplan/plan/distance_field.hpp"
#include "hpcplan/plan/grid_planner.hpp"

namespace hpcplan::python {

namespace {

// A GOG field built once from hpcplan grid's field options, or an occupancy grid built once
// from an array, shared by every query and solve on it (immutable: any number of threads may
// use it at once).
struct Field {
  GridProblem problem;  // dims, extent and the field's parameters as given (or the grid's)
  std::shared_ptr<const GogField> field;  // null for an occupancy grid (problem.occupancy)

  bool occupancy() const { return problem.occupancy != nullptr; }
  int dims() const { return problem.dims; }
  int extent() const { return problem.extent; }
};

// The dtype's name, as NumPy writes it ("float64").
std::string dtype_name(const py::array& a) {
  return py::str(a.dtype()).cast<std::string>();
}

// An occupancy array's bytes, checked (with the GIL held): a NumPy bool or uint8 array of 1 to
// 16 dimensions, C-contiguous, read where it lies (no copy is made, so none is made silently:
// an array that would need one is refused with what to do instead).
struct ArrayBytes {
  const std::uint8_t* data = nullptr;
  std::vector<std::int64_t> shape;  // NumPy order
};

ArrayBytes occupancy_bytes(const py::handle& object) {
  if (!py::isinstance<py::array>(object))
    throw py::type_error(
        "occupancy must be a NumPy array (bool or uint8, nonzero = blocked), not " +
        py::str(py::type::of(object).attr("__name__")).cast<std::string>());
  const auto a = py::reinterpret_borrow<py::array>(object);
  if (a.ndim() < 1 || a.ndim() > 16)
    throw InputError("occupancy must have 1 to 16 dimensions, not " + std::to_string(a.ndim()));
  const char kind = a.dtype().kind();
  if (!((kind == 'b' || kind == 'u') && a.itemsize() == 1))
    throw InputError("occupancy must be a bool or uint8 array (nonzero = blocked), not " +
                     dtype_name(a) + "; convert it with a.astype(np.uint8)");
  if (!(a.flags() & py::array::c_style))
    throw InputError(
        "occupancy must be C-contiguous (it is read in place, not copied); pass "
        "np.ascontiguousarray(a)");
  ArrayBytes b;
  b.data = static_cast<const std::uint8_t*>(a.data());
  b.shape.assign(a.shape(), a.shape() + a.ndim());
  return b;
}

// The grid of checked bytes: one bit per cell. Needs no GIL (the caller holds the array).
std::shared_ptr<const OccupancyGrid> grid_of(const ArrayBytes& b) {
  return std::make_shared<const OccupancyGrid>(occupancy_from_bytes(b.data, b.shape));
}

Field field_of_array(const py::object& array) {
  const ArrayBytes bytes = occupancy_bytes(array);
  std::shared_ptr<const OccupancyGrid> grid;
  {
    py::gil_scoped_release release;  // a large array's bits take a while; `array` is held
    grid = grid_of(bytes);
  }
  return {occupancy_problem(std::move(grid)), nullptr};
}

// The lattice states an occupancy grid's NumPy array of bits (nonzero = blocked), in NumPy
// order (the grid's axis 0 is the array's last axis), as bool: True = blocked.
py::array array_of_grid(const OccupancyGrid& grid) {
  const int d = grid.dims();
  std::vector<py::ssize_t> shape(d);
  for (int a = 0; a < d; ++a) shape[d - 1 - a] = grid.size(a);
  py::array_t<bool> out(shape);
  bool* cells = out.mutable_data();
  {
    py::gil_scoped_release release;
    const std::uint64_t width = static_cast<std::uint64_t>(grid.size(0));
    const std::uint64_t rows = grid.cells() / width;
    const std::uint64_t row_bits = d > 1 ? static_cast<std::uint64_t>(grid.stride(1)) : 0;
    for (std::uint64_t r = 0; r < rows; ++r) {
      bool* row = cells + r * width;
      const std::uint64_t base = r * row_bits;
      for (std::uint64_t x = 0; x < width; x += 64) {
        const int n = static_cast<int>(std::min<std::uint64_t>(64, width - x));
        const std::uint64_t free = grid.bits(base + x, n);
        for (int k = 0; k < n; ++k) row[x + k] = ((free >> k) & 1) == 0;
      }
    }
  }
  return out;
}

py::array load_map_array(const std::string& path, const std::string& terrain) {
  const env::MapFormat format = env::map_format_of(path);
  env::Terrain t = env::Terrain::ground;
  if (terrain == "water")
    t = env::Terrain::water;
  else if (terrain != "ground")
    throw InputError("terrain must be ground or water, not '" + terrain + "'");
  if (t == env::Terrain::water && format != env::MapFormat::movingai)
    throw InputError("terrain='water' is a .map's class of cells; '" + path + "' is a " +
                     std::string(env::to_string(format)) + " file");
  OccupancyGrid grid = [&] {
    py::gil_scoped_release release;
    return env::load_occupancy(path, t);
  }();
  return array_of_grid(grid);
}

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
// On an occupancy grid, a state is its cell (x first), free when inside the shape and unblocked.
py::object free_states(const Field& f, const py::array& states) {
  const int dims = f.dims();
  const py::array_t<std::int64_t> s = states_of(states, dims);
  const std::int64_t* in = s.data();
  const py::ssize_t n = s.ndim() == 1 ? 1 : s.shape(0);
  py::array_t<bool> out(n);
  bool* free = out.mutable_data();
  auto decide_on_grid = [&] {
    const OccupancyGrid& grid = *f.problem.occupancy;
    std::vector<int> c(dims);
    for (py::ssize_t i = 0; i < n; ++i) {
      bool inside = true;
      for (int k = 0; k < dims && inside; ++k) {
        const std::int64_t v = in[i * dims + k];
        inside = v >= 0 && v < grid.size(k);
        c[k] = inside ? static_cast<int>(v) : 0;
      }
      free[i] = inside && grid.is_free(c);
    }
  };
  auto decide_on_gog = [&] {
    const GogField& field = *f.field;
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
  auto decide = [&] { f.occupancy() ? decide_on_grid() : decide_on_gog(); };
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

// The options that describe the GOG field, refused on an occupancy grid (the array is the
// field), named as the keyword arguments.
void refuse_gog_options(const cli::GridArgs& a) {
  std::vector<const CLI::Option*> options = a.gog_options;
  options.push_back(a.dims_option);
  for (const CLI::Option* o : options) {
    if (o == nullptr || o->count() == 0) continue;
    std::string name = o->get_name().substr(o->get_name().find_first_not_of('-'));
    std::replace(name.begin(), name.end(), '-', '_');
    throw InputError(name + "= describes the GOG field; occupancy= plans on the array's own " +
                     "shape and obstacles");
  }
  if (!a.map.empty()) throw InputError("map= and occupancy= both give the obstacles; give one");
}

// A configuration space a Python caller defines by its validity function: fn takes a (k, d)
// float64 array of states and returns k booleans. The lattice engines hand it whole batches
// (an expansion's successor ends, then their edges' samples), so the GIL is taken once per
// batch, only for the call. An exception from fn, or an answer of the wrong shape or type,
// ends the search as an InputError (ValueError) with one line.
class PythonSpace final : public ConfigSpace {
 public:
  // `resolution`: the absolute motion-check step (python_space: a fraction of the diagonal).
  PythonSpace(py::function fn, std::vector<AxisBounds> axes, double resolution)
      : ConfigSpace("python", std::move(axes), resolution), fn_(std::move(fn)) {}
  ~PythonSpace() override {
    py::gil_scoped_acquire gil;
    fn_ = py::function();
    pending_ = py::object();
  }

  // A KeyboardInterrupt or SystemExit raised inside fn (Ctrl-C lands there: the GIL is held
  // only while fn runs, so Python's handler raises it in fn) ended the search: it is raised
  // again once the call is back in Python, as itself, not as a ValueError. GIL held.
  void raise_pending() const {
    if (!pending_) return;
    py::object e = std::move(pending_);
    PyErr_SetObject(reinterpret_cast<PyObject*>(Py_TYPE(e.ptr())), e.ptr());
    throw py::error_already_set();
  }
  // What the search throws when fn raised one of those (caught by solve()).
  struct Aborted : std::runtime_error {
    Aborted() : std::runtime_error("valid= was interrupted") {}
  };

 protected:
  bool valid(const double* state) const override {
    std::uint8_t ok = 0;
    valid_batch(state, 1, &ok);
    return ok != 0;
  }
  void valid_batch(const double* states, std::size_t k, std::uint8_t* out) const override {
    const std::size_t d = static_cast<std::size_t>(dims());
    py::gil_scoped_acquire gil;
    py::array_t<double> batch({k, d});
    std::copy(states, states + k * d, batch.mutable_data());
    py::object answer;
    try {
      answer = fn_(batch);
    } catch (py::error_already_set& e) {
      if (!e.matches(PyExc_Exception)) {  // KeyboardInterrupt, SystemExit: not the user's bug
        pending_ = e.value();
        throw Aborted();
      }
      std::string what = e.what();
      what = what.substr(0, what.find('\n'));
      throw InputError("valid= raised " + what);
    }
    if (!py::isinstance<py::array>(answer))
      answer = py::module_::import("numpy").attr("asarray")(answer);
    const auto a = py::reinterpret_borrow<py::array>(answer);
    const char kind = a.dtype().kind();
    if (a.ndim() != 1 || static_cast<std::size_t>(a.shape(0)) != k ||
        !(kind == 'b' || kind == 'i' || kind == 'u'))
      throw InputError("valid= must return " + std::to_string(k) + " booleans for a (" +
                       std::to_string(k) + ", " + std::to_string(d) + ") array of states, got " +
                       py::str(a.attr("shape")).cast<std::string>() + " of " +
                       py::str(a.dtype()).cast<std::string>());
    // Nonzero is true, read in the answer's own type (256 is true, not a uint8 0).
    const py::array truth = kind == 'b' ? a : py::array(a.attr("__ne__")(0));
    const auto b = py::array_t<bool, py::array::forcecast>::ensure(truth);
    const auto view = b.unchecked<1>();
    for (std::size_t i = 0; i < k; ++i) out[i] = view(static_cast<py::ssize_t>(i)) ? 1 : 0;
  }

 private:
  py::function fn_;
  mutable py::object pending_;
};

// valid=, bounds= and periodic= as a space (GIL held): bounds a sequence of (low, high) pairs,
// periodic one boolean per axis (default none).
std::shared_ptr<const PythonSpace> python_space(const py::object& valid, const py::object& bounds,
                                                const py::object& periodic, double fraction) {
  if (!PyCallable_Check(valid.ptr()))
    throw InputError("valid= must be a function of a (k, d) array of states");
  if (bounds.is_none()) throw InputError("valid= needs bounds=[(low, high), ...], one per axis");
  std::vector<AxisBounds> axes;
  double diagonal = 0.0;
  try {
    for (const auto& pair : bounds) {
      const auto lh = py::cast<std::vector<double>>(pair);
      if (lh.size() != 2) throw InputError("bounds= must be (low, high) pairs, one per axis");
      axes.push_back({lh[0], lh[1], false});
      diagonal += (lh[1] - lh[0]) * (lh[1] - lh[0]);
    }
  } catch (const py::cast_error&) {
    throw InputError("bounds= must be (low, high) pairs of numbers, one per axis");
  }
  if (!periodic.is_none()) {
    std::vector<bool> flags;
    try {
      flags = py::cast<std::vector<bool>>(periodic);
    } catch (const py::cast_error&) {
      throw InputError("periodic= must be a sequence of booleans, one per axis");
    }
    if (flags.size() != axes.size())
      throw InputError("periodic= needs one flag per axis: " + std::to_string(axes.size()) +
                       ", got " + std::to_string(flags.size()));
    for (std::size_t i = 0; i < axes.size(); ++i) axes[i].periodic = flags[i];
  }
  // The motion-check step: a fraction of the bounds' diagonal, as for the benchmark spaces.
  diagonal = std::sqrt(diagonal);
  if (!std::isfinite(diagonal) || !(diagonal > 0.0))
    throw InputError("bounds= must span a finite, positive diagonal");
  return std::make_shared<PythonSpace>(py::reinterpret_borrow<py::function>(valid), std::move(axes),
                                       (fraction > 0.0 ? fraction : 0.01) * diagonal);
}

// One query: on the GOG field the options describe, on `on_field` (built once), or on the
// occupancy array `array` (read in place while the GIL is released; None: not given).
py::tuple solve(const std::vector<std::string>& tokens, const StopSource* stop,
                const Field* on_field, const py::object& array,
                const py::object& valid = py::none(), const py::object& bounds = py::none(),
                const py::object& periodic = py::none()) {
  auto a = std::make_shared<cli::GridArgs>(parse_cached<cli::GridArgs>(
      "hpcplan grid", tokens,
      [](CLI::App* c, cli::GridArgs& args) { cli::add_grid_options(c, args); }));
  std::shared_ptr<const PythonSpace> user_space;
  if (!valid.is_none()) {
    if (!array.is_none() || on_field != nullptr)
      throw InputError("valid= defines the space; it takes no occupancy= or Field");
    user_space = python_space(valid, bounds, periodic, a->resolution);
    a->space = user_space;
  } else if (!bounds.is_none() || !periodic.is_none()) {
    throw InputError("bounds= and periodic= describe a space of your own: give valid= too");
  }
  std::optional<ArrayBytes> bytes;
  if (!array.is_none()) bytes = occupancy_bytes(array);
  std::shared_ptr<const OccupancyGrid> grid =
      on_field != nullptr ? on_field->problem.occupancy : nullptr;
  if (bytes || grid) {
    refuse_gog_options(*a);
    a->dims_option = nullptr;  // the array gives the dimensions
  } else if (on_field != nullptr) {
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
  auto run = [&] {
    return call_released<Answer>(
        [&](const cli::RunControl& control) {
          cli::prepare_grid_run(*a, 0, 1, control);
          if (bytes) grid = grid_of(*bytes);  // the caller's frame holds `array` meanwhile
          if (grid) {
            GridProblem p = occupancy_problem(grid, a->problem.connectivity);
            p.start = std::move(a->problem.start);
            p.goal = std::move(a->problem.goal);
            a->problem = std::move(p);
          }
          Answer r;
          r.report = on_field != nullptr && on_field->field
                         ? solve_grid(*on_field->field, a->problem, a->options)
                         : solve_grid(a->problem, a->options);
          r.json = cli::finish_grid_run(r.report, *a, control);
          r.json.erase("path");  // given as an array instead
          return r;
        },
        stop, on_ctrl_c);
  };
  // A KeyboardInterrupt (or SystemExit) raised inside valid= comes back as itself.
  Answer answer = [&] {
    try {
      return run();
    } catch (const PythonSpace::Aborted&) {
      user_space->raise_pending();
      throw;
    }
  }();
  py::object path = py::none();
  if (a->options.keep_path && answer.report.result.status == Status::solved) {
    if (answer.report.cspace) {
      // On a configuration space: the path in its coordinates (start, vertices, goal).
      const auto& states = answer.report.cspace->path;
      const std::size_t d = static_cast<std::size_t>(answer.report.problem.dims);
      py::array_t<double> out({states.size(), d});
      for (std::size_t i = 0; i < states.size(); ++i)
        std::copy(states[i].begin(), states[i].end(), out.mutable_data() + i * d);
      path = std::move(out);
    } else {
      path = path_array(answer.report.result.path, answer.report.problem.dims);
    }
  }
  // The space (Python's function inside) is let go here, with the GIL held.
  a.reset();
  return py::make_tuple(to_python(answer.json), path);
}

// `values` moved into a capsule that owns it and viewed as a NumPy array of `shape` (C order):
// the field's own memory, no copy.
template <class T>
py::array owning_array(std::vector<T>&& values, const std::vector<std::int64_t>& shape) {
  auto* owned = new std::vector<T>(std::move(values));
  py::capsule owner(owned, [](void* p) { delete static_cast<std::vector<T>*>(p); });
  return py::array_t<T>(std::vector<py::ssize_t>(shape.begin(), shape.end()), owned->data(), owner);
}

// The distance field of the options' start (plan/distance_field.hpp) on the GOG field, a map
// file or the array `array`: the grid report as JSON, and the field as a NumPy array in NumPy
// order (int32 hops for BFS, float32 costs for Dijkstra, -1 where none).
py::tuple distance_field_of(const std::vector<std::string>& tokens, const StopSource* stop,
                            const py::object& array) {
  auto a = std::make_shared<cli::GridArgs>(parse_cached<cli::GridArgs>(
      "hpcplan grid", tokens,
      [](CLI::App* c, cli::GridArgs& args) { cli::add_grid_options(c, args); }));
  std::optional<ArrayBytes> bytes;
  if (!array.is_none()) {
    bytes = occupancy_bytes(array);
    refuse_gog_options(*a);
    a->dims_option = nullptr;
  }
  a->options.threads = call_threads(a->options.threads);
  struct Answer {
    DistanceFieldRun run;
    nlohmann::json json;
  };
  Answer answer = call_released<Answer>(
      [&](const cli::RunControl& control) {
        cli::prepare_grid_run(*a, 0, 1, control);
        if (bytes) {
          GridProblem p = occupancy_problem(grid_of(*bytes), a->problem.connectivity);
          p.start = std::move(a->problem.start);
          p.goal = std::move(a->problem.goal);
          a->problem = std::move(p);
        }
        Answer r;
        r.run = distance_field(a->problem, a->options);
        r.json = cli::finish_grid_run(r.run.report, *a, control);
        r.json.erase("path");
        r.json["field_complete"] = r.run.field.complete;
        r.json["field_reached"] = r.run.field.reached;
        return r;
      },
      stop, OnCtrlC::cancel);
  DistanceField& f = answer.run.field;
  const std::vector<std::int64_t> shape = f.numpy_shape();
  py::array values =
      f.hops ? owning_array(std::move(f.levels), shape) : owning_array(std::move(f.costs), shape);
  return py::make_tuple(to_python(answer.json), values);
}

}  // namespace

void bind_grid(py::module_& m) {
  m.def("grid_options", [] {
    return describe_options<cli::GridArgs>(
        "hpcplan grid", [](CLI::App* c, cli::GridArgs& a) { cli::add_grid_options(c, a); });
  });
  m.def(
      "grid_solve",
      [](const std::vector<std::string>& tokens, const StopSource* stop,
         const py::object& occupancy, const py::object& valid, const py::object& bounds,
         const py::object& periodic) {
        return solve(tokens, stop, nullptr, occupancy, valid, bounds, periodic);
      },
      py::arg("tokens"), py::arg("stop") = nullptr, py::arg("occupancy") = py::none(),
      py::arg("valid") = py::none(), py::arg("bounds") = py::none(),
      py::arg("periodic") = py::none());
  m.def("load_map", &load_map_array, py::arg("path"), py::arg("terrain") = "ground");
  m.def("grid_distance_field", &distance_field_of, py::arg("tokens"), py::arg("stop") = nullptr,
        py::arg("occupancy") = py::none());

  // A GOG field's parameter, None on an occupancy grid.
  auto gog = [](auto get) {
    return [get](const Field& f) -> py::object {
      return f.field ? py::cast(get(*f.field)) : py::none();
    };
  };
  py::class_<Field>(m, "Field",
                    "A GOG field or an occupancy grid built once (hpcplan.grid.Field wraps it)")
      .def(py::init(&make_field), py::arg("tokens"))
      .def_static("from_occupancy", &field_of_array, py::arg("occupancy"))
      .def_property_readonly("dims", &Field::dims)
      .def_property_readonly("extent", &Field::extent)
      .def_property_readonly("is_occupancy", &Field::occupancy)
      .def_property_readonly("shape",
                             [](const Field& f) -> py::object {
                               if (!f.occupancy()) return py::none();
                               const OccupancyGrid& g = *f.problem.occupancy;
                               py::tuple t(g.dims());
                               for (int a = 0; a < g.dims(); ++a)
                                 t[g.dims() - 1 - a] = py::int_(g.size(a));
                               return t;
                             })
      .def_property_readonly("grid_bytes",
                             [](const Field& f) -> std::uint64_t {
                               return f.occupancy() ? f.problem.occupancy->bytes() : 0;
                             })
      .def_property_readonly("threshold", gog([](const GogField& g) { return g.threshold(); }))
      .def_property_readonly("blocked_fraction",
                             [](const Field& f) {
                               if (f.field) return f.field->blocked_fraction();
                               return ObstacleSource(*f.problem.occupancy).blocked_fraction();
                             })
      .def_property_readonly("seed", gog([](const GogField& g) { return g.params().seed; }))
      .def_property_readonly("gog_shift_p",
                             gog([](const GogField& g) { return g.params().shift_p; }))
      .def_property_readonly("gog_shift_v",
                             gog([](const GogField& g) { return g.params().shift_v; }))
      .def_property_readonly("density", gog([](const GogField& g) { return g.params().density; }))
      .def("free", &free_states, py::arg("states"))
      .def("occupancy",
           [](const Field& f) {
             if (!f.occupancy()) throw InputError("a GOG Field has no occupancy array");
             return array_of_grid(*f.problem.occupancy);
           })
      .def(
          "levels",
          [](py::object self, int axis) {
            const Field& f = self.cast<const Field&>();
            if (!f.field)
              throw InputError(
                  "an occupancy Field has no GOG levels (occupancy() gives its cells)");
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
            return solve(tokens, stop, &f, py::none());
          },
          py::arg("tokens"), py::arg("stop") = nullptr);
}

}  // namespace hpcplan::python
