// The replanning step of the simulator under Google Benchmark, at the seed's largest fluid
// (25,000 particles, dynamic boxes, 2 threads for the fluid). The fluid settles for 200 frames,
// the robot and goal are placed as in a run, and then every iteration advances the fluid by 10
// frames (not timed), moves the robot 0.4 along its last plan (the controller's 2 wu/s for
// 0.2 s), and times one replan: snapshot + world + search + smoothing, failed replans included.
//   Replan/<algo>            per-replan time; counters p50_ms, p95_ms, p99_ms, failed (fraction),
//                            and the mean of each part: snapshot, world, search, smoothing
//   Frame/<with snapshot>    one SPH frame, and one frame plus a snapshot
//   World/<occupancy|particles>  building a world from a snapshot
//   DStarVsAStar             the same replans (the robot follows A*'s plans) planned by A* afresh
//                            and by D* Lite incrementally; counters: how often D* Lite repairs
//                            rather than restarts, and the p50 of each on repairs and restarts
//   OccupancyChange          between replans 10 frames apart: the fraction of occupancy cells
//                            that change, and of particles whose covered cells change (an
//                            incremental update of the grid would have to redo at least those)
#include <benchmark/benchmark.h>
#include <omp.h>

#include <cmath>
#include <cstdio>
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
  const sim::Placement at = sim::place_robot_and_goal(sph::Scenario::particles, fluid.state(), 1);
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
  const sim::Placement at = sim::place_robot_and_goal(sph::Scenario::particles, fluid.state(), 1);
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

void DStarVsAStar(benchmark::State& state) {
  sph::Fluid fluid = settled_fluid();
  const sim::Placement at = sim::place_robot_and_goal(sph::Scenario::particles, fluid.state(), 1);
  const std::uint32_t exclude[2] = {at.robot_id, at.goal_id};
  plan::FluidPlanOptions ao, dopt;
  ao.algo = "astar";
  dopt.algo = "dstar_lite";
  plan::FluidReplanner astar(ao), dstar(dopt);
  env::Vec<3> robot = at.robot;
  std::vector<double> a_repair, d_repair, a_restart, d_restart;
  std::uint64_t index = 0, wins = 0, changed = 0;
  for (auto _ : state) {
    for (int f = 0; f < 10; ++f) fluid.advance_frame();
    const env::Vec<3> goal = sim::particle_position(fluid.state(), at.goal_id);
    const env::FluidSnapshot snap = sim::take_snapshot(fluid.state(), exclude);
    const plan::FluidPlan pa = astar.plan(snap, robot, goal, index);
    const plan::FluidPlan pd = dstar.plan(snap, robot, goal, index++);
    state.SetIterationTime((pa.counters.time_ms * 1e3 + pd.counters.time_ms * 1e3) * 1e-6);
    if (pd.status != pa.status)
      state.SkipWithError("A* and D* Lite disagree on whether a path exists");
    if (pa.status == Status::solved &&
        std::abs(pa.search_cost - pd.search_cost) > 1e-9 * (1.0 + pa.search_cost)) {
      std::fprintf(stderr, "mismatch %s astar %.9f dstar %.9f raw %.6f %.6f\n",
                   std::string(plan::to_string(pd.incremental)).c_str(), pa.search_cost,
                   pd.search_cost, pa.raw_length, pd.raw_length);
      state.SkipWithError("D* Lite's optimum differs from A*'s");
    }
    if (pd.incremental == plan::Incremental::repair) {
      a_repair.push_back(pa.counters.time_ms * 1e3 * 1e-3),
          d_repair.push_back(pd.counters.time_ms * 1e3 * 1e-3);
      wins += pd.counters.time_ms * 1e3 < pa.counters.time_ms * 1e3;
      changed += pd.changed_cells;
    } else if (pd.incremental == plan::Incremental::restart) {
      a_restart.push_back(pa.counters.time_ms * 1e3 * 1e-3),
          d_restart.push_back(pd.counters.time_ms * 1e3 * 1e-3);
    }
    if (pa.status == Status::solved) robot = along(pa.path, 0.4);
    if (env::distance<3>(robot, goal) < 0.2) robot = at.robot;
  }
  const double repairs = static_cast<double>(a_repair.size());
  state.counters["repair_fraction"] = repairs / static_cast<double>(index);
  state.counters["repair_astar_p50_ms"] = sim::quantile(a_repair, 0.5);
  state.counters["repair_dstar_p50_ms"] = sim::quantile(d_repair, 0.5);
  state.counters["repair_dstar_wins"] = repairs ? static_cast<double>(wins) / repairs : 0.0;
  state.counters["repair_changed_cells"] = repairs ? static_cast<double>(changed) / repairs : 0.0;
  state.counters["restart_astar_p50_ms"] = sim::quantile(a_restart, 0.5);
  state.counters["restart_dstar_p50_ms"] = sim::quantile(d_restart, 0.5);
}

void OccupancyChange(benchmark::State& state) {
  sph::Fluid fluid = settled_fluid();
  std::vector<std::uint32_t> none;
  env::FluidSnapshot before = sim::take_snapshot(fluid.state(), none);
  env::OccupancyWorld old_world(before);
  double cells = 0, particles = 0, occupied = 0;
  std::uint64_t n = 0;
  for (auto _ : state) {
    for (int f = 0; f < 10; ++f) fluid.advance_frame();
    // Compare particles by id: the snapshot lists them in storage order, which reordering moves.
    const sph::Particles& p = fluid.state().particles;
    env::FluidSnapshot now;
    now.domain = before.domain;
    now.particles.resize(p.size());
    for (std::size_t i = 0; i < p.size(); ++i) now.particles[p.id[i]] = {p.x[i], p.y[i], p.z[i]};
    for (const auto& b : fluid.state().boxes)
      now.boxes.push_back(
          {{b.box.lo[0], b.box.lo[1], b.box.lo[2]}, {b.box.hi[0], b.box.hi[1], b.box.hi[2]}});
    const env::OccupancyWorld world(now);
    std::uint64_t changed = 0;
    for (std::uint32_t c = 0; c < world.cell_count(); ++c)
      changed += world.occupied(c) != old_world.occupied(c);
    // A particle's covered cells are those whose centre lies within 0.14: they change when the
    // particle crosses one of the spheres around the cell centres; count a change of the nearest
    // centre's cell or of the rounded offset to it (a lower bound on what an update must redo).
    std::uint64_t moved = 0;
    if (before.particles.size() == now.particles.size())
      for (std::size_t i = 0; i < now.particles.size(); ++i)
        moved += world.cell_of(now.particles[i]) != old_world.cell_of(before.particles[i]);
    cells += static_cast<double>(changed) / static_cast<double>(world.cell_count());
    occupied += static_cast<double>(changed) /
                std::max<double>(1.0, static_cast<double>(world.occupied_count()));
    particles += static_cast<double>(moved) / static_cast<double>(now.particles.size());
    ++n;
    old_world = world;
    before = std::move(now);
  }
  state.counters["changed_cells_of_all"] = cells / static_cast<double>(n);
  state.counters["changed_cells_of_occupied"] = occupied / static_cast<double>(n);
  state.counters["particles_changing_cell"] = particles / static_cast<double>(n);
}

BENCHMARK(DStarVsAStar)->Iterations(200)->UseManualTime()->Unit(benchmark::kMillisecond);
BENCHMARK(OccupancyChange)->Iterations(50)->Unit(benchmark::kMillisecond);
BENCHMARK(Replan)->DenseRange(0, 3)->Iterations(200)->UseManualTime()->Unit(
    benchmark::kMillisecond);
BENCHMARK(Frame)->DenseRange(0, 1)->Iterations(200)->Unit(benchmark::kMillisecond);
BENCHMARK(World)->DenseRange(0, 1)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
