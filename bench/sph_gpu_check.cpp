// The CUDA backend against the CPU backend, on a machine with a GPU (built only with CUDA; it
// needs nothing but the fluid's own libraries, so it can be carried to a GPU machine without
// hpcplan's other dependencies). One JSON object per line on stdout:
//   agree       the same fluid stepped by both backends, frame by frame: the largest distance
//               between a particle's two positions (matched by id) after 1, 10, 100, 1000
//               frames, both frame checks (NaN, escape, boxes) and the fluid count (mass) on
//               each, and the final kinetic energy and density error of each;
//   dambreak    Martin and Moyce's surge front from the CUDA backend, against the experiment;
//   throughput  particle-steps per second of one substep, CUDA and CPU (all cores), per preset
//               and particle count, and their ratio.
// Usage: hpcplan_sph_gpu_check [--quick] [--verify] [--frames F] [--sizes N,N,...] [--only PART]
//                              [--budget-s S]
//   --quick: small fluids only (also for compute-sanitizer); --verify: exit 1 unless every
//   agreement run ends with positions within 1e-6 of each other and both frame checks clean;
//   --only agree|dambreak|throughput: that part alone; --budget-s: skip what would start after
//   this many seconds.
// Exit 77 (a skipped test to CTest) where no CUDA device can run.
//
// Why 1e-6 over a few frames only: both backends are the same double-precision arithmetic in
// a different summation order (cell order on the GPU, list order on the CPU), so they start
// 1e-16 apart; the dam break's free surface amplifies that about tenfold per frame (1e-9 after
// 10 frames, centimetres after 20 on the H200), a fluid at rest far less (1e-10 after 100
// frames, 0.09 m after 1,000 in a 1 m tank). Long runs are compared by their statistics.
#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <string>
#include <unordered_map>
#include <vector>

#include "hpcplan/sph/diagnostics.hpp"
#include "hpcplan/sph/fluid.hpp"
#include "hpcplan/sph/presets.hpp"
#include "hpcplan/sph/run.hpp"

namespace {

using namespace hpcplan::sph;
using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

// The largest distance between the two fluids' positions of each particle (matched by id).
double max_distance(const FluidState& a, const FluidState& b) {
  std::vector<std::size_t> where(a.particles.size());
  for (std::size_t i = 0; i < b.particles.size(); ++i) where[b.particles.id[i]] = i;
  double worst = 0.0;
  for (std::size_t i = 0; i < a.particles.size(); ++i) {
    const std::size_t j = where[a.particles.id[i]];
    const double dx = a.particles.x[i] - b.particles.x[j], dy = a.particles.y[i] - b.particles.y[j],
                 dz = a.particles.z[i] - b.particles.z[j];
    worst = std::max(worst, std::sqrt(dx * dx + dy * dy + dz * dz));
  }
  return worst;
}

std::size_t fluid_particles(const FluidState& s) {
  std::size_t n = 0;
  for (std::uint8_t w : s.particles.wall) n += w == 0;
  return n;
}

bool g_verify_failed = false;

void agree(Preset preset, Scenario scenario, std::size_t particles, std::uint64_t frames,
           bool verify = false) {
  FluidOptions o;
  o.preset = preset;
  o.scenario = scenario;
  o.particles = particles;
  o.seed = 5;
  Fluid cpu(make_fluid(o), "cpu"), gpu(make_fluid(o), "cuda");
  std::string cpu_problem, gpu_problem;
  std::string checkpoints;
  std::uint64_t done = 0;
  double last_difference = 0.0;
  // The dam break's front after every substep, from each backend: what a per-substep observer
  // (the front CSV) sees must agree too.
  std::vector<double> zc, zg;
  std::function<void(const FluidState&)> front_cpu, front_gpu;
  if (scenario == Scenario::dambreak) {
    front_cpu = [&](const FluidState& s) { zc.push_back(dam_break_front(s).z); };
    front_gpu = [&](const FluidState& s) { zg.push_back(dam_break_front(s).z); };
  }
  const auto t0 = Clock::now();
  double gpu_s = 0.0, cpu_s = 0.0;
  for (std::uint64_t f = 1; f <= frames; ++f) {
    const auto a = Clock::now();
    const FrameReport rc = cpu.advance_frame(front_cpu);
    const auto b = Clock::now();
    const FrameReport rg = gpu.advance_frame(front_gpu);
    gpu_s += seconds_since(b);
    cpu_s += std::chrono::duration<double>(b - a).count();
    done = f;
    if (!rc.problem.empty()) cpu_problem = rc.problem;
    if (!rg.problem.empty()) gpu_problem = rg.problem;
    if (f == 1 || f == 10 || f == 100 || f == 1000 || f == frames) {
      last_difference = max_distance(cpu.state(), gpu.state());
      char buf[96];
      std::snprintf(buf, sizeof buf, "%s\"%llu\": %.3e", checkpoints.empty() ? "" : ", ",
                    static_cast<unsigned long long>(f), last_difference);
      checkpoints += buf;
    }
    if (!cpu_problem.empty() || !gpu_problem.empty()) break;
  }
  const FluidSummary sc = summarise(cpu.full_state()), sg = summarise(gpu.full_state());
  double front_difference = zc.size() == zg.size() ? 0.0 : 1e9;
  for (std::size_t k = 0; k < std::min(zc.size(), zg.size()); ++k)
    front_difference = std::max(front_difference, std::abs(zc[k] - zg[k]));
  if (verify && (!(last_difference <= 1e-6) || !(front_difference <= 1e-6) ||
                 !cpu_problem.empty() || !gpu_problem.empty() ||
                 fluid_particles(cpu.state()) != fluid_particles(gpu.state()) || done != frames)) {
    std::fprintf(stderr,
                 "hpcplan_sph_gpu_check: %s %s disagree: positions %.3e, fronts %.3e after %llu "
                 "frames\n",
                 std::string(to_string(preset)).c_str(), std::string(to_string(scenario)).c_str(),
                 last_difference, front_difference, static_cast<unsigned long long>(done));
    g_verify_failed = true;
  }
  std::printf(
      "{\"check\": \"agree\", \"preset\": \"%s\", \"scenario\": \"%s\", \"particles\": %zu, "
      "\"frames\": %llu, \"max_position_difference\": {%s}, \"cpu_problem\": \"%s\", "
      "\"gpu_problem\": \"%s\", \"fluid_cpu\": %zu, \"fluid_gpu\": %zu, \"kinetic_energy_cpu\": "
      "%.6g, \"kinetic_energy_gpu\": %.6g, \"density_error_cpu\": %.4g, \"density_error_gpu\": "
      "%.4g, \"substeps_cpu\": %llu, \"substeps_gpu\": %llu, \"cpu_s\": %.2f, \"gpu_s\": %.2f, "
      "\"max_front_difference\": %.3e, \"seconds\": %.1f}\n",
      std::string(to_string(preset)).c_str(), std::string(to_string(scenario)).c_str(),
      cpu.state().fluid_count, static_cast<unsigned long long>(done), checkpoints.c_str(),
      cpu_problem.c_str(), gpu_problem.c_str(), fluid_particles(cpu.state()),
      fluid_particles(gpu.state()), sc.kinetic_energy, sg.kinetic_energy, sc.max_density_error,
      sg.max_density_error, static_cast<unsigned long long>(cpu.state().substeps),
      static_cast<unsigned long long>(gpu.state().substeps), cpu_s, gpu_s, front_difference,
      seconds_since(t0));
  std::fflush(stdout);
}

void dambreak(std::size_t particles, const char* backend) {
  FluidOptions o;
  o.preset = Preset::water;
  o.scenario = Scenario::dambreak;
  o.particles = particles;
  Fluid fluid(make_fluid(o), backend);
  std::vector<std::pair<double, double>> tz;
  const RunReport r = run_frames(fluid, 9, {}, [&](const FluidState& s) {
    const SurgeFront f = dam_break_front(s);
    tz.emplace_back(f.t, f.z);
  });
  // Martin and Moyce (1952), the points with 0.8 <= T <= 3.
  const std::pair<double, double> data[] = {
      {0.832, 1.217}, {1.219, 1.474}, {1.997, 2.292}, {2.547, 2.995}};
  std::string points;
  double worst = 0.0;
  for (const auto& [t, z] : data) {
    auto it = std::lower_bound(tz.begin(), tz.end(), std::make_pair(t, 0.0));
    if (it == tz.end()) continue;
    const double err = (it->second - z) / z;
    worst = std::max(worst, std::abs(err));
    char buf[96];
    std::snprintf(buf, sizeof buf, "%s{\"T\": %.3f, \"Z\": %.4f, \"Z_exp\": %.3f}",
                  points.empty() ? "" : ", ", t, it->second, z);
    points += buf;
  }
  std::printf(
      "{\"check\": \"dambreak\", \"backend\": \"%s\", \"particles\": %zu, \"stable\": %s, "
      "\"problem\": \"%s\", \"points\": [%s], \"max_relative_error\": %.4f}\n",
      backend, fluid.state().fluid_count, r.stable ? "true" : "false", r.problem.c_str(),
      points.c_str(), worst);
  std::fflush(stdout);
}

// Particle-steps per second of one substep, after `warm` substeps, over at least `min_s`
// seconds (and at least `min_steps` substeps).
double throughput(FluidState& s, StepBackend& b, int warm, int min_steps, double min_s) {
  for (int k = 0; k < warm; ++k) b.substep(s, b.stable_dt(s));
  b.end_frame(s);  // waits for the GPU
  int steps = 0;
  const auto t0 = Clock::now();
  while (steps < min_steps || seconds_since(t0) < min_s) {
    b.substep(s, b.stable_dt(s));
    ++steps;
  }
  b.end_frame(s);
  return static_cast<double>(s.fluid_count) * steps / seconds_since(t0);
}

void speed(Preset preset, std::size_t particles, bool with_cpu) {
  FluidOptions o;
  o.preset = preset;
  o.scenario = preset == Preset::seed ? Scenario::dynamic_boxes : Scenario::tank;
  o.particles = particles;
  const auto t0 = Clock::now();
  FluidState g = make_fluid(o);
  const std::size_t total = g.particles.size(), fluid = g.fluid_count;
  auto gpu_backend = make_backend("cuda", g);
  const double gpu = throughput(g, *gpu_backend, 5, 10, 1.0);
  gpu_backend.reset();
  double cpu = 0.0;
  if (with_cpu) {
    FluidState c = make_fluid(o);
    auto cpu_backend = make_backend("cpu", c);
    cpu = throughput(c, *cpu_backend, 2, 3, 1.0);
  }
  std::printf(
      "{\"check\": \"throughput\", \"preset\": \"%s\", \"scenario\": \"%s\", \"particles\": %zu, "
      "\"with_walls\": %zu, \"gpu_particle_steps_per_s\": %.4e, \"cpu_particle_steps_per_s\": "
      "%.4e, \"cpu_threads\": %d, \"gpu_over_cpu\": %.1f, \"seconds\": %.1f}\n",
      std::string(to_string(preset)).c_str(), std::string(to_string(o.scenario)).c_str(), fluid,
      total, gpu, cpu, omp_get_max_threads(), cpu > 0 ? gpu / cpu : 0.0, seconds_since(t0));
  std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) {
  bool quick = false, verify = false;
  std::string only;  // agree, dambreak or throughput; empty: all
  std::uint64_t frames = 1000;
  double budget = 1e9;
  std::vector<std::size_t> sizes = {25000, 100000, 1000000, 4000000};
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--quick") {
      quick = true;
    } else if (a == "--verify") {
      verify = true;
    } else if (a == "--frames" && i + 1 < argc) {
      frames = std::strtoull(argv[++i], nullptr, 10);
    } else if (a == "--only" && i + 1 < argc) {
      only = argv[++i];
    } else if (a == "--budget-s" && i + 1 < argc) {
      budget = std::strtod(argv[++i], nullptr);
    } else if (a == "--sizes" && i + 1 < argc) {
      sizes.clear();
      for (char* p = argv[++i]; *p;) {
        sizes.push_back(std::strtoull(p, &p, 10));
        if (*p == ',') ++p;
      }
    } else {
      std::fprintf(stderr, "hpcplan_sph_gpu_check: unknown argument %s\n", argv[i]);
      return 2;
    }
  }
  if (const std::string why = cuda_unavailable_reason(); !why.empty()) {
    std::fprintf(stderr, "hpcplan_sph_gpu_check: %s\n", why.c_str());
    return 77;
  }
  const auto start = Clock::now();
  auto time_left = [&] { return seconds_since(start) < budget; };
  std::printf("{\"check\": \"device\", \"name\": \"%s\", \"cpu_threads\": %d}\n",
              cuda_device_name().c_str(), omp_get_max_threads());
  if (quick) {
    agree(Preset::water, Scenario::dambreak, 500, frames, verify);
    agree(Preset::seed, Scenario::dynamic_boxes, 1000, frames, verify);
    agree(Preset::water, Scenario::column, 250, frames, verify);
    return g_verify_failed ? 1 : 0;
  }
  auto wanted = [&](const char* part) { return (only.empty() || only == part) && time_left(); };
  if (wanted("agree")) agree(Preset::water, Scenario::tank, 4000, frames);
  if (wanted("agree")) agree(Preset::seed, Scenario::dynamic_boxes, 1500, frames);
  if (wanted("agree"))
    agree(Preset::water, Scenario::dambreak, 864, std::min<std::uint64_t>(frames, 9));
  if (wanted("agree"))
    agree(Preset::water, Scenario::column, 2000, std::min<std::uint64_t>(frames, 100));
  if (wanted("dambreak")) dambreak(864, "cpu");  // the reference, in the same process
  for (std::size_t n : {864ul, 4000ul, 13500ul})
    if (wanted("dambreak")) dambreak(n, "cuda");
  for (Preset preset : {Preset::water, Preset::seed})
    for (std::size_t n : sizes)
      if (wanted("throughput")) speed(preset, n, true);
  return g_verify_failed ? 1 : 0;
}
