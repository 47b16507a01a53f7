#pragma once
// The dense engine's superstep driver: the level-synchronous loop written once, for every
// algorithm that advances the whole lattice in steps (BFS levels, Dijkstra's cost buckets).
//
// The driver owns what a stencil code's driver owns: the OpenMP threads of this rank, the
// barriers between phases, the halo exchange with the neighbouring ranks, the decision that
// ends or continues the run (reduced over threads and ranks, ending with a Status), the
// checkpoint schedule, write and restart, the run's counters and figures, and the errors
// raised inside the parallel region. An algorithm (a SuperstepAlgorithm) supplies only its own
// work: expanding its part of the frontier, applying what other threads and ranks sent it,
// reporting its step, and, after the run, its answer.
//
// One step, every thread:
//   work(thread)       expand this thread's entries; targets another thread or rank holds go
//                      to outboxes. Thread 0 also polls the query's stop and the checkpoint
//                      schedule (Stop's contract: one thread evaluates the condition).
//   barrier
//   [several ranks]    the master thread swaps the rank's outboxes with its peer ranks
//   barrier            (send_halo / receive_halo)
//   receive(thread)    apply what the other threads and ranks sent this thread
//   publish            this thread's StepReport, halt and (thread 0) checkpoint request, in the
//                      slot of the step's parity
//   barrier
//   decide             one rank: every thread combines the published reports itself (no
//                      further barrier); several: the master thread combines them, reduces
//                      over the ranks, and a barrier hands the decision to the others
//   next_step(thread)  clear outboxes and the step's counters
//   [a checkpoint due] barrier, the master writes, barrier
// So a step costs two barriers on one rank and four on several, for every algorithm. A thread
// writes its published slot again only two steps later, after every thread has passed the
// next step's first barrier, so the lock-free reads of the other slots are ordered by the
// barriers alone.
#include <cstdint>
#include <exception>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "engine_common.hpp"
#include "hpcplan/core/checkpoint_file.hpp"
#include "hpcplan/core/status.hpp"
#include "hpcplan/core/stop.hpp"

namespace hpcplan::dense::detail {

// What one thread reports at the end of a step.
struct StepReport {
  std::uint64_t fresh = 0;       // states this step reached (BFS) or settled (Dijkstra)
  std::uint64_t pending = 0;     // entries left for later steps (0 on every thread: exhausted)
  std::uint64_t list_bytes = 0;  // its lists' memory
  std::uint64_t active = 0;      // tiles it worked on (BFS: swept with states of the level;
                                 // Dijkstra: class entries taken)
  double next_key = std::numeric_limits<double>::infinity();  // smallest pending key
  bool goal = false;                                          // it reached the goal
};

// How a run ends early. One vocabulary, Status, plus `failed` (an exception, rethrown after the
// parallel region): when threads or ranks disagree, the most severe wins, failed > cancelled >
// budget_exceeded > timeout.
struct Halt {
  std::optional<Status> stop;  // timeout, budget_exceeded or cancelled
  bool failed = false;

  void raise(Status s);  // std::logic_error unless timeout, budget_exceeded or cancelled
  void merge(const Halt& other);
  bool any() const { return failed || stop.has_value(); }
  // A total order of severity (0: none), for reductions over ranks.
  std::uint64_t severity() const;
  static Halt of_severity(std::uint64_t s);
};

// What every thread needs to know about the step it is in.
struct Superstep {
  std::uint64_t index = 0;  // steps done before this one
  double key = 0.0;         // its key: Dijkstra's bucket floor (BFS: unused)
};

// The decision taken after a step, the same on every thread of every rank.
struct Decision {
  StepReport sum;  // fresh, pending and list bytes summed, next_key the least, goal any
  Halt halt;
  int save = 0;  // a checkpoint after this step: kSave, kSaveAndEnd or 0
};

// The figures that carry over steps (and over a checkpoint).
struct Totals {
  std::uint64_t steps = 0;         // steps done
  std::uint64_t reached = 0;       // states reached or settled
  std::uint64_t peak_fresh = 0;    // most states one step reached
  std::uint64_t peak_pending = 0;  // most entries pending after a step
  std::uint64_t list_peak = 0;     // most list memory of this rank after a step
  double key = 0.0;                // the next step's key
  bool goal_seen = false;          // some step reached the goal (a distance field goes on)
  std::uint64_t goal_step = 0;     // the steps done when it did
};

// One thread's control block: its first exception and its halt, a cache line apart from the
// other threads'.
struct alignas(64) ThreadControl {
  std::exception_ptr error;
  Halt halt;
  const Stop* workers_stop = nullptr;  // the query's stop without its condition

  // Polls the token and the deadline; raises the halt and says whether to stop.
  bool poll() {
    if (!workers_stop->can_stop()) return false;
    if (const auto s = workers_stop->check()) {  // cancelled or timeout
      halt.raise(*s);
      return true;
    }
    return false;
  }
  // In a catch block: an exception may not leave an OpenMP region (std::terminate), so the
  // first one is kept and the run ends at the next decision on every thread and rank.
  void caught() {
    if (!error) error = std::current_exception();
    halt.failed = true;
  }
};

// An algorithm run by the driver. Its methods are called from the threads the comments name;
// a method called on every thread touches only that thread's part (and reads others' parts
// only in receive(), after the barrier that ends their writes).
class SuperstepAlgorithm {
 public:
  virtual ~SuperstepAlgorithm() = default;

  // Before the threads start (the calling thread), on a run that does not restart: places the
  // start state and returns the figures a fresh run starts from. solved_at_start: nothing to
  // do (a BFS whose start is its goal).
  virtual Totals start() = 0;
  virtual bool solved_at_start() const { return false; }
  // Bytes allocated before the lists grow (the store, marks, window table).
  virtual std::uint64_t fixed_bytes() const = 0;
  // A checkpoint's payload after `totals` steps, and its restoration (InputError if refused:
  // checkpoint::Reader::fail). The driver writes and reads the file around it.
  virtual void save(checkpoint::Writer& w, const Totals& totals) const = 0;
  virtual void restore(checkpoint::Reader& r, Totals& totals) = 0;

  // Every thread, each step (see superstep.hpp's header).
  virtual void work(int thread, const Superstep& step, ThreadControl& control) = 0;
  virtual void receive(int thread, const Superstep& step) = 0;
  virtual StepReport report(int thread) const = 0;
  virtual std::uint64_t list_bytes(int thread) const = 0;
  virtual void next_step(int thread) = 0;
  // The master thread, several ranks only: this rank's outboxes, one buffer per peer
  // (SlabMap::peers), and what the peers sent back, in the same order.
  virtual void send_halo(std::vector<std::vector<std::byte>>& to) = 0;
  virtual void receive_halo(const std::vector<std::vector<std::byte>>& from) = 0;
  // The key of the step after a decision (Dijkstra's next bucket; BFS: 0).
  virtual double next_key(const Decision& d) const = 0;
  // The progress line's unit and value ("level", 17).
  virtual const char* progress_unit() const = 0;
  virtual double progress_value(const Totals& totals) const = 0;

  // After the threads (collective): this rank's expansions and generations; then the answer's
  // figures (levels, peaks) and, when solved, its cost, hops and path.
  virtual std::uint64_t expanded() const = 0;
  virtual std::uint64_t generated() const = 0;
  virtual void finish(Result& result, const Totals& totals, bool solved) = 0;
};

// Runs `algorithm` over this rank's part `slabs` (with slabs.threads OpenMP threads) of a
// lattice of `free_states` free states: collective over the transport's ranks. Fills the result's
// status, counters and shared figures, and calls finish(). Rethrows the first exception of any
// thread; RunError if another rank failed or OpenMP started fewer threads than asked.
Result run_supersteps(SuperstepAlgorithm& algorithm, const ObstacleSource& field, const Query& q,
                      SlabTransport& tr, const SlabMap& slabs, std::uint64_t free_states);

}  // namespace hpcplan::dense::detail
