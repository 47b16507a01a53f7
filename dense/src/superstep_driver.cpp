// The superstep driver (superstep.hpp): the one level-synchronous loop of the dense engine.
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <stdexcept>
#include <string>

#include "engine_checkpoint.hpp"
#include "hpcplan/core/error.hpp"
#include "hpcplan/core/stopwatch.hpp"
#include "superstep.hpp"

namespace hpcplan::dense::detail {

namespace {

// The stops in increasing severity (a stop's severity is its place here + 1; failed follows).
constexpr Status kStops[] = {Status::timeout, Status::budget_exceeded, Status::cancelled};
constexpr std::uint64_t kFailedSeverity = std::size(kStops) + 1;

std::uint64_t severity_of(Status s) {
  for (std::size_t i = 0; i < std::size(kStops); ++i)
    if (kStops[i] == s) return i + 1;
  return 0;
}

// One thread's state in the driver: its control block and what it published (its report, its
// halt, and on thread 0 the checkpoint schedule's answer), by step parity.
struct alignas(64) DriverThread {
  ThreadControl control;
  Decision published[2];
};

Decision combine(const std::vector<DriverThread>& threads, int slot) {
  Decision d;
  for (const DriverThread& t : threads) {
    const Decision& p = t.published[slot];
    d.sum.fresh += p.sum.fresh;
    d.sum.pending += p.sum.pending;
    d.sum.list_bytes += p.sum.list_bytes;
    d.sum.active += p.sum.active;
    d.sum.next_key = std::min(d.sum.next_key, p.sum.next_key);
    d.sum.goal = d.sum.goal || p.sum.goal;
    d.halt.merge(p.halt);
    d.save = std::max(d.save, p.save);
  }
  return d;
}

// The ranks' decision from this rank's: sums, the least key, and the most severe halt. A
// failing reduction is a failure of this rank.
void reduce_over_ranks(SlabTransport& tr, Decision& d) {
  std::uint64_t sums[3] = {d.sum.fresh, d.sum.pending, d.sum.active};
  std::uint64_t maxes[3] = {d.sum.goal ? 1u : 0u, d.halt.severity(),
                            static_cast<std::uint64_t>(d.save)};
  tr.sum(sums);
  tr.max(maxes);
  tr.min(std::span<double>(&d.sum.next_key, 1));
  d.sum.fresh = sums[0];
  d.sum.pending = sums[1];
  d.sum.active = sums[2];
  d.sum.goal = maxes[0] != 0;
  d.halt = Halt::of_severity(maxes[1]);
  d.save = static_cast<int>(maxes[2]);
}

// After the parallel region: an OpenMP team smaller than asked (a thread limit, OMP_DYNAMIC)
// would have left blocks unexpanded, so it is an error, not an answer; then a thread's
// exception, or another rank's failure.
void rethrow_failure(const std::vector<DriverThread>& threads, int team, bool failed) {
  if (team != static_cast<int>(threads.size()))
    throw RunError("dense engine: OpenMP started " + std::to_string(team) + " of the " +
                   std::to_string(threads.size()) +
                   " threads asked for (OMP_DYNAMIC or OMP_THREAD_LIMIT); use --threads " +
                   std::to_string(team));
  for (const DriverThread& t : threads)
    if (t.control.error) std::rethrow_exception(t.control.error);
  if (failed) throw RunError("dense engine: another rank failed");
}

}  // namespace

void Halt::raise(Status s) {
  // A status outside the order would be dropped by the ranks' reduction (severity 0) while it
  // ends this rank's run: the ranks would decide differently.
  if (severity_of(s) == 0)
    throw std::logic_error("dense engine: a run stops only on timeout, budget or cancel, not " +
                           std::string(to_string(s)));
  if (!stop || severity_of(s) > severity_of(*stop)) stop = s;
}
void Halt::merge(const Halt& other) {
  failed = failed || other.failed;
  if (other.stop) raise(*other.stop);
}
std::uint64_t Halt::severity() const {
  return failed ? kFailedSeverity : stop ? severity_of(*stop) : 0;
}
Halt Halt::of_severity(std::uint64_t s) {
  Halt h;
  if (s >= kFailedSeverity)
    h.failed = true;
  else if (s > 0)
    h.stop = kStops[s - 1];
  return h;
}

Result run_supersteps(SuperstepAlgorithm& alg, const ObstacleSource& field, const Query& q,
                      SlabTransport& tr, const SlabMap& slabs, std::uint64_t free_states) {
  Result res;
  Stopwatch clock;
  const int T = slabs.threads;
  std::vector<DriverThread> threads(T);
  // What every thread polls in its work; thread 0 alone also evaluates the query's condition
  // (Stop's contract: a condition runs on one polling thread), once per step.
  const Stop workers_stop = q.stop.without_condition();
  for (DriverThread& t : threads) t.control.workers_stop = &workers_stop;

  // The checkpoint files of this rank: the job's FILE on one rank, FILE.r<rank> on several.
  const Checkpointing& cp = q.checkpointing;
  const std::string save_path = cp.path.empty() ? "" : rank_file(cp.path, tr.rank(), tr.ranks());
  const std::string restart_path =
      cp.restart.empty() ? "" : rank_file(cp.restart, tr.rank(), tr.ranks());
  const std::string identity =
      save_path.empty() && restart_path.empty() ? "" : run_identity(field, q, slabs);

  Totals totals;
  if (restart_path.empty()) {
    totals = alg.start();
  } else {
    agree_on_restart(tr, [&] {
      const std::string file = read_checkpoint_file(restart_path);
      checkpoint::Reader r(open_checkpoint(file, restart_path, identity), restart_path);
      alg.restore(r, totals);
      if (r.left() != 0) r.fail("has bytes after its end (damaged)");
      return totals.steps;
    });
  }
  const std::uint64_t fixed = alg.fixed_bytes();
  const bool field_run = q.distances != nullptr;
  const bool trivial = alg.solved_at_start();

  DenseProgress progress(q.progress_label, q.progress_after_s, free_states);
  CheckpointSchedule schedule(cp);
  Status status = Status::no_path;
  bool solved = trivial, failed = false;
  const std::uint64_t budget = q.memory_budget;
  std::vector<std::vector<std::byte>> to_peers, from_peers;  // the halo swap's buffers
  int team = T;
  // Whether this rank trades with others: then the master thread runs the halo swap and the
  // ranks' reduction, each between barriers. Alone, every thread takes the decision itself
  // from what the others published: fewer points where a thread on a time-shared core can
  // hold up the others.
  const bool alone = tr.ranks() == 1;
  Decision shared;  // the ranks' decision, from the master thread (not alone)
  // Tiles worked on in each step, over every rank (from the resumed step on after a restart).
  std::vector<std::uint64_t> step_active;
#pragma omp parallel num_threads(T) if (T > 1)
  {
    const int id = omp_get_thread_num();
    DriverThread& me = threads[id];
    ThreadControl& ctl = me.control;
    if (omp_get_num_threads() != T) {
#pragma omp master
      team = omp_get_num_threads();
    } else if (!trivial) {
      Superstep step{totals.steps, totals.key};
      for (;;) {
        int save = 0;
        try {
          alg.work(id, step, ctl);
          if (budget && alg.list_bytes(id) * T + fixed > budget)
            ctl.halt.raise(Status::budget_exceeded);
          if (id == 0) {
            if (q.stop.can_stop())
              if (const auto s = q.stop.check()) ctl.halt.raise(*s);
            save = schedule.due();
          }
        } catch (...) {
          ctl.caught();
        }
#pragma omp barrier
        if (!alone) {
#pragma omp master
          try {
            alg.send_halo(to_peers);
            tr.exchange(slabs.peers, to_peers, from_peers);
            alg.receive_halo(from_peers);
          } catch (...) {
            threads.front().control.caught();
          }
#pragma omp barrier
        }
        try {
          alg.receive(id, step);
        } catch (...) {
          ctl.caught();
        }
        const int slot = static_cast<int>(step.index & 1);
        Decision& mine = me.published[slot];
        try {
          mine.sum = alg.report(id);
        } catch (...) {
          ctl.caught();
          mine.sum = {};
        }
        mine.halt = ctl.halt;
        mine.save = save;
#pragma omp barrier
        Decision d;
        if (alone) {
          d = combine(threads, slot);
        } else {
#pragma omp master
          {
            shared = combine(threads, slot);
            try {
              reduce_over_ranks(tr, shared);
            } catch (...) {
              threads.front().control.caught();
              shared.halt.failed = true;  // the reduction itself failed
            }
          }
#pragma omp barrier
          d = shared;
        }
        ++step.index;
        step.key = alg.next_key(d);
        const bool end = d.halt.any() || (d.sum.goal && !field_run) || d.sum.pending == 0;
#pragma omp master
        {
          totals.steps = step.index;
          totals.key = step.key;
          totals.reached += d.sum.fresh;
          totals.peak_fresh = std::max(totals.peak_fresh, d.sum.fresh);
          totals.peak_pending = std::max(totals.peak_pending, d.sum.pending);
          totals.list_peak = std::max(totals.list_peak, d.sum.list_bytes);
          step_active.push_back(d.sum.active);
          if (d.sum.goal && !totals.goal_seen) {
            totals.goal_seen = true;
            totals.goal_step = step.index;
          }
          if (d.halt.failed)
            failed = true;
          else if (d.sum.goal && !field_run)
            solved = true;
          else if (d.halt.stop)
            status = *d.halt.stop;
          else if (d.sum.pending == 0)
            status = Status::no_path;
          try {
            progress.update(alg.progress_unit(), alg.progress_value(totals), totals.reached);
          } catch (...) {
            ctl.caught();  // ends the run at the next step's decision
          }
        }
        if (end) break;
        // Every read of this thread's outboxes (the other threads' receive, the master's halo
        // swap) happened before the last barrier.
        try {
          alg.next_step(id);
        } catch (...) {
          ctl.caught();
        }
        if (d.save) {
          // Every thread's lists are in place: the step's state is whole.
#pragma omp barrier
#pragma omp master
          try {
            checkpoint::Writer w;
            alg.save(w, totals);
            write_checkpoint(save_path, identity, w.bytes());
          } catch (...) {
            threads.front().control.caught();  // rethrown after the region
          }
#pragma omp barrier
          if (d.save == kSaveAndEnd) {
#pragma omp master
            status = Status::interrupted;
            break;
          }
        }
      }
    }
  }
  // Every rank must know of a failure before the collectives below: one raised after the last
  // decision (the checkpoint that ends an interrupted run, a team smaller than asked) would
  // otherwise leave the other ranks waiting in the first of them while this one throws.
  {
    bool mine = failed || team != T;
    for (const DriverThread& t : threads) mine = mine || t.control.error != nullptr;
    std::uint64_t any = mine ? 1 : 0;
    tr.max(std::span<std::uint64_t>(&any, 1));
    failed = any != 0;
  }
  rethrow_failure(threads, team, failed);

  Counters& k = res.counters;
  std::uint64_t local[2] = {alg.expanded(), alg.generated()};
  res.figures.rank_expanded = gather_ranks(tr, local[0]);
  res.figures.rank_search_ms = gather_ranks(tr, clock.milliseconds());
  tr.sum(std::span<std::uint64_t>(local, 2));
  k.expanded = local[0];
  k.generated = local[1];
  res.figures.bytes_needed = fixed;
  res.figures.step_active_tiles = std::move(step_active);
  for (std::uint64_t a : res.figures.step_active_tiles) res.figures.active_tiles += a;
  std::uint64_t bytes[2] = {fixed + totals.list_peak, fixed + totals.list_peak};
  tr.max(std::span<std::uint64_t>(bytes, 1));
  tr.sum(std::span<std::uint64_t>(bytes + 1, 1));
  res.figures.bytes_per_rank = bytes[0];
  res.figures.bytes_total = bytes[1];
  // A distance field that ran to its end (no stop) has solved the query if it reached the goal.
  if (field_run && status == Status::no_path && totals.goal_seen) solved = true;
  res.status = solved ? Status::solved : status;
  alg.finish(res, totals, solved);
  k.time_ms = clock.milliseconds();
  return res;
}

}  // namespace hpcplan::dense::detail
