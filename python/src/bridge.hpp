#pragma once
// What every binding of the Python module shares: parsing keyword arguments with the CLI's own
// options, JSON results as Python objects, NumPy arrays, the user's stop source, and running a
// long call with the GIL released while Ctrl-C stays live.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <atomic>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <stop_token>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "hpcplan/cli/run_control.hpp"

namespace hpcplan::python {

namespace py = pybind11;

// hpcplan.StopSource: a request to end a call early, from any Python thread (std::stop_source's
// model). A search or plan then answers with status cancelled; a fluid step or a simulation
// ends at its next frame's end.
class StopSource {
 public:
  bool request_stop() { return source_.request_stop(); }
  bool stop_requested() const { return source_.stop_requested(); }
  std::stop_token token() const { return source_.get_token(); }

 private:
  std::stop_source source_;
};

// Parses `tokens` ("--name=value", as the Python side builds them from keyword arguments) with
// `command`'s options: a bad value is the CLI's own message, as an InputError (ValueError).
void parse_options(CLI::App& command, const std::vector<std::string>& tokens);

// A subcommand's options parsed into a fresh copy of their arguments, with the CLI11 command
// built once per thread and `key` (building hpcplan grid's costs about 40 us, three times a
// small query's search): each parse starts again from the values registration left.
// `register_options(app, args)` registers them.
template <class Args, class Register>
Args parse_cached(const std::string& key, const std::vector<std::string>& tokens,
                  Register register_options) {
  struct Entry {
    Args args;
    CLI::App app;
    Args defaults;
  };
  thread_local std::map<std::string, std::unique_ptr<Entry>> cache;
  std::unique_ptr<Entry>& e = cache[key];
  if (!e) {
    e = std::make_unique<Entry>();
    e->app.name(key);
    register_options(&e->app, e->args);
    e->defaults = e->args;
  }
  e->args = e->defaults;
  e->app.clear();
  parse_options(e->app, tokens);
  return e->args;
}

// The options `command` declares (cli/option_catalog.hpp), as a list of dicts.
py::list describe(const CLI::App& command);

// The same for the command `register_options(app, args)` registers (the module's *_options()).
template <class Args, class Register>
py::list describe_options(const std::string& name, Register register_options) {
  Args args;
  CLI::App command(name);
  register_options(&command, args);
  return describe(command);
}

// A JSON value as the Python object json.loads would make of its text.
py::object to_python(const nlohmann::json& value);

// A read-only NumPy view of `data` with this shape and these strides (bytes), kept alive by
// `owner`.
template <class T>
py::array read_only_view(const T* data, std::vector<py::ssize_t> shape,
                         std::vector<py::ssize_t> strides, py::handle owner) {
  py::array a(py::dtype::of<T>(), std::move(shape), std::move(strides), data, owner);
  py::detail::array_proxy(a.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
  return a;
}

// The OpenMP threads of the calling thread for one call, put back after it however it ends: one
// thread (Python's main thread, most often) makes many calls, and one call's --threads must not
// become the next call's. 0 leaves them as they are.
class OmpThreads {
 public:
  explicit OmpThreads(int threads);
  ~OmpThreads();
  OmpThreads(const OmpThreads&) = delete;
  OmpThreads& operator=(const OmpThreads&) = delete;

 private:
  int before_;
  bool set_;
};

// A call's OpenMP threads in this process: `requested` (0: the default), or 1 in a process
// forked after this one's engine had run. GNU OpenMP's thread pool does not survive fork(): the
// child's first parallel region with more than one thread waited forever for the parent's
// threads (multiprocessing's default start method on Linux is fork). A team of one needs no
// pool, so such a child runs every call on one thread, and says so in its results' threads.
int call_threads(int requested);

// Registers the fork handler behind call_threads (once, at import).
void install_fork_guard();

// What a call does on a Ctrl-C: end at its next safe boundary with its checkpoint
// (interrupt: the dense lattice search with checkpoint=, a fluid step, a simulation), or
// stop at once (cancel: everything else, whose answer is then status cancelled).
enum class OnCtrlC { cancel, interrupt };

// Runs `work(control)` on the calling thread with the GIL released. On Python's main thread a
// Ctrl-C (SIGINT) meanwhile stops the work through `control`, as `on_ctrl_c` says
// (interrupt_relay.hpp), and once the work is back Python runs its handler, whose
// KeyboardInterrupt is raised. `stop`, when given, also stops it (from any thread).
void run_released(const std::function<void(const cli::RunControl&)>& work, const StopSource* stop,
                  OnCtrlC on_ctrl_c);

template <class R>
R call_released(const std::function<R(const cli::RunControl&)>& work, const StopSource* stop,
                OnCtrlC on_ctrl_c = OnCtrlC::cancel) {
  std::optional<R> result;
  run_released([&](const cli::RunControl& control) { result.emplace(work(control)); }, stop,
               on_ctrl_c);
  return std::move(*result);
}

// The module's parts.
void bind_grid(py::module_& m);
void bind_worlds(py::module_& m);
void bind_fluid(py::module_& m);
void bind_sim(py::module_& m);
void bind_scen(py::module_& m);

}  // namespace hpcplan::python
