#include "hpcplan/sim/planner_thread.hpp"

#include <exception>

namespace hpcplan::sim {

bool PlannerThread::launch(PlanJob job) {
  if (running_.load(std::memory_order_acquire)) return false;
  running_.store(true, std::memory_order_release);
  // Assigning a jthread joins the previous one, which has already finished (running_ was false).
  thread_ = std::jthread([this, job = std::move(job)](std::stop_token stop) mutable {
    FinishedPlan done;
    try {
      done.plan = replanner_.plan(job.snapshot, job.robot, job.goal, job.replan_index, stop);
    } catch (const std::exception& e) {
      done.error = e.what();
    }
    done.job = std::move(job);
    {
      const std::lock_guard lock(mutex_);
      pending_ = std::move(done);
    }
    ready_.store(true, std::memory_order_release);
    running_.store(false, std::memory_order_release);
  });
  return true;
}

std::optional<FinishedPlan> PlannerThread::take() {
  if (!ready_.load(std::memory_order_acquire)) return std::nullopt;
  std::optional<FinishedPlan> out;
  {
    const std::lock_guard lock(mutex_);
    out.swap(pending_);
    ready_.store(false, std::memory_order_release);
  }
  return out;
}

void PlannerThread::cancel() {
  if (thread_.joinable()) {
    thread_.request_stop();
    thread_.join();
  }
  running_.store(false, std::memory_order_release);
}

}  // namespace hpcplan::sim
