#include "hpcplan/python/polled_worker.hpp"

#include <pthread.h>
#include <signal.h>
#include <unistd.h>

namespace hpcplan::python {

PolledWorker::~PolledWorker() {
  if (!thread_) return;
  if (owner_ != getpid()) {  // a forked child's copy: there is no thread to end
    (void)thread_.release();
    return;
  }
  {
    std::lock_guard lock(m_);
    quit_ = true;
  }
  wake_.notify_one();
  thread_->join();
}

void PolledWorker::start() {
  if (thread_ && owner_ == getpid()) return;
  // Inherited through fork(): that thread does not exist in this process; its handle is
  // dropped without being touched.
  if (thread_) (void)thread_.release();
  job_ = nullptr;
  finished_ = quit_ = false;
  owner_ = getpid();
  // Started with the signals blocked, so that the thread inherits the mask from its first
  // instruction on.
  sigset_t blocked, previous;
  sigemptyset(&blocked);
  for (int s : {SIGINT, SIGTERM, SIGUSR1, SIGUSR2, SIGHUP, SIGQUIT, SIGALRM})
    sigaddset(&blocked, s);
  pthread_sigmask(SIG_BLOCK, &blocked, &previous);
  thread_ = std::make_unique<std::thread>([this] { loop(); });
  pthread_sigmask(SIG_SETMASK, &previous, nullptr);
}

void PolledWorker::loop() {
  std::unique_lock lock(m_);
  for (;;) {
    wake_.wait(lock, [this] { return job_ != nullptr || quit_; });
    if (job_ == nullptr) return;  // quit
    const std::function<void()>* job = job_;
    lock.unlock();
    std::exception_ptr error;
    try {
      (*job)();
    } catch (...) {
      error = std::current_exception();
    }
    lock.lock();
    job_ = nullptr;
    error_ = error;
    finished_ = true;
    done_.notify_one();
  }
}

void PolledWorker::run(const std::function<void()>& job, const std::function<void()>& poll,
                       std::chrono::milliseconds interval) {
  std::lock_guard caller(callers_);
  std::unique_lock lock(m_);
  start();
  finished_ = false;
  error_ = nullptr;
  job_ = &job;
  wake_.notify_one();
  std::exception_ptr poll_error;
  while (!done_.wait_for(lock, interval, [this] { return finished_; })) {
    lock.unlock();
    try {
      if (poll) poll();
    } catch (...) {
      if (!poll_error) poll_error = std::current_exception();
    }
    lock.lock();
  }
  const std::exception_ptr error = error_;
  error_ = nullptr;
  lock.unlock();
  if (poll_error) std::rethrow_exception(poll_error);
  if (error) std::rethrow_exception(error);
}

}  // namespace hpcplan::python
