// hpcplan._hpcplan: the engine's bindings, one part per area (grid, worlds, fluid, simulator),
// under the pure-Python package `hpcplan` that gives them their signatures and result types.
#include <string>

#include "bridge.hpp"
#include "hpcplan/cli/planners_options.hpp"
#include "hpcplan/core/error.hpp"
#include "hpcplan/io/planners_json.hpp"
#include "hpcplan/plan/planner_registry.hpp"

PYBIND11_MODULE(_hpcplan, m) {
  namespace py = pybind11;
  using hpcplan::python::StopSource;
  m.doc() = "hpcplan's engine (use the package hpcplan: hpcplan.grid, hpcplan.map3d, ...)";
  m.attr("__version__") = HPCPLAN_VERSION_STRING;  // the project's, as the checkpoints carry it
  // As the CLI's exit codes: bad input is a ValueError (exit 2), anything else that ends a run
  // a RuntimeError (exit 1), out of memory a MemoryError, each with the CLI's message.
  // pybind11's own exceptions (a wrong argument type, a Python error passing through) are left
  // to pybind11.
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const py::error_already_set&) {
      throw;
    } catch (const py::builtin_exception&) {
      throw;
    } catch (const hpcplan::InputError& e) {
      PyErr_SetString(PyExc_ValueError, hpcplan::one_line(e.what()).c_str());
    } catch (const std::bad_alloc&) {
      PyErr_SetString(PyExc_MemoryError,
                      "out of memory; lower the problem size (--max-states, --particles, "
                      "--memory-mb)");
    } catch (const std::exception& e) {
      PyErr_SetString(PyExc_RuntimeError, hpcplan::one_line(e.what()).c_str());
    }
  });
  py::class_<StopSource>(m, "StopSource",
                         "A request to end a call early, from any thread: a search or plan "
                         "answers with status 'cancelled', a fluid step or a simulation ends at "
                         "its next frame's end.")
      .def(py::init<>())
      .def("request_stop", &StopSource::request_stop,
           "Asks every call given this source to stop; True the first time.")
      .def_property_readonly("stop_requested", &StopSource::stop_requested);
  m.def(
      "planners",
      [](const std::string& world) {
        // --world parsed by the CLI's own option: the same setting names, the same refusal.
        std::string setting;
        CLI::App command("hpcplan planners");
        hpcplan::cli::add_planners_world_option(&command, setting);
        if (!world.empty()) hpcplan::python::parse_options(command, {"--world=" + world});
        return hpcplan::python::to_python(
            hpcplan::to_json(hpcplan::plan::PlannerRegistry::get(), setting));
      },
      py::arg("world") = "");
  hpcplan::python::install_fork_guard();
  hpcplan::python::bind_grid(m);
  hpcplan::python::bind_worlds(m);
  hpcplan::python::bind_fluid(m);
  hpcplan::python::bind_sim(m);
  hpcplan::python::bind_scen(m);
}
