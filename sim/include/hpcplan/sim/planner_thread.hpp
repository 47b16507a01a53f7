#pragma once
// The seed's background planner: at most one plan runs at a time on its own thread; the frame
// loop launches one when none is running (launch() refuses otherwise) and, at each frame,
// collects a finished one (take()). The hand-off is double-buffered: the planner writes its
// answer into a pending slot under a mutex and raises an atomic flag; the frame loop swaps the
// slot out under the same mutex, so neither side ever waits for the other's work. cancel() asks
// a running plan to stop through its stop token and joins it (a run's end).
//
// Threads: launch/take/cancel from the frame loop's thread only; the job runs on the planner's.
#include <atomic>
#include <cstdint>
#include <functional>
#include <mutex>
#include <optional>
#include <stop_token>
#include <string>
#include <thread>

#include "hpcplan/plan/fluid_planner.hpp"

namespace hpcplan::sim {

struct PlanJob {
  env::FluidSnapshot snapshot;
  env::Vec<3> robot{}, goal{};
  std::uint64_t replan_index = 0;
  std::uint64_t frame = 0;  // when it was launched
};

struct FinishedPlan {
  PlanJob job;
  plan::FluidPlan plan;
  std::string error;  // the planner threw (an internal error): the frame loop rethrows it
};

class PlannerThread {
 public:
  explicit PlannerThread(plan::FluidReplanner& replanner) : replanner_(replanner) {}
  ~PlannerThread() { cancel(); }
  PlannerThread(const PlannerThread&) = delete;
  PlannerThread& operator=(const PlannerThread&) = delete;

  bool running() const { return running_.load(std::memory_order_acquire); }
  // Starts the job unless a plan is running (then false, nothing started).
  bool launch(PlanJob job);
  // A plan that finished since the last take(), if any.
  std::optional<FinishedPlan> take();
  // Stops a running plan (it ends as cancelled) and waits for its thread.
  void cancel();

 private:
  plan::FluidReplanner& replanner_;
  std::jthread thread_;
  std::atomic<bool> running_{false};
  std::atomic<bool> ready_{false};
  std::mutex mutex_;
  std::optional<FinishedPlan> pending_;  // guarded by mutex_
};

}  // namespace hpcplan::sim
