// The Python module's Ctrl-C relay (python/interrupt_relay.hpp): while a job runs, SIGINT wakes
// the relay, which calls the job's on_interrupt, and the handler it replaced still runs; the job
// stays on the calling thread; the handler in place is restored however the job ends; a default
// or ignored SIGINT is left alone. Also run under ThreadSanitizer (threads_python).
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <functional>
#include <memory>
#include <stdexcept>
#include <stop_token>
#include <thread>

#include "hpcplan/python/interrupt_relay.hpp"

#if defined(__SANITIZE_THREAD__)
#define HPCPLAN_UNDER_TSAN 1
#elif defined(__has_feature)
#if __has_feature(thread_sanitizer)
#define HPCPLAN_UNDER_TSAN 1
#endif
#endif

namespace {

using hpcplan::python::InterruptRelay;
using namespace std::chrono_literals;

std::atomic<int> handled{0};  // the "previous" handler's calls (Python's, in the module)
extern "C" void count_sigint(int) {
  ++handled;
}

// SIGINT's handler for one test, put back after it.
class SigintHandler {
 public:
  explicit SigintHandler(void (*handler)(int)) {
    struct sigaction a {};
    a.sa_handler = handler;
    sigemptyset(&a.sa_mask);
    sigaction(SIGINT, &a, &previous_);
  }
  ~SigintHandler() { sigaction(SIGINT, &previous_, nullptr); }

 private:
  struct sigaction previous_ {};
};

void (*current_handler())(int) {
  struct sigaction now {};
  sigaction(SIGINT, nullptr, &now);
  return now.sa_handler;
}

// What a job's on_interrupt reaches. The relay thread may still be inside request_stop() when
// the job has seen the stop and the test has ended (interrupt_relay.hpp: on_interrupt must own
// what it uses), so each on_interrupt shares ownership of it; a stop_source on the test's
// stack was freed under the relay thread's feet (ThreadSanitizer, 2 runs in 300).
struct Relayed {
  std::stop_source stop;
  std::atomic<int> count{0};
};

// The on_interrupt that counts and stops.
std::function<void()> count_and_stop(const std::shared_ptr<Relayed>& relayed) {
  return [relayed] {
    ++relayed->count;
    relayed->stop.request_stop();
  };
}

// Waits until `stop` is requested, at most `limit`.
bool wait_for(const std::stop_source& stop, std::chrono::milliseconds limit) {
  const auto end = std::chrono::steady_clock::now() + limit;
  while (!stop.stop_requested() && std::chrono::steady_clock::now() < end)
    std::this_thread::sleep_for(1ms);
  return stop.stop_requested();
}

TEST(InterruptRelay, ASigintStopsTheJobAndStillReachesTheHandlerItReplaced) {
  const SigintHandler handler(count_sigint);
  handled = 0;
  const auto relayed = std::make_shared<Relayed>();
  const std::thread::id caller = std::this_thread::get_id();
  std::thread::id job_thread;
  bool stopped = false;
  InterruptRelay::run(
      [&] {
        job_thread = std::this_thread::get_id();
        std::thread([] { kill(getpid(), SIGINT); }).join();  // as a terminal's Ctrl-C
        stopped = wait_for(relayed->stop, 5000ms);
      },
      count_and_stop(relayed));
  EXPECT_TRUE(stopped);
  EXPECT_EQ(relayed->count.load(), 1);
  EXPECT_EQ(handled.load(), 1);
  EXPECT_EQ(job_thread, caller);
  EXPECT_EQ(current_handler(), &count_sigint);  // restored
}

TEST(InterruptRelay, TheHandlerIsRestoredWhenTheJobThrows) {
  const SigintHandler handler(count_sigint);
  EXPECT_THROW(InterruptRelay::run([] { throw std::runtime_error("failed"); }, [] {}),
               std::runtime_error);
  EXPECT_EQ(current_handler(), &count_sigint);
}

TEST(InterruptRelay, ADefaultOrIgnoredSigintIsLeftAlone) {
  for (void (*action)(int) : {SIG_DFL, SIG_IGN}) {
    const SigintHandler handler(action);
    void (*during)(int) = nullptr;
    InterruptRelay::run([&] { during = current_handler(); }, [] {});
    EXPECT_EQ(during, action);
    EXPECT_EQ(current_handler(), action);
  }
}

TEST(InterruptRelay, ARunInsideARunRelaysOnce) {
  const SigintHandler handler(count_sigint);
  const auto relayed = std::make_shared<Relayed>();
  const auto inner = std::make_shared<Relayed>();
  InterruptRelay::run(
      [&] {
        InterruptRelay::run(
            [&] {
              kill(getpid(), SIGINT);
              wait_for(relayed->stop, 5000ms);
            },
            count_and_stop(inner));
      },
      count_and_stop(relayed));
  EXPECT_EQ(relayed->count.load(), 1);
  EXPECT_EQ(inner->count.load(), 0);  // the inner run did not relay
  EXPECT_EQ(current_handler(), &count_sigint);
}

TEST(InterruptRelay, ASigintAfterTheJobReachesOnlyThePreviousHandler) {
  const SigintHandler handler(count_sigint);
  handled = 0;
  const auto relayed = std::make_shared<Relayed>();
  InterruptRelay::run([] {}, count_and_stop(relayed));
  kill(getpid(), SIGINT);
  // (A guard: the signal is delivered at once, under ThreadSanitizer at its next sync point.)
  const auto end = std::chrono::steady_clock::now() + 10000ms;
  while (handled.load() == 0 && std::chrono::steady_clock::now() < end)
    std::this_thread::sleep_for(1ms);
  EXPECT_EQ(handled.load(), 1);
  // A relay of that signal, which should not happen, would come before any later one: the
  // relay thread takes its wake-ups in order. So once the next job's own Ctrl-C is relayed,
  // the relay has looked at this one, and no sleep can pass while a late relay is still due.
  const auto next = std::make_shared<Relayed>();
  InterruptRelay::run(
      [&] {
        kill(getpid(), SIGINT);
        EXPECT_TRUE(wait_for(next->stop, 10000ms));
      },
      count_and_stop(next));
  EXPECT_EQ(next->count.load(), 1);
  EXPECT_EQ(relayed->count.load(), 0);
}

TEST(InterruptRelay, ManyJobsInARowEachRelayTheirOwnSignal) {
  const SigintHandler handler(count_sigint);
  for (int k = 0; k < 20; ++k) {
    const auto relayed = std::make_shared<Relayed>();
    InterruptRelay::run(
        [&] {
          kill(getpid(), SIGINT);
          EXPECT_TRUE(wait_for(relayed->stop, 5000ms)) << k;
        },
        count_and_stop(relayed));
    EXPECT_EQ(relayed->count.load(), 1) << k;
  }
}

// A relay thread that wakes late (here: still inside the previous job's on_interrupt) does not
// stop the job under way for a signal that reached the job before it. Before run numbers, the
// late wake-up stopped the next call (a Python loop that catches KeyboardInterrupt and calls
// again saw that call cancelled with no Ctrl-C during it).
TEST(InterruptRelay, ALateRelayDoesNotStopTheNextJob) {
  const SigintHandler handler(count_sigint);
  // Job 0's on_interrupt holds the relay thread for a while.
  auto held = std::make_shared<std::atomic<bool>>(false);
  InterruptRelay::run(
      [&] {
        kill(getpid(), SIGINT);
        const auto end = std::chrono::steady_clock::now() + 5000ms;
        while (!held->load() && std::chrono::steady_clock::now() < end)
          std::this_thread::sleep_for(1ms);
        ASSERT_TRUE(held->load());
      },
      [held] {
        held->store(true);
        std::this_thread::sleep_for(300ms);
      });
  // Job A gets a Ctrl-C and ends before the relay thread is free to look at it.
  const auto a = std::make_shared<Relayed>();
  InterruptRelay::run([] { kill(getpid(), SIGINT); }, count_and_stop(a));
  // Job B runs past the moment the relay thread wakes: nothing may stop it.
  const auto b = std::make_shared<Relayed>();
  bool b_stopped = true;
  InterruptRelay::run([&] { b_stopped = wait_for(b->stop, 700ms); }, count_and_stop(b));
  EXPECT_FALSE(b_stopped);
  EXPECT_EQ(b->count.load(), 0);
  EXPECT_EQ(a->count.load(), 0);  // A had ended: its signal reached only Python's handler
}

// os.fork() from a second Python thread while the main thread's call runs: the child has no
// such call and no relay thread. Its own runs must still relay; before, the parent's run stayed
// "under way" in the child and no later run there relayed a signal.
TEST(InterruptRelay, AChildForkedDuringARunRelaysItsOwnRuns) {
#ifdef HPCPLAN_UNDER_TSAN
  GTEST_SKIP() << "ThreadSanitizer ends a child of a threaded process that starts a thread";
#endif
  const SigintHandler handler(count_sigint);
  int status = -1;
  InterruptRelay::run(
      [&] {
        std::thread([&] {
          const pid_t child = fork();
          if (child == 0) {
            const auto own = std::make_shared<Relayed>();
            bool stopped = false;
            InterruptRelay::run(
                [&] {
                  kill(getpid(), SIGINT);
                  stopped = wait_for(own->stop, 5000ms);
                },
                count_and_stop(own));
            _exit(stopped && current_handler() == &count_sigint ? 0 : 1);
          }
          waitpid(child, &status, 0);
        }).join();
      },
      [] {});
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 0);
  EXPECT_EQ(current_handler(), &count_sigint);
}

}  // namespace
