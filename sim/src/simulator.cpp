#include "hpcplan/sim/simulator.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <deque>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "hpcplan/core/error.hpp"
#include "hpcplan/core/splitmix64.hpp"
#include "hpcplan/core/stopwatch.hpp"
#include "hpcplan/sim/planner_thread.hpp"
#include "hpcplan/sim/snapshot.hpp"
#include "hpcplan/sph/fluid.hpp"

namespace hpcplan::sim {

Pace parse_pace(std::string_view name) {
  if (name == "realtime") return Pace::realtime;
  if (name == "lockstep") return Pace::lockstep;
  throw InputError("unknown --pace " + std::string(name) + " (realtime or lockstep)");
}

std::string_view to_string(Pace p) {
  return p == Pace::realtime ? "realtime" : "lockstep";
}

void validate(const SimOptions& o) {
  using sph::Scenario;
  if (o.scenario != Scenario::particles && o.scenario != Scenario::static_boxes &&
      o.scenario != Scenario::dynamic_boxes && o.scenario != Scenario::dambreak)
    throw InputError("the simulator runs --scenario particles, static, dynamic or dambreak (not " +
                     std::string(sph::to_string(o.scenario)) + ")");
  if (o.particles < 2) throw InputError("--particles must be at least 2 (a robot and a goal)");
  if (o.runs < 1) throw InputError("--runs must be at least 1");
  if (o.replan_every < 1) throw InputError("--replan-every must be at least 1 frame");
  if (o.lockstep_delay < 0) throw InputError("--lockstep-delay must not be negative");
  if (o.settle_frames < -1) throw InputError("--settle-frames must not be negative");
  if (!(o.max_sim_s > 0) || !std::isfinite(o.max_sim_s))
    throw InputError("--max-sim-s must be a positive number of seconds");
  if (!(o.max_wall_s >= 0) || !std::isfinite(o.max_wall_s))
    throw InputError("--max-wall-s must be a number of seconds >= 0 (0: no cap)");
  if (!(o.goal_radius > 0)) throw InputError("the goal radius must be positive");
  if (!(o.safety.robot_radius >= 0) || !std::isfinite(o.safety.robot_radius) ||
      !(o.safety.particle_radius >= 0) || !std::isfinite(o.safety.particle_radius))
    throw InputError("--robot-radius and the particle radius must be numbers >= 0");
  const ReactiveController check_reactive(o.reactive, o.safety,
                                          o.robot.max_speed);  // throws if bad
  if (!o.make_fluid) sph::validate(fluid_options(o, o.seed));
  sph::check_backend_name(o.backend);
  plan::FluidReplanner check(o.planner);  // throws for an unknown planner or bad options
}

sph::FluidOptions fluid_options(const SimOptions& o, std::uint64_t seed) {
  sph::FluidOptions fo;
  fo.particles = o.particles;
  fo.seed = seed;
  fo.scenario = o.scenario;
  if (o.scenario == sph::Scenario::dambreak) {
    fo.preset = sph::Preset::water;
    fo.scenario = sph::Scenario::column;
  }
  return fo;
}

int settle_frames(const SimOptions& o) {
  if (o.settle_frames >= 0) return o.settle_frames;
  return o.scenario == sph::Scenario::dambreak ? 0 : 200;
}

namespace {

// dambreak: a point in each end bay of the tank, the robot's end drawn at random.
Placement place_in_end_bays(const sph::FluidState& s, std::uint64_t seed) {
  SplitMix64 rng(splitmix64_mix(seed ^ 0xDA3B5EEDull));
  auto uniform = [&](double lo, double hi) {
    return lo + (hi - lo) * static_cast<double>(rng.next() >> 11) * 0x1.0p-53;
  };
  const sph::Box3& d = s.domain;
  auto point_in_bay = [&](bool low_end) {
    const double from_end = uniform(0.2, 1.0);
    return env::Vec<3>{low_end ? d.lo[0] + from_end : d.hi[0] - from_end,
                       uniform(d.lo[1] + 0.2, d.hi[1] - 0.2), d.lo[2] + uniform(0.3, 1.0)};
  };
  const bool robot_low = (rng.next() & 1) == 0;
  Placement at;
  at.robot = point_in_bay(robot_low);
  at.goal = point_in_bay(!robot_low);
  return at;
}

}  // namespace

Placement place_robot_and_goal(sph::Scenario scenario, const sph::FluidState& s,
                               std::uint64_t seed) {
  if (scenario == sph::Scenario::dambreak) return place_in_end_bays(s, seed);
  const sph::Particles& p = s.particles;
  std::vector<std::size_t> fluid;
  for (std::size_t i = 0; i < p.size(); ++i)
    if (!p.wall[i]) fluid.push_back(i);
  // Draw by id order, not storage order, so the choice does not depend on the reordering.
  std::sort(fluid.begin(), fluid.end(),
            [&](std::size_t a, std::size_t b) { return p.id[a] < p.id[b]; });
  const double side = s.domain.hi[0] - s.domain.lo[0];
  SplitMix64 rng(splitmix64_mix(seed ^ 0x5EEDF00Dull));
  Placement best;
  double best_d = -1.0;
  for (int t = 0; t < 10000; ++t) {
    const std::size_t a = fluid[rng.next() % fluid.size()], b = fluid[rng.next() % fluid.size()];
    if (a == b) continue;
    const double d = env::distance<3>({p.x[a], p.y[a], p.z[a]}, {p.x[b], p.y[b], p.z[b]});
    if (d > best_d) {
      best_d = d;
      best = {p.id[a], p.id[b], {p.x[a], p.y[a], p.z[a]}, {p.x[b], p.y[b], p.z[b]}};
    }
    if (d >= 0.5 * side) break;
  }
  return best;
}

sph::FluidState without_particle(sph::FluidState state, std::uint32_t id) {
  sph::Particles& p = state.particles;
  const std::size_t n = p.size();
  std::size_t at = n;
  for (std::size_t i = 0; i < n; ++i)
    if (p.id[i] == id) {
      at = i;
      break;
    }
  if (at == n) throw RunError("internal error: no particle has id " + std::to_string(id));
  const bool wall = p.wall[at] != 0;
  // Every other particle keeps its order (the order of the fluid's sums): the removed one is
  // moved to the end and cut off.
  std::vector<std::uint32_t> order;
  order.reserve(n);
  for (std::size_t i = 0; i < n; ++i)
    if (i != at) order.push_back(static_cast<std::uint32_t>(i));
  order.push_back(static_cast<std::uint32_t>(at));
  p.permute(order);
  p.resize(n - 1);
  if (!wall) --state.fluid_count;
  state.grid.build(p);  // (a backend rebuilds it at the next frame's first substep anyway)
  return state;
}

namespace {

ReplanRecord record_of(int run, const FinishedPlan& f, const std::string& algo, double frame_dt) {
  ReplanRecord r;
  r.run = run;
  r.frame = f.job.frame;
  r.sim_time_s = static_cast<double>(f.job.frame) * frame_dt;
  r.algorithm = algo;
  r.status = f.plan.status;
  r.blocked = f.plan.blocked;
  r.plan_us = f.plan.counters.time_ms * 1e3;
  r.world_us = f.plan.world_us;
  r.search_us = f.plan.search_us;
  r.smooth_us = f.plan.smooth_us;
  r.expanded = f.plan.counters.expanded + f.plan.counters.samples;
  r.length = r.solved() ? f.plan.cost : 0.0;
  r.waypoints = r.solved() ? f.plan.path.size() : 0;
  r.start_escaped = f.plan.start_escaped;
  r.goal_escaped = f.plan.goal_escaped;
  r.incremental = f.plan.incremental;
  return r;
}

// Returns false when should_stop ended the run before it ended by itself (nothing recorded).
bool run_one(const SimOptions& o, int run, RunRecord& rec, std::vector<ReplanRecord>& replans,
             const std::function<void(const FrameView&)>& on_frame,
             const std::function<bool()>& should_stop) {
  const std::uint64_t run_seed =
      splitmix64_mix(o.seed ^ splitmix64_mix(static_cast<std::uint64_t>(run)));
  rec.run_number = run;
  rec.seed = o.seed;
  rec.algorithm = o.planner.algo;
  rec.scenario = std::string(sph::to_string(o.scenario));
  rec.pace = std::string(to_string(o.pace));
  rec.controller = std::string(to_string(o.controller));
  rec.occupancy = env::occupancy_label(o.planner.occupancy);

  sph::Fluid fluid(
      o.make_fluid ? o.make_fluid(run_seed) : sph::make_fluid(fluid_options(o, run_seed)),
      o.backend);
  rec.particle_count = fluid.state().fluid_count;
  const double dt = fluid.state().params.frame_dt;
  for (int f = 0, settle = settle_frames(o); f < settle; ++f) {
    if (const auto r = fluid.advance_frame(); !r.problem.empty()) {
      rec.end = RunEnd::fluid_unstable;
      return true;
    }
    // The settling frames are frames too: a stop asked for during them ends the run here (a
    // large fluid settles for seconds of wall time before the robot is placed).
    if (should_stop && should_stop()) return false;
  }

  Placement at;
  if (o.place) {
    const auto [robot_id, goal_id] = o.place(fluid.state());
    at = {robot_id, goal_id, particle_position(fluid.state(), robot_id),
          particle_position(fluid.state(), goal_id)};
  } else {
    at = place_robot_and_goal(o.scenario, fluid.state(), run_seed);
  }
  rec.start_goal_distance = env::distance<3>(at.robot, at.goal);
  // The robot takes its particle's place: the particle leaves the fluid here, at a frame's end
  // (the fluid goes on as a restart from a checkpoint would, one particle fewer), so that every
  // particle left is an obstacle to the planners, the reactive layer and the contact metric.
  // Only the goal's particle is not: it is what the robot is to reach.
  if (at.robot_id != kNoParticle) {
    if (at.robot_id == at.goal_id)
      throw RunError("internal error: the robot and the goal were given the same particle");
    fluid = sph::Fluid(without_particle(fluid.full_state(), at.robot_id), o.backend,
                       fluid.frames_done());
  }
  const std::uint32_t exclude[1] = {at.goal_id};
  const sph::Box3& d = fluid.state().domain;
  const env::Aabb<3> box{{d.lo[0], d.lo[1], d.lo[2]}, {d.hi[0], d.hi[1], d.hi[2]}};
  Robot robot(at.robot, box, o.robot);
  std::optional<ReactiveController> reactive;
  if (o.controller == Controller::reactive)
    reactive.emplace(o.reactive, o.safety, o.robot.max_speed);
  SafetyRecord safety;

  plan::FluidPlanOptions po = o.planner;
  po.seed = run_seed;
  plan::FluidReplanner replanner(po);
  PlannerThread thread(replanner);
  std::deque<std::pair<std::uint64_t, FinishedPlan>> lockstep_queue;  // (apply at frame, plan)
  std::vector<env::Vec<3>> previous, trail{robot.position()};
  std::vector<double> sph_ms, snapshot_ms;
  std::uint64_t replan_index = 0;

  env::FluidSnapshot snapshot;
  auto apply = [&](FinishedPlan f) {
    if (!f.error.empty()) throw RunError(f.error);
    if (!f.job.snapshot.particles.empty()) snapshot = std::move(f.job.snapshot);  // reuse it
    ReplanRecord r = record_of(run, f, o.planner.algo, dt);
    if (r.solved()) {
      if (!previous.empty()) r.divergence = divergence(previous, f.plan.path);
      previous = f.plan.path;
      robot.follow(std::move(f.plan.path));
    }
    // A failed replan leaves the robot on its previous plan (as the seed's does).
    replans.push_back(std::move(r));
  };

  const Stopwatch wall;
  using Clock = std::chrono::steady_clock;
  const auto frame_wall =
      std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(dt));
  env::Vec<3> goal = at.goal;
  std::optional<RunEnd> end;  // set by the frame that ends the run
  for (std::uint64_t frame = 0;; ++frame) {
    const auto frame_start = Clock::now();
    if (frame % static_cast<std::uint64_t>(o.replan_every) == 0) {
      if (o.pace == Pace::lockstep || !thread.running()) {
        // One snapshot buffer, reused: lockstep plans from it here; the planner thread gets it
        // and hands it back with its plan.
        const Stopwatch snap_clock;
        take_snapshot(fluid.state(), exclude, snapshot);
        snapshot_ms.push_back(snap_clock.milliseconds());
        PlanJob job{std::move(snapshot), robot.position(), goal, replan_index++, frame};
        if (o.pace == Pace::lockstep) {
          FinishedPlan f;
          f.plan = replanner.plan(job.snapshot, job.robot, job.goal, job.replan_index);
          snapshot = std::move(job.snapshot);
          f.job = std::move(job);
          lockstep_queue.emplace_back(frame + static_cast<std::uint64_t>(o.lockstep_delay),
                                      std::move(f));
        } else {
          thread.launch(std::move(job));  // none is running: it starts
        }
      }
      // (realtime: a plan still running means this replan is skipped, as in the seed.)
    }
    if (o.pace == Pace::lockstep) {
      while (!lockstep_queue.empty() && lockstep_queue.front().first <= frame) {
        apply(std::move(lockstep_queue.front().second));
        lockstep_queue.pop_front();
      }
    } else if (auto f = thread.take()) {
      apply(std::move(*f));
    }

    const sph::FrameReport report = fluid.advance_frame();
    sph_ms.push_back(report.ms);
    rec.frames = frame + 1;
    rec.sim_time_s = static_cast<double>(frame + 1) * dt;
    if (!report.problem.empty()) {
      end = RunEnd::fluid_unstable;
      break;
    }
    env::Vec<3> velocity = robot.wished_velocity(dt);
    if (reactive)  // velocities: full_state() (a GPU backend copies them back)
      velocity = reactive->choose(fluid.full_state(), robot.position(), velocity, exclude, dt);
    robot.step(dt, velocity);
    if (at.goal_id != kNoParticle) goal = particle_position(fluid.state(), at.goal_id);
    trail.push_back(robot.position());
    const double gap = clearance(fluid.state(), robot.position(), o.safety, exclude).value();
    safety.observe(gap, dt);
    if (env::distance<3>(robot.position(), goal) <= o.goal_radius)
      end = RunEnd::goal_reached;
    else if (rec.sim_time_s >= o.max_sim_s - 1e-9)
      end = RunEnd::sim_time_cap;
    else if (o.max_wall_s > 0 && wall.milliseconds() >= o.max_wall_s * 1e3)
      end = RunEnd::wall_time_cap;
    if (on_frame) {
      FrameView v{run,  frame + 1,     &fluid.state(), &fluid, robot.position(),
                  goal, &robot.path(), &trail,         gap,    end.has_value()};
      on_frame(v);
    }
    if (end) break;
    if (should_stop && should_stop()) break;
    if (o.pace == Pace::realtime) std::this_thread::sleep_until(frame_start + frame_wall);
  }
  if (!end) {  // interrupted: the run is dropped whole (a restart makes it again)
    thread.cancel();
    (void)thread.take();
    return false;
  }
  rec.end = *end;
  // The run is over: a plan still running is cancelled (and logged as such); finished ones that
  // were not applied yet are logged as the replans they were.
  thread.cancel();
  if (auto f = thread.take()) {
    if (!f->error.empty()) throw RunError(f->error);
    replans.push_back(record_of(run, *f, o.planner.algo, dt));
  }
  for (auto& [at_frame, f] : lockstep_queue)
    replans.push_back(record_of(run, f, o.planner.algo, dt));
  rec.wall_time_s = wall.milliseconds() * 1e-3;
  rec.sph_ms_per_frame = quantile(sph_ms, 0.5);
  rec.snapshot_ms = quantile(snapshot_ms, 0.5);
  rec.distance_travelled = robot.travelled();
  rec.contacts = safety.contacts;
  rec.contact_frames = safety.contact_frames;
  rec.contact_time_s = safety.contact_time_s;
  rec.min_clearance = safety.min_clearance;  // +infinity: nothing to collide with
  rec.max_overlap = safety.max_overlap;
  rec.reactive_overrides = reactive ? reactive->overrides() : 0;
  return true;
}

}  // namespace

SimResult run_simulation(
    const SimOptions& options,
    const std::function<void(const RunRecord&, const SimResult& so_far)>& on_run,
    const std::function<void(const FrameView&)>& on_frame, SimResult done,
    const std::function<bool()>& should_stop) {
  validate(options);
  if (done.runs.size() > static_cast<std::size_t>(options.runs))
    throw InputError("the runs already made (" + std::to_string(done.runs.size()) +
                     ") are more than --runs " + std::to_string(options.runs));
  SimResult result = std::move(done);
  for (int run = static_cast<int>(result.runs.size()) + 1; run <= options.runs; ++run) {
    RunRecord rec;
    const std::size_t replans_before = result.replans.size();
    if (!run_one(options, run, rec, result.replans, on_frame, should_stop)) {
      result.replans.resize(replans_before);
      result.interrupted = true;
      break;
    }
    summarise_replans(rec, result.replans);
    result.runs.push_back(rec);
    if (on_run) on_run(rec, result);
  }
  return result;
}

}  // namespace hpcplan::sim
