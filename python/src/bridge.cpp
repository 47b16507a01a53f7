#include "bridge.hpp"

#include <Python.h>
#include <omp.h>
#include <pthread.h>
#include <pythread.h>
#include <unistd.h>

#include <algorithm>
#include <exception>
#include <utility>

#include "hpcplan/cli/option_catalog.hpp"
#include "hpcplan/core/error.hpp"
#include "hpcplan/python/interrupt_relay.hpp"

namespace hpcplan::python {

OmpThreads::OmpThreads(int threads) : before_(omp_get_max_threads()), set_(threads > 0) {
  if (set_) omp_set_num_threads(threads);
}

OmpThreads::~OmpThreads() {
  if (set_) omp_set_num_threads(before_);
}

namespace {

// Whether this process's engine has run a call (and so, perhaps, started OpenMP's threads),
// and whether this process is a child forked after its parent's engine had.
std::atomic<bool> engine_ran{false};
std::atomic<bool> forked_after_engine{false};

extern "C" void after_fork_in_child() {
  if (engine_ran.load()) forked_after_engine = true;
}

}  // namespace

int call_threads(int requested) {
  return forked_after_engine.load() ? 1 : requested;
}

void install_fork_guard() {
  static const int installed = pthread_atfork(nullptr, nullptr, after_fork_in_child);
  (void)installed;
}

void parse_options(CLI::App& command, const std::vector<std::string>& tokens) {
  std::vector<std::string> reversed(tokens.rbegin(), tokens.rend());  // CLI11's order
  try {
    command.parse(reversed);
  } catch (const CLI::ParseError& e) {
    throw InputError(e.what());
  }
}

py::list describe(const CLI::App& command) {
  py::list out;
  for (const cli::OptionInfo& o : cli::describe_options(command)) {
    py::dict d;
    d["name"] = o.name;
    d["option"] = o.option;
    d["kind"] = o.kind;
    d["default"] = o.default_text;
    d["required"] = o.required;
    d["range"] = o.range;
    d["choices"] = o.choices;
    d["help"] = o.help;
    d["group"] = o.group;
    out.append(std::move(d));
  }
  return out;
}

py::object to_python(const nlohmann::json& v) {
  switch (v.type()) {
    case nlohmann::json::value_t::null:
    case nlohmann::json::value_t::discarded:
      return py::none();
    case nlohmann::json::value_t::boolean:
      return py::bool_(v.get<bool>());
    case nlohmann::json::value_t::number_integer:
      return py::int_(v.get<std::int64_t>());
    case nlohmann::json::value_t::number_unsigned:
      return py::int_(v.get<std::uint64_t>());
    case nlohmann::json::value_t::number_float:
      return py::float_(v.get<double>());
    case nlohmann::json::value_t::string:
      return py::str(v.get_ref<const std::string&>());
    case nlohmann::json::value_t::array: {
      py::list list;
      for (const nlohmann::json& item : v) list.append(to_python(item));
      return list;
    }
    case nlohmann::json::value_t::object: {
      py::dict dict;
      for (auto it = v.begin(); it != v.end(); ++it)
        dict[py::str(it.key())] = to_python(it.value());
      return dict;
    }
    case nlohmann::json::value_t::binary:
      break;
  }
  throw RunError("a result holds a value JSON cannot carry");
}

namespace {

// Python's main thread: read again in a forked child, whose main thread is the one that forked.
bool on_main_thread() {
  static pid_t read_in = 0;
  static unsigned long main_ident = 0;
  if (read_in != getpid()) {
    main_ident =
        py::module_::import("threading").attr("main_thread")().attr("ident").cast<unsigned long>();
    read_in = getpid();
  }
  return PyThread_get_thread_ident() == main_ident;
}

// The control of one call: its own stop source (linked to the user's) and interruption flag.
struct CallStop {
  std::stop_source cancel;
  std::atomic<const char*> interruption{nullptr};
};

}  // namespace

void run_released(const std::function<void(const cli::RunControl&)>& work, const StopSource* stop,
                  OnCtrlC on_ctrl_c) {
  engine_ran = true;
  auto state = std::make_shared<CallStop>();
  cli::RunControl control;
  control.cancel = state->cancel.get_token();
  control.interruption = [state] { return state->interruption.load(); };
  std::optional<std::stop_callback<std::function<void()>>> link;
  if (stop != nullptr)
    link.emplace(stop->token(), std::function<void()>([state] { state->cancel.request_stop(); }));

  if (!on_main_thread()) {  // where Python runs no signal handler, nothing to relay
    py::gil_scoped_release release;
    work(control);
    return;
  }
  // On the main thread: SIGINT is relayed to the call's stop for as long as it runs
  // (interrupt_relay.hpp); Python's own handler records it too, for the KeyboardInterrupt below.
  std::exception_ptr failure;
  {
    py::gil_scoped_release release;
    try {
      InterruptRelay::run([&] { work(control); },
                          [state, on_ctrl_c] {
                            state->interruption = "KeyboardInterrupt";
                            if (on_ctrl_c == OnCtrlC::cancel) state->cancel.request_stop();
                          });
    } catch (...) {
      failure = std::current_exception();
    }
  }
  // Ctrl-C wins over what the stopped work said: the handler's exception (KeyboardInterrupt).
  if (PyErr_CheckSignals() != 0) throw py::error_already_set();
  if (failure) std::rethrow_exception(failure);
}

}  // namespace hpcplan::python
