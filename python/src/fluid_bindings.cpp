// hpcplan.sph: the fluid stepped from Python (hpcplan sph's problem options and session), its
// particles seen as NumPy views of the engine's own arrays.
#include <omp.h>

#include <atomic>
#include <filesystem>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "bridge.hpp"
#include "hpcplan/cli/fluid_options.hpp"
#include "hpcplan/cli/fluid_session.hpp"
#include "hpcplan/cli/vtk_dir.hpp"
#include "hpcplan/core/atomic_file.hpp"
#include "hpcplan/core/error.hpp"
#include "hpcplan/io/sph_report.hpp"
#include "hpcplan/io/vtk_fluid.hpp"
#include "hpcplan/sph/checkpoint.hpp"
#include "hpcplan/sph/presets.hpp"

namespace hpcplan::python {

namespace {

class Fluid {
 public:
  Fluid(std::unique_ptr<cli::FluidSession> session, int threads, std::string backend)
      : session_(std::move(session)), threads_(threads), backend_(std::move(backend)) {
    total_.frames = session_->frame();
  }

  // One user of the fluid at a time: a step releases the GIL, so another Python thread could
  // otherwise read or step it mid-step.
  class Use {
   public:
    explicit Use(const Fluid& f) : f_(f) {
      if (f_.busy_.exchange(true))
        throw RunError("this Fluid is in use by another thread (a step is under way)");
    }
    ~Use() { f_.busy_ = false; }
    Use(const Use&) = delete;
    Use& operator=(const Use&) = delete;

   private:
    const Fluid& f_;
  };

  cli::FluidSession& session() { return *session_; }
  const cli::FluidSession& session() const { return *session_; }
  // The OpenMP threads a step runs: threads= as given, else OpenMP's default (1 in a child
  // forked after the engine ran: call_threads).
  int threads() const {
    const int t = call_threads(threads_);
    return t > 0 ? t : omp_get_max_threads();
  }
  const std::string& backend() const { return backend_; }

  py::dict step(std::uint64_t frames, const StopSource* stop) {
    const Use use(*this);
    if (frames == 0) throw InputError("frames must be at least 1");
    // The totals are kept inside the call, so that a step ended by Ctrl-C (which then raises
    // KeyboardInterrupt) still counts the frames it made.
    const sph::RunReport r = call_released<sph::RunReport>(
        [&](const cli::RunControl& control) {
          const OmpThreads threads(call_threads(threads_));
          sph::RunReport done =
              session_->advance(frames, {}, [&] { return control.should_stop(); });
          add_to_total(done);
          return done;
        },
        stop, OnCtrlC::interrupt);
    py::dict d;
    d["frame"] = r.frames;
    d["substeps"] = r.substeps;
    d["frame_ms"] = r.frame_ms;
    d["stable"] = r.stable;
    d["problem"] = r.problem;
    d["interrupted"] = r.interrupted;
    return d;
  }

  // The whole life's report: frames and substeps so far, every frame's times.
  void add_to_total(const sph::RunReport& r) {
    total_.frames = r.frames;
    total_.substeps += r.substeps;
    total_.frame_ms.insert(total_.frame_ms.end(), r.frame_ms.begin(), r.frame_ms.end());
    total_.grid_ms.insert(total_.grid_ms.end(), r.grid_ms.begin(), r.grid_ms.end());
    if (!r.stable && total_.stable) {
      total_.stable = false;
      total_.unstable_frame = r.unstable_frame;
      total_.problem = r.problem;
    }
  }

  // hpcplan sph --json's object for the frames run so far.
  py::object report() const {
    const Use use(*this);
    io::SphRun info = session_->describe(threads());
    info.report = total_;
    info.summary = sph::summarise(session_->fluid().full_state());
    double seconds = 0.0;
    for (double ms : total_.frame_ms) seconds += ms / 1000.0;
    info.seconds = seconds;
    return to_python(io::to_json(info));
  }

  void write_vtk(const std::string& dir) {
    const Use use(*this);
    cli::prepare_vtk_dir(dir);  // the CLI's checks and messages (created if its parent exists)
    const std::string key = std::filesystem::weakly_canonical(dir).string();  // one series a folder
    auto it = vtk_.find(key);
    if (it == vtk_.end()) {
      auto series = std::make_unique<io::VtkSeries>(dir);
      if (session_->restarted())  // the frames the interrupted run wrote there
        series->resume(session_->restarted_at_frame(), session_->fluid().state().params.frame_dt);
      it = vtk_.emplace(key, Series{std::move(series), {}}).first;
    }
    // A frame already in the series is the same state: it is not written twice (a failed write,
    // a full disk say, is not counted as written).
    if (it->second.frames.count(session_->frame()) != 0) return;
    {
      // The file's write with the GIL released (Use keeps other threads off the fluid): a
      // large fluid's frame is megabytes.
      const py::gil_scoped_release release;
      it->second.series->write(session_->frame(), session_->fluid().full_state());
    }
    it->second.frames.insert(session_->frame());
  }

  void checkpoint(const std::string& path) {
    const Use use(*this);
    if (path.empty()) throw InputError("--checkpoint: an empty path");
    require_writable_destination(path, "--checkpoint");
    // The soundness check before the write is an OpenMP loop: the fluid's threads (one in a
    // forked child: call_threads).
    const OmpThreads threads(call_threads(threads_));
    bool written = false;
    {
      // Encoding and the flush to disk with the GIL released (95 ms for 35k particles).
      const py::gil_scoped_release release;
      written = session_->write_checkpoint(path);
    }
    if (!written)
      throw RunError("the fluid's state is unsound (" +
                     sph::first_problem(session_->fluid().full_state()) +
                     "): no checkpoint written to '" + path + "'");
  }

  // `read(session)` while no step runs (RuntimeError while one does): every property reads the
  // fluid this way, so no reader sees a step in progress.
  template <class Read>
  auto read(Read read) const {
    const Use use(*this);
    return read(*session_);
  }
  // The same with the state: its positions current (state()) or every array (full_state()).
  template <class Read>
  auto read_state(bool every_array, Read read) const {
    const Use use(*this);
    return read(every_array ? session_->fluid().full_state() : session_->fluid().state());
  }

 private:
  std::unique_ptr<cli::FluidSession> session_;
  int threads_;
  std::string backend_;
  sph::RunReport total_;
  struct Series {
    std::unique_ptr<io::VtkSeries> series;
    std::set<std::uint64_t> frames;  // written by this fluid
  };
  std::map<std::string, Series> vtk_;
  mutable std::atomic<bool> busy_{false};
};

std::unique_ptr<Fluid> make(const std::vector<std::string>& tokens) {
  cli::FluidArgs a;
  CLI::App command("hpcplan sph");
  cli::add_fluid_options(&command, a);
  parse_options(command, tokens);
  const sph::FluidOptions o = cli::fluid_problem(a);
  sph::validate(o);
  sph::check_backend_name(a.backend);
  cli::require_memory(sph::estimated_bytes(o), o.particles, a.memory_mb);
  auto session = call_released<std::unique_ptr<cli::FluidSession>>(
      [&](const cli::RunControl&) {
        const OmpThreads threads(call_threads(a.threads));
        return std::make_unique<cli::FluidSession>(o, a.backend);
      },
      nullptr);
  return std::make_unique<Fluid>(std::move(session), a.threads, a.backend);
}

std::unique_ptr<Fluid> restart(const std::string& path, const std::vector<std::string>& tokens) {
  if (path.empty()) throw InputError("--restart: an empty path");
  cli::FluidArgs a;
  CLI::App command("hpcplan sph");
  cli::add_fluid_options(&command, a);
  parse_options(command, tokens);
  sph::check_backend_name(a.backend);
  auto session = call_released<std::unique_ptr<cli::FluidSession>>(
      [&](const cli::RunControl&) {
        const OmpThreads threads(call_threads(a.threads));
        sph::FluidCheckpoint checkpoint = sph::read_checkpoint(path);
        cli::require_memory(sph::estimated_bytes(checkpoint.options), checkpoint.options.particles,
                            a.memory_mb);
        return std::make_unique<cli::FluidSession>(std::move(checkpoint), a.backend);
      },
      nullptr);
  return std::make_unique<Fluid>(std::move(session), a.threads, a.backend);
}

// A field of the particles as a read-only view of the engine's own array: (n,) for one
// column, (n, 3) for a vector quantity whose three columns follow one another in the block
// (sph/particles.hpp).
template <class T>
py::array column_view(py::object self, const sph::Column<T>& first, std::size_t capacity,
                      int components) {
  const py::ssize_t n = static_cast<py::ssize_t>(first.size());
  const auto item = static_cast<py::ssize_t>(sizeof(T));
  if (components == 1) return read_only_view(first.data(), {n}, {item}, self);
  return read_only_view(first.data(), {n, components},
                        {item, static_cast<py::ssize_t>(capacity) * item}, self);
}

template <class Pick>
auto view_property(bool every_array, int components, Pick pick) {
  return [every_array, components, pick](py::object self) {
    return self.cast<const Fluid&>().read_state(every_array, [&](const sph::FluidState& s) {
      return column_view(self, pick(s.particles), s.particles.capacity(), components);
    });
  };
}

// A property read from the session while no step runs.
template <class Get>
auto session_property(Get get) {
  return
      [get](const Fluid& f) { return f.read([&](const cli::FluidSession& s) { return get(s); }); };
}
template <class Get>
auto state_property(Get get) {
  return [get](const Fluid& f) {
    return f.read_state(false, [&](const sph::FluidState& s) { return get(s); });
  };
}

}  // namespace

void bind_fluid(py::module_& m) {
  m.def("fluid_options", [] {
    return describe_options<cli::FluidArgs>(
        "hpcplan sph", [](CLI::App* c, cli::FluidArgs& a) { cli::add_fluid_options(c, a); });
  });
  py::class_<Fluid>(m, "Fluid")
      .def(py::init(&make), py::arg("tokens"))
      .def_static("restart", &restart, py::arg("path"), py::arg("tokens"))
      .def("step", &Fluid::step, py::arg("frames") = 1, py::arg("stop") = nullptr)
      .def("report", &Fluid::report)
      .def("write_vtk", &Fluid::write_vtk, py::arg("dir"))
      .def("checkpoint", &Fluid::checkpoint, py::arg("path"))
      .def_property_readonly("frame",
                             session_property([](const cli::FluidSession& s) { return s.frame(); }))
      .def_property_readonly("time",
                             state_property([](const sph::FluidState& s) { return s.time; }))
      .def_property_readonly("substeps",
                             state_property([](const sph::FluidState& s) { return s.substeps; }))
      .def_property_readonly(
          "size", state_property([](const sph::FluidState& s) { return s.particles.size(); }))
      .def_property_readonly("fluid_count",
                             state_property([](const sph::FluidState& s) { return s.fluid_count; }))
      .def_property_readonly("backend", session_property([](const cli::FluidSession& s) {
                               return s.fluid().backend().name();
                             }))
      .def_property_readonly("threads", &Fluid::threads)
      .def_property_readonly("options", session_property([](const cli::FluidSession& s) {
                               const sph::FluidOptions& o = s.options();
                               py::dict d;
                               d["preset"] = std::string(sph::to_string(o.preset));
                               d["scenario"] = std::string(sph::to_string(o.scenario));
                               d["particles"] = o.particles;
                               d["seed"] = o.seed;
                               return d;
                             }))
      .def_property_readonly("restarted_at_frame",
                             session_property([](const cli::FluidSession& s) -> py::object {
                               if (!s.restarted()) return py::none();
                               return py::int_(s.restarted_at_frame());
                             }))
      .def_property_readonly("positions",
                             view_property(
                                 false, 3, [](const sph::Particles& p) -> auto& { return p.x; }))
      .def_property_readonly("velocities",
                             view_property(
                                 true, 3, [](const sph::Particles& p) -> auto& { return p.vx; }))
      .def_property_readonly("density",
                             view_property(
                                 true, 1, [](const sph::Particles& p) -> auto& { return p.rho; }))
      .def_property_readonly("pressure",
                             view_property(
                                 true, 1, [](const sph::Particles& p) -> auto& { return p.p; }))
      .def_property_readonly("ids",
                             view_property(
                                 false, 1, [](const sph::Particles& p) -> auto& { return p.id; }))
      .def_property_readonly("wall",
                             view_property(
                                 false, 1, [](const sph::Particles& p) -> auto& { return p.wall; }))
      .def_property_readonly(
          "boxes", state_property([](const sph::FluidState& s) {
            py::array_t<double> a({static_cast<py::ssize_t>(s.boxes.size()), py::ssize_t{9}});
            double* out = a.mutable_data();
            for (const sph::MovingBox& b : s.boxes) {
              out = std::copy(b.box.lo.begin(), b.box.lo.end(), out);
              out = std::copy(b.box.hi.begin(), b.box.hi.end(), out);
              out = std::copy(b.velocity.begin(), b.velocity.end(), out);
            }
            return a;
          }))
      .def_property_readonly(
          "probes", session_property([](const cli::FluidSession& s) {
            const sph::Probes& p = s.probes();
            py::dict d;
            d["columns"] = p.columns;
            const py::ssize_t width = static_cast<py::ssize_t>(p.columns.size());
            py::array_t<double> rows({static_cast<py::ssize_t>(p.rows.size()), width});
            double* out = rows.mutable_data();
            for (const std::vector<double>& row : p.rows)
              out = std::copy(row.begin(), row.end(), out);
            d["rows"] = std::move(rows);
            return d;
          }));
}

}  // namespace hpcplan::python
