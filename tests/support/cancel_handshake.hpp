#pragma once
// Cancelling a run from another thread while it runs, on any machine: the run's own stop
// condition (which its polling loop calls) says that the run is under way, then holds it until
// the cancel has been requested; the canceller waits for that word. What a test then checks
// (the run ends cancelled, within one poll) does not depend on how fast the machine, or a
// sanitizer, is.
#include <atomic>
#include <functional>
#include <stop_token>
#include <thread>

namespace hpcplan::test_support {

class CancelHandshake {
 public:
  // The run's stop condition: on its `hold_at`-th call it says "running" and waits for the
  // cancel; it never stops the run itself (the token does).
  std::function<bool()> condition(int hold_at = 1) {
    return [this, hold_at] {
      if (++calls_ == hold_at) {
        running_ = true;
        while (!source_.stop_requested()) std::this_thread::yield();
      }
      return false;
    };
  }
  std::stop_token token() const { return source_.get_token(); }
  // A thread that cancels once the run has said that it is under way. If the run ends without
  // saying so (it finished first: the test then fails on its status), the thread's own stop,
  // requested when it is joined, releases it instead of hanging the test.
  std::jthread canceller() {
    return std::jthread([this](std::stop_token joined) {
      while (!running_ && !joined.stop_requested()) std::this_thread::yield();
      source_.request_stop();
    });
  }
  int calls() const { return calls_; }

 private:
  std::stop_source source_;
  std::atomic<bool> running_{false};
  std::atomic<int> calls_{0};
};

}  // namespace hpcplan::test_support
