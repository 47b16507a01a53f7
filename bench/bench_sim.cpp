// The replanning step of the simulator under Google Benchmark, at the seed's largest fluid
// (25,000 particles, dynamic boxes, 2 threads for the fluid). The fluid settles for 200 frames,
// the robot and goal are placed as in a run, and then every iteration advances the fluid by 10
// frames (not timed), moves the robot 0.4 along its last plan (the controller's 2 wu/s for
// 0.2 s), and times one replan: snapshot + world + search + smoothing, failed replans included.
//   Replan/<algo>            per-replan time; counters p50_ms, p95_ms, p99_ms, failed (fraction),
//                            and the mean of each part: snapshot, world, search, smoothing
//   Frame/<with snapshot>    one SPH frame, and one frame plus a snapshot
//   World/<occupancy|particles>  building a world from a snapshot
#include <benchmark/benchmark.h>
#include <omp.h>

#include <string>

#include "hpcplan/core/stopwatch.hpp"
#include "hpcplan/env/occupancy_world.hpp"
#include "hpcplan/env/particle_world.hpp"
#include "hpcplan/plan/fluid_planner.hpp"
#include "hpcplan/sim/metrics.hpp"
#include "hpcplan/sim/simulator.hpp"
#include "hpcplan/sim/snapshot.hpp"
#include "hpcplan/sph/fluid.hpp"

namespace {

using namespace hpcplan;

constexpr std::size_t kParticles = 25000;
const char* const kAlgos[] = {"astar", "astar_euclid", "dstar_lite", "rrtstar"};

sph::Fluid settled_fluid() {
  omp_set_num_threads(2);
  sph::FluidOptions o;
  o.scenario = sph::Scenario::dynamic_boxes;
  o.particles = kParticles;
  sph::Fluid fluid(sph::make_fluid(o), sph::make_cpu_backend());
  for (int f = 0; f < 200; ++f) fluid.advance_frame();
  return fluid;
}

// The point `distance` further along `path` from its start.
env::Vec<3> along(const std::vector<env::Vec<3>>& path, double distance) {
  for (std::size_t i = 1; i < path.size(); ++i) {
    const double l = env::distance<3>(path[i - 1], path[i]);
    if (distance <= l) return env::lerp<3>(path[i - 1], path[i], distance / l);
    distance -= l;
  }
  return path.back();
}

void Replan(benchmark::State& state) {
  sph::Fluid fluid = settled_fluid();
  const sim::Placement at = sim::place_robot_and_goal(fluid.state(), 1);
  const std::uint32_t exclude[2] = {at.robot_id, at.goal_id};
  plan::FluidPlanOptions po;
  po.algo = kAlgos[state.range(0)];
  plan::FluidReplanner planner(po);
  env::Vec<3> robot = at.robot;
  std::vector<double> ms;
  std::uint64_t failed = 0, index = 0;
  double world_ms = 0, search_ms = 0, smooth_ms = 0, snapshot_ms = 0;
  for (auto _ : state) {
    for (int f = 0; f < 10; ++f) fluid.advance_frame();
    const env::Vec<3> goal = sim::particle_position(fluid.state(), at.goal_id);
    const Stopwatch clock;
    const env::FluidSnapshot snap = sim::take_snapshot(fluid.state(), exclude);
    snapshot_ms += clock.milliseconds();
    const plan::FluidPlan p = planner.plan(snap, robot, goal, index++);
    const double t = clock.milliseconds();
    state.SetIterationTime(t * 1e-3);
    ms.push_back(t);
    world_ms += p.world_us * 1e-3, search_ms += p.search_us * 1e-3, smooth_ms += p.smooth_us * 1e-3;
    if (p.status != Status::solved) {
      ++failed;
    } else {
      robot = along(p.path, 0.4);
    }
    if (env::distance<3>(robot, goal) < 0.2) robot = at.robot;  // arrived: start over
  }
  state.counters["p50_ms"] = sim::quantile(ms, 0.5);
  state.counters["p95_ms"] = sim::quantile(ms, 0.95);
  state.counters["p99_ms"] = sim::quantile(ms, 0.99);
  state.counters["failed"] = static_cast<double>(failed) / static_cast<double>(ms.size());
  const double n = static_cast<double>(ms.size());
  state.counters["snapshot_ms"] = snapshot_ms / n;
  state.counters["world_ms"] = world_ms / n;
  state.counters["search_ms"] = search_ms / n;
  state.counters["smooth_ms"] = smooth_ms / n;
  state.SetLabel(po.algo);
}

void Frame(benchmark::State& state) {
  sph::Fluid fluid = settled_fluid();
  const sim::Placement at = sim::place_robot_and_goal(fluid.state(), 1);
  const std::uint32_t exclude[2] = {at.robot_id, at.goal_id};
  for (auto _ : state) {
    fluid.advance_frame();
    if (state.range(0)) benchmark::DoNotOptimize(sim::take_snapshot(fluid.state(), exclude));
  }
  state.SetLabel(state.range(0) ? "frame + snapshot" : "frame");
}

void World(benchmark::State& state) {
  sph::Fluid fluid = settled_fluid();
  const env::FluidSnapshot snap = sim::take_snapshot(fluid.state(), {});
  for (auto _ : state) {
    if (state.range(0) == 0)
      benchmark::DoNotOptimize(env::OccupancyWorld(snap));
    else
      benchmark::DoNotOptimize(env::ParticleWorld(snap));
  }
  state.SetLabel(state.range(0) == 0 ? "occupancy" : "particles");
}

BENCHMARK(Replan)->DenseRange(0, 3)->Iterations(200)->UseManualTime()->Unit(
    benchmark::kMillisecond);
BENCHMARK(Frame)->DenseRange(0, 1)->Iterations(200)->Unit(benchmark::kMillisecond);
BENCHMARK(World)->DenseRange(0, 1)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
