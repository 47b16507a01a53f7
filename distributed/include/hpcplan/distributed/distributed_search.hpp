#pragma once
// Best-first search and BFS spread over MPI ranks. Every state has one owner rank (any
// callable State -> rank; for lattices the SplitMix64 ownership of ownership.hpp), and only
// the owner stores it, opens it and expands it. Successors owned elsewhere travel to their
// owners as records {state, g, move}. Each rank keeps its states in the same SearchStore the
// serial engine uses, so the relax/reopen/pop rules are the serial ones.
//
// Three schedules over that common core:
//  - async (HDA*): ranks expand independently; records go in batches over non-blocking sends
//    (mpi::BatchedChannel) and are received by polling between slices of expansions. The goal's
//    owner turns every better arrival of the goal into a new incumbent cost and sends it to all
//    ranks; a state is pruned when it cannot beat the incumbent by more than the weight allows
//    (w * (g + h) >= incumbent). The search ends when no rank holds an open state and no
//    message is in flight, proven by Mattern's four-counter waves (mpi/termination.hpp).
//  - bulk_sync (seed 002 Algorithms 6-7): ranks expand up to N states, then all exchange
//    their records (mpi::AllToAllExchange) and agree by all-reduce on the incumbent and on
//    whether any open work is left.
//  - level_sync BFS (seed 002 Algorithm 4): each BFS level is expanded, exchanged and closed
//    by an all-reduce, so the goal is first stored at its fewest-hops level.
// Optimality (w = 1): while the incumbent exceeds the optimum C*, some state of an optimal
// path is open or in flight with its optimal g, and f <= C* < incumbent keeps it from being
// pruned, so the search cannot end before the goal's owner has seen C*. With w > 1, closed
// states are reopened (expansion order differs from serial, so the serial no-reopen argument
// does not carry over) and the same argument with the pruning rule gives cost <= w * C*.
// The path is rebuilt from the owners' parent moves, one owner's run of states at a time.
// A one-rank job runs the serial engine (best_first.hpp) on the same store: no schedule.
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <thread>
#include <vector>

#include "hpcplan/core/error.hpp"
#include "hpcplan/core/stopwatch.hpp"
#include "hpcplan/distributed/sent_filter.hpp"
#include "hpcplan/mpi/alltoall_exchange.hpp"
#include "hpcplan/mpi/batched_channel.hpp"
#include "hpcplan/mpi/communicator.hpp"
#include "hpcplan/mpi/termination.hpp"
#include "hpcplan/search/best_first.hpp"
#include "hpcplan/search/search_result.hpp"
#include "hpcplan/search/search_store.hpp"

namespace hpcplan::distributed {

enum class Scheme { async, bulk_sync, level_sync };

struct DistOptions {
  Scheme scheme = Scheme::async;
  std::size_t batch = 512;          // async: records per message
  double batch_age_ms = 0.5;        // async: longest a buffered record waits before it is sent
  int poll_every = 64;              // async: expansions between polls of the network
  std::uint64_t sync_every = 4096;  // bulk_sync: expansions between exchanges (the seed's N)
  bool yield_when_idle = false;     // async: give the core away while idle (oversubscribed runs)
  int sent_filter_log2 = 16;        // slots of the duplicate filter on outgoing records; 0 = off
  // Fault injection for the failure tests: > 0 makes this rank fail once it has expanded this
  // many states, while the others wait for it in the exchange: it throws a RunError (a bug, a
  // failed allocation), or with fault_kill it dies at once (SIGKILL: the node lost, the OOM
  // killer). 0: never.
  std::uint64_t fail_after_expansions = 0;
  bool fault_kill = false;
};

template <class State>
struct DistResult {
  search::Result<State> result;                // on every rank; counters summed (rank 0)
  std::vector<search::RankCounters> per_rank;  // rank 0 only
};

template <class State, class Cost, class Move>
struct StateRecord {
  State state;
  Cost g;
  Move move;
};

struct ControlRecord {
  enum Kind : std::uint32_t { incumbent = 1, abort = 2 };
  std::uint32_t kind = 0;
  std::uint32_t status = 0;  // abort: the search::Status that stopped the search
  double value = 0.0;        // incumbent: its cost
};

template <class MapPolicy, search::SearchGraph G, class Heuristic, class Owner>
class DistributedSearch {
 public:
  using State = typename G::State;
  using Cost = typename G::Cost;
  using Move = typename G::Move;
  using Store = search::SearchStore<MapPolicy, G, Heuristic>;
  using Record = StateRecord<State, Cost, Move>;

  DistributedSearch(const G& graph, const Heuristic& h, const Owner& owner,
                    const mpi::Communicator& comm, search::Options options, const DistOptions& dist)
      : graph_(graph),
        h_(h),
        owner_(owner),
        comm_(comm),
        serial_options_(options),
        options_(adjusted(options, dist)),
        dist_(dist),
        rank_(comm.rank()),
        // States from other ranks, and reopened ones, can arrive below the last priority
        // popped here; the store keeps those in its binary heap and the rest in the radix list.
        store_(h, options_, search::kMonotonePriorities<Heuristic, G>),
        sent_(dist.sent_filter_log2, dist.scheme == Scheme::level_sync) {}

  // Collective: every rank calls it with the same arguments.
  DistResult<State> run(const State& start, const State& goal) {
    // One rank owns everything, so there is nothing to route, send or agree on: the job is
    // the serial search, and running the serial engine itself keeps P = 1 exactly as fast
    // and gives the serial expansion order (weighted A* without reopening included).
    if (comm_.size() == 1) return run_single(start, goal);
    goal_ = goal;
    checks_before_ = graph_.collision_checks();
    // All ranks start the clock together; waiting ranks sleep, because rank 0 may be busy
    // with a serial reference run (--compare-serial) that a spinning rank would slow down.
    comm_.quiet_barrier();
    clock_ = Stopwatch();
    if (owner_(start) == rank_) accept(start, Cost{}, G::kNoMove);
    switch (dist_.scheme) {
      case Scheme::async:
        run_async();
        break;
      case Scheme::bulk_sync:
        run_bulk_sync();
        break;
      case Scheme::level_sync:
        run_level_sync();
        break;
    }
    return finish(start);
  }

 private:
  static constexpr double kInf = std::numeric_limits<double>::infinity();
  enum Abort : std::uint32_t { none = 0, timed_out = 1, over_budget = 2, cancelled = 3 };

  static search::Options adjusted(search::Options o, const DistOptions& d) {
    if (d.scheme == Scheme::level_sync) {
      o.frontier = search::Frontier::fifo;
    } else {
      o.frontier = search::Frontier::best_first;
      o.reopen_closed = true;
    }
    return o;
  }

  DistResult<State> run_single(const State& start, const State& goal) {
    DistResult<State> out;
    out.result = search::best_first_search<MapPolicy>(graph_, start, goal, h_, serial_options_);
    const search::Counters& c = out.result.counters;
    search::RankCounters me;
    me.expanded = c.expanded;
    me.generated = c.generated;
    me.collision_checks = c.collision_checks;
    me.states_stored = c.peak_states;
    me.peak_open = c.peak_open;
    me.reopened = c.reopened;
    me.search_ms = c.time_ms;
    out.per_rank.push_back(me);
    return out;
  }

  // --- the part every schedule shares --------------------------------------------------

  // A state this rank owns, reached with cost g via move m. False once the budget is spent.
  [[gnu::always_inline]] bool accept(const State& t, const Cost& g, Move m) {
    const auto offered = store_.offer(t, g, m);
    if (offered == Store::Offered::pushed) {
      if (t == goal_ && cost_value(g) < incumbent_) {
        incumbent_ = cost_value(g);
        new_incumbent_ = true;
      }
    } else if (offered == Store::Offered::over_budget) {
      abort_locally(over_budget);
      return false;
    }
    return true;
  }

  // Costs at or above this cannot beat the incumbent (a margin absorbs rounding; exact
  // lattice costs that truly differ differ far more). +inf while there is no incumbent.
  double prune_bound() const { return incumbent_ - 1e-9 * (1.0 + incumbent_); }

  // Whether an open state can no longer beat the incumbent by more than the weight allows.
  bool prunable(const State& x, const Cost& g, double f) const {
    if (incumbent_ == kInf) return false;
    if (options_.weight == 1.0) return f >= prune_bound();
    return options_.weight * (cost_value(g) + cost_value(h_(x))) >= prune_bound();
  }

  // Collective, for the synchronous schedules: sums `work` and `found` over all ranks and
  // adopts the most severe stop any rank hit (cancel over budget over time limit). Time spent
  // counts as waiting.
  std::array<std::uint64_t, 2> agree(std::uint64_t work, std::uint64_t found) {
    Stopwatch wait;
    std::uint64_t sums[5] = {work, found, abort_ == timed_out ? 1u : 0u,
                             abort_ == over_budget ? 1u : 0u, abort_ == cancelled ? 1u : 0u};
    comm_.allreduce_sum(sums);
    wait_ms_ += wait.milliseconds();
    if (sums[4] != 0)
      abort_ = cancelled;
    else if (sums[3] != 0)
      abort_ = over_budget;
    else if (sums[2] != 0)
      abort_ = timed_out;
    return {sums[0], sums[1]};
  }

  template <class Route>
  void expand(const State& x, const Cost& gx, Route&& route) {
    ++expanded_;
    // Counted locally: a member updated per successor costs a store each time.
    std::uint64_t generated = 0;
    bool stop = false;
    // Where every successor is owned here, the loop is the serial engine's: no owner asked.
    if (holds_neighbourhood(x)) {
      graph_.for_each_successor(
          x, [&](const State& t, const Cost& cost, Move m) __attribute__((always_inline)) {
            ++generated;
            if (!stop) stop = !accept(t, gx + cost, m);
          });
      generated_ += generated;
      return;
    }
    const auto x_cell = cell_of(x);
    // (Forced inline, as the serial engine's: GCC kept it a call per successor.)
    auto emit = [&](const State& t, const Cost& cost, Move m) __attribute__((always_inline)) {
      ++generated;
      if (stop) return;
      const Cost gt = gx + cost;
      // x is owned here, so a neighbour in x's ownership cell is too: no hash needed.
      const int o = same_cell(x_cell, t) ? rank_ : owner_(t);
      if (o == rank_)
        stop = !accept(t, gt, m);
      else if (sent_.admit(t, cost_value(gt)))
        route(o, Record{t, gt, m});
    };
    if constexpr (search::FiltersSuccessors<G>) {
      // A graph whose successors cost collision checks (a configuration space's) first asks
      // whether each could change anything: a state owned here that the store would not
      // improve, or one already sent at no higher cost, is not tested at all. (Without this
      // the ranks tested 8.5 times the serial engine's states on the 7-link chain.)
      graph_.for_each_successor(x, emit, [&](const State& t, const Cost& cost) {
        const Cost gt = gx + cost;
        const int o = same_cell(x_cell, t) ? rank_ : owner_(t);
        return o == rank_ ? store_.could_improve(t, gt) : sent_.would_admit(t, cost_value(gt));
      });
    } else {
      graph_.for_each_successor(x, emit);
    }
    generated_ += generated;
  }

  // True when the owner vouches for x's whole unit neighbourhood and the graph's moves stay
  // inside it (both declare it; any other owner or graph is asked per successor).
  bool holds_neighbourhood(const State& x) const {
    if constexpr (
        requires { owner_.holds_neighbourhood(x); } && requires { G::kMoveRadius; })
      return G::kMoveRadius == 1 && owner_.holds_neighbourhood(x);
    else
      return false;
  }

  // Owners that group states into cells (Ownership::cell) let neighbours in the expanded
  // state's cell skip the owner hash; any other owner callable is asked every time.
  auto cell_of(const State& x) const {
    if constexpr (requires { owner_.cell(x); })
      return owner_.cell(x);
    else
      return 0;
  }
  template <class Cell>
  bool same_cell(const Cell& c, const State& t) const {
    if constexpr (requires { owner_.cell(t); })
      return owner_.coarsen_shift() > 0 && owner_.cell(t) == c;
    else
      return false;
  }

  // Pops and expands up to `limit` states; returns how many were expanded.
  template <class Route>
  std::uint64_t expand_slice(std::uint64_t limit, Route&& route) {
    std::uint64_t done = 0;
    State x;
    Cost g;
    double f;
    // BFS is done once the goal is stored: it was stored at its fewest-hops level.
    const bool fifo = options_.frontier == search::Frontier::fifo;
    while (done < limit && abort_ == none && !(fifo && incumbent_ < kInf) && store_.pop(x, g, f)) {
      if (x == goal_ || prunable(x, g, f)) {
        // With w = 1 the heap is ordered by the pruning key: everything left is prunable.
        if (options_.weight == 1.0 && !(x == goal_)) store_.clear_open();
        continue;
      }
      expand(x, g, route);
      ++done;
      if (expanded_ == dist_.fail_after_expansions) inject_fault();
      if ((expanded_ & 1023) == 0) check_time();
    }
    return done;
  }

  [[noreturn]] void inject_fault() const {
    if (dist_.fault_kill) std::raise(SIGKILL);
    throw RunError("injected fault after " + std::to_string(expanded_) +
                   " expansions (HPCPLAN_FAULT_THROW)");
  }

  void check_time() {
    if (abort_ != none) return;
    if (const auto why = options_.stop.check())
      abort_locally(*why == search::Status::cancelled ? cancelled : timed_out);
  }

  void abort_locally(Abort why) {
    if (abort_ != none) return;
    abort_ = why;
    abort_announce_ = true;
    store_.clear_open();
  }

  // --- async (HDA*) ---------------------------------------------------------------------

  void run_async() {
    const auto age = std::chrono::microseconds(
        static_cast<std::int64_t>(std::max(0.0, dist_.batch_age_ms) * 1000.0));
    mpi::BatchedChannel<Record> work(comm_, kWorkTag, dist_.batch, age);
    mpi::BatchedChannel<ControlRecord> control(comm_, kControlTag, 1, std::chrono::microseconds(0));
    mpi::TerminationDetector termination(comm_);
    auto route = [&](int dest, const Record& r) { work.post(dest, r); };
    auto broadcast_control = [&](const ControlRecord& c) {
      for (int d = 0; d < comm_.size(); ++d)
        if (d != rank_) control.post(d, c);
    };
    const std::uint64_t slice = static_cast<std::uint64_t>(std::max(1, dist_.poll_every));
    Stopwatch idle;
    bool was_passive = false;
    for (;;) {
      const bool had_work = !store_.open_empty();
      expand_slice(slice, route);
      control.poll([&](const ControlRecord& c, int) {
        if (c.kind == ControlRecord::incumbent) {
          incumbent_ = std::min(incumbent_, c.value);
        } else if (c.kind == ControlRecord::abort && abort_ == none) {
          abort_ = static_cast<Abort>(c.status);  // already announced by its sender
          store_.clear_open();
        }
      });
      work.poll([&](const Record& r, int) {
        if (abort_ == none) accept(r.state, r.g, r.move);
      });
      // A rank that is passive must not start anything unprompted (the termination proof
      // relies on it), so only a rank that had work announces its own timeout.
      if (had_work) check_time();
      if (new_incumbent_) {
        broadcast_control({ControlRecord::incumbent, 0, incumbent_});
        new_incumbent_ = false;
      }
      if (abort_announce_) {
        broadcast_control({ControlRecord::abort, static_cast<std::uint32_t>(abort_), 0.0});
        abort_announce_ = false;
      }
      const bool open_empty = store_.open_empty();
      if (open_empty)
        work.flush_all();
      else
        work.flush_aged();
      const bool passive = open_empty && !work.has_buffered() && !control.has_buffered();
      if (passive && !was_passive) idle = Stopwatch();
      if (!passive && was_passive) wait_ms_ += idle.milliseconds();
      was_passive = passive;
      const std::uint64_t sent = work.traffic().messages_sent + control.traffic().messages_sent;
      const std::uint64_t received =
          work.traffic().messages_received + control.traffic().messages_received;
      if (termination.poll(passive, sent, received)) break;
      if (passive && dist_.yield_when_idle) std::this_thread::yield();
    }
    if (was_passive) wait_ms_ += idle.milliseconds();
    sync_rounds_ = termination.waves();
    work.wait_all();
    control.wait_all();
    traffic_ = work.traffic();
    traffic_ += control.traffic();
  }

  // --- bulk-synchronous best-first ------------------------------------------------------

  void run_bulk_sync() {
    mpi::AllToAllExchange<Record> exchange(comm_);
    auto route = [&](int dest, const Record& r) { exchange.post(dest, r); };
    const std::uint64_t n = std::max<std::uint64_t>(1, dist_.sync_every);
    for (;;) {
      expand_slice(n, route);
      check_time();
      exchange.exchange([&](const Record& r, int) {
        if (abort_ == none) accept(r.state, r.g, r.move);
      });
      ++sync_rounds_;
      Stopwatch wait;
      incumbent_ = comm_.allreduce_min(incumbent_);
      wait_ms_ += wait.milliseconds();
      // With w = 1 the heap front bounds every open state (a stale front only errs towards
      // one more round).
      const bool has_work = abort_ == none && !store_.open_empty() &&
                            !(options_.weight == 1.0 && store_.best_priority() >= prune_bound());
      const std::uint64_t work = agree(has_work ? 1 : 0, 0)[0];
      if (abort_ != none || work == 0) break;
    }
    wait_ms_ += exchange.wait_ms();
    traffic_ = exchange.traffic();
  }

  // --- level-synchronous BFS ------------------------------------------------------------

  void run_level_sync() {
    mpi::AllToAllExchange<Record> exchange(comm_);
    auto route = [&](int dest, const Record& r) { exchange.post(dest, r); };
    for (;;) {
      const auto [frontier, found] = agree(store_.open_size(), incumbent_ < kInf ? 1 : 0);
      if (abort_ != none || found != 0 || frontier == 0) break;
      // Expand exactly this level: states opened meanwhile belong to the next one.
      expand_slice(store_.open_size(), route);
      check_time();
      exchange.exchange([&](const Record& r, int) {
        if (abort_ == none) accept(r.state, r.g, r.move);
      });
      ++sync_rounds_;
    }
    wait_ms_ += exchange.wait_ms();
    traffic_ = exchange.traffic();
  }

  // --- agreement, path and figures ------------------------------------------------------

  DistResult<State> finish(const State& start) {
    DistResult<State> out;
    search::Result<State>& r = out.result;
    const double incumbent = comm_.allreduce_min(incumbent_);
    const auto abort = static_cast<Abort>(comm_.allreduce_max(static_cast<double>(abort_)));
    if (abort == over_budget)
      r.status = search::Status::budget_exceeded;
    else if (abort == timed_out)
      r.status = search::Status::timeout;
    else if (abort == cancelled)
      r.status = search::Status::cancelled;
    else
      r.status = incumbent < kInf ? search::Status::solved : search::Status::no_path;
    if (r.status == search::Status::solved) {
      r.path = rebuild_path(start);
      const double length = search::validated_length(graph_, r.path);
      // Parents only improve after a state is reached, so the chain can only be cheaper.
      if (length > incumbent + 1e-9 * (1.0 + incumbent))
        throw RunError("internal error: distributed path is longer than the incumbent");
      r.cost = length;
      r.hops = r.path.size() - 1;
    }
    const double elapsed = clock_.milliseconds();

    search::RankCounters me;
    me.expanded = expanded_;
    me.generated = generated_;
    me.collision_checks = graph_.collision_checks() - checks_before_;
    me.states_stored = store_.stored();
    me.peak_open = store_.peak_open();
    me.reopened = store_.reopened();
    me.messages_sent = traffic_.messages_sent;
    me.messages_received = traffic_.messages_received;
    me.bytes_sent = traffic_.bytes_sent;
    me.bytes_received = traffic_.bytes_received;
    me.records_sent = traffic_.records_sent;
    me.records_received = traffic_.records_received;
    me.sync_rounds = sync_rounds_;
    me.records_filtered = sent_.dropped();
    me.wait_ms = wait_ms_;
    me.search_ms = elapsed;
    const auto bytes = comm_.gather(&me, sizeof me, 0);
    if (rank_ == 0) {
      out.per_rank.resize(comm_.size());
      std::memcpy(out.per_rank.data(), bytes.data(), bytes.size());
      search::Counters& c = r.counters;
      for (const auto& k : out.per_rank) {
        c.expanded += k.expanded;
        c.generated += k.generated;
        c.reopened += k.reopened;
        c.collision_checks += k.collision_checks;
        c.peak_states += k.states_stored;
        c.peak_open += k.peak_open;
        c.time_ms = std::max(c.time_ms, k.search_ms);
      }
    }
    return out;
  }

  // Collective. Walks parent moves back from the goal: the owner of the current state
  // follows the chain while it stays on that rank and broadcasts the moves; every rank
  // applies them, so all hold the same path and know the next owner.
  std::vector<State> rebuild_path(const State& start) {
    constexpr int kRun = 250;
    struct Segment {
      std::uint32_t count = 0;
      std::uint8_t done = 0;
      std::uint8_t broken = 0;
      Move moves[kRun];
    };
    const std::uint64_t limit = comm_.allreduce_sum(store_.stored()) + 1;
    std::vector<State> path;
    State s = goal_;
    while (path.size() <= limit) {
      const int o = owner_(s);
      Segment seg{};
      if (o == rank_) {
        State at = s;
        while (seg.count < kRun) {
          const auto* node = store_.find(at);
          if (node == nullptr) {
            seg.broken = 1;
            break;
          }
          seg.moves[seg.count++] = node->move;
          if (node->move == G::kNoMove) {
            seg.done = 1;
            break;
          }
          at = graph_.predecessor(at, node->move);
          if (owner_(at) != rank_) break;
        }
      }
      comm_.broadcast(&seg, sizeof seg, o);
      if (seg.broken) throw RunError("internal error: a path state is missing on its owner");
      for (std::uint32_t i = 0; i < seg.count; ++i) {
        path.push_back(s);
        if (seg.moves[i] != G::kNoMove) s = graph_.predecessor(s, seg.moves[i]);
      }
      if (seg.done) {
        std::reverse(path.begin(), path.end());
        if (!(path.front() == start))
          throw RunError("internal error: distributed path does not begin at the start");
        return path;
      }
    }
    throw RunError("internal error: distributed parent chain does not end");
  }

  static constexpr int kWorkTag = 101;
  static constexpr int kControlTag = 102;

  const G& graph_;
  const Heuristic& h_;
  const Owner& owner_;
  const mpi::Communicator& comm_;
  search::Options serial_options_;  // as the caller gave them: what a one-rank run uses
  search::Options options_;         // adjusted for the distributed schedules
  DistOptions dist_;
  int rank_;
  Store store_;
  SentFilter<State, typename G::Hash> sent_;
  State goal_{};
  Stopwatch clock_;
  std::uint64_t checks_before_ = 0;
  std::uint64_t expanded_ = 0;
  std::uint64_t generated_ = 0;
  std::uint64_t sync_rounds_ = 0;
  double incumbent_ = kInf;
  bool new_incumbent_ = false;
  Abort abort_ = none;
  bool abort_announce_ = false;
  double wait_ms_ = 0.0;
  mpi::Traffic traffic_;
};

}  // namespace hpcplan::distributed
