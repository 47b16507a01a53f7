// The Python module's worker for long calls from the main thread (python/polled_worker.hpp):
// the job runs on the worker's own thread while the caller polls, the poll can stop it, an
// exception crosses back, the thread is kept between jobs and blocks the signals, and callers
// from several threads are served one at a time. Also run under ThreadSanitizer (threads_python).
#include <gtest/gtest.h>
#include <pthread.h>
#include <signal.h>

#include <atomic>
#include <chrono>
#include <stdexcept>
#include <stop_token>
#include <thread>
#include <vector>

#include "hpcplan/python/polled_worker.hpp"

namespace {

using hpcplan::python::PolledWorker;
using namespace std::chrono_literals;

TEST(PolledWorker, PollsWhileTheJobRunsOnItsOwnThread) {
  PolledWorker worker;
  std::atomic<int> polls{0};
  std::thread::id job_thread;
  worker.run(
      [&] {
        job_thread = std::this_thread::get_id();
        std::this_thread::sleep_for(100ms);
      },
      [&] { ++polls; }, 5ms);
  EXPECT_NE(job_thread, std::this_thread::get_id());
  EXPECT_GE(polls.load(), 5);
}

TEST(PolledWorker, APollStopsTheJobThroughItsToken) {
  PolledWorker worker;
  std::stop_source stop;
  int polls = 0;
  std::atomic<long> spins{0};
  const auto t0 = std::chrono::steady_clock::now();
  worker.run(
      [&] {
        while (!stop.stop_requested()) ++spins;
      },
      [&] {
        if (++polls == 3) stop.request_stop();
      },
      10ms);
  EXPECT_EQ(polls, 3);
  EXPECT_GT(spins.load(), 0);
  EXPECT_LT(std::chrono::steady_clock::now() - t0, 2s);
}

TEST(PolledWorker, TheJobsExceptionIsRethrownAndTheWorkerGoesOn) {
  PolledWorker worker;
  EXPECT_THROW(worker.run([] { throw std::runtime_error("job failed"); }, {}, 1ms),
               std::runtime_error);
  bool ran = false;
  worker.run([&] { ran = true; }, {}, 1ms);
  EXPECT_TRUE(ran);
}

TEST(PolledWorker, APollsExceptionComesAfterTheJobEnds) {
  PolledWorker worker;
  std::atomic<bool> job_done{false};
  std::stop_source stop;
  EXPECT_THROW(worker.run(
                   [&] {
                     while (!stop.stop_requested()) std::this_thread::sleep_for(1ms);
                     job_done = true;
                   },
                   [&] {
                     stop.request_stop();
                     throw std::runtime_error("KeyboardInterrupt");
                   },
                   2ms),
               std::runtime_error);
  EXPECT_TRUE(job_done.load());
}

TEST(PolledWorker, KeepsItsThreadWithTheSignalsBlocked) {
  PolledWorker worker;
  std::thread::id first, second;
  bool sigint_blocked = false, sigusr1_blocked = false;
  worker.run([&] { first = std::this_thread::get_id(); }, {}, 1ms);
  worker.run(
      [&] {
        second = std::this_thread::get_id();
        sigset_t mask;
        pthread_sigmask(SIG_BLOCK, nullptr, &mask);
        sigint_blocked = sigismember(&mask, SIGINT) == 1;
        sigusr1_blocked = sigismember(&mask, SIGUSR1) == 1;
      },
      {}, 1ms);
  EXPECT_EQ(first, second);
  EXPECT_TRUE(sigint_blocked);
  EXPECT_TRUE(sigusr1_blocked);
  sigset_t mine;  // the caller's mask is as it was
  pthread_sigmask(SIG_BLOCK, nullptr, &mine);
  EXPECT_FALSE(sigismember(&mine, SIGINT) == 1);
}

TEST(PolledWorker, ServesCallersFromSeveralThreadsOneAtATime) {
  PolledWorker worker;
  std::atomic<int> running{0}, most{0}, done{0};
  std::vector<std::thread> callers;
  for (int k = 0; k < 4; ++k)
    callers.emplace_back([&] {
      for (int j = 0; j < 5; ++j)
        worker.run(
            [&] {
              const int now = ++running;
              int seen = most.load();
              while (now > seen && !most.compare_exchange_weak(seen, now)) {
              }
              std::this_thread::sleep_for(1ms);
              --running;
              ++done;
            },
            [] {}, 1ms);
    });
  for (std::thread& t : callers) t.join();
  EXPECT_EQ(done.load(), 20);
  EXPECT_EQ(most.load(), 1);
}

}  // namespace
