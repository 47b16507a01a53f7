#pragma once
// Asynchronous point-to-point transport of fixed-size records: records for each destination
// collect in a buffer that is sent as one non-blocking message when it holds `batch` records
// or its oldest record is older than `max_age`; arrived messages are received by polling, so
// a rank keeps computing while its messages travel. Knows nothing of searches.
#include <mpi.h>

#include <chrono>
#include <cstdint>
#include <deque>
#include <exception>
#include <type_traits>
#include <vector>

#include "hpcplan/mpi/communicator.hpp"
#include "hpcplan/mpi/traffic.hpp"

namespace hpcplan::mpi {

template <class Record>
class BatchedChannel {
  static_assert(std::is_trivially_copyable_v<Record>, "records travel as raw bytes");
  using Clock = std::chrono::steady_clock;

 public:
  // `tag` separates this channel's messages from other channels on the same communicator.
  BatchedChannel(const Communicator& comm, int tag, std::size_t batch,
                 std::chrono::microseconds max_age)
      : comm_(comm.handle()),
        tag_(tag),
        batch_(batch == 0 ? 1 : batch),
        max_age_(max_age),
        out_(comm.size()),
        first_at_(comm.size()) {}

  // While an exception unwinds, the receivers may never take the pending messages, so waiting
  // could hang: their buffers are left alive (leaked) for MPI instead, and the job aborts.
  ~BatchedChannel() {
    if (std::uncaught_exceptions() == 0)
      wait_all();
    else if (!in_flight_.empty())
      new std::deque<InFlight>(std::move(in_flight_));
  }
  BatchedChannel(const BatchedChannel&) = delete;
  BatchedChannel& operator=(const BatchedChannel&) = delete;

  void post(int dest, const Record& r) {
    auto& buf = out_[dest];
    if (buf.empty()) {
      ++pending_buffers_;
      if (max_age_.count() > 0) first_at_[dest] = Clock::now();
    }
    buf.push_back(r);
    if (buf.size() >= batch_) send(dest);
  }

  // Sends every buffer whose oldest record has waited longer than max_age.
  void flush_aged() {
    if (pending_buffers_ == 0) return;
    const auto now = Clock::now();
    for (int d = 0; d < static_cast<int>(out_.size()); ++d)
      if (!out_[d].empty() && now - first_at_[d] >= max_age_) send(d);
  }
  void flush_all() {
    if (pending_buffers_ == 0) return;
    for (int d = 0; d < static_cast<int>(out_.size()); ++d)
      if (!out_[d].empty()) send(d);
  }
  bool has_buffered() const { return pending_buffers_ != 0; }

  // Receives every message that has arrived and calls on_record(record, source) for each of
  // its records. Returns the number of messages received.
  template <class OnRecord>
  std::size_t poll(OnRecord&& on_record) {
    std::size_t messages = 0;
    for (;;) {
      int arrived = 0;
      MPI_Status status;
      MPI_Iprobe(MPI_ANY_SOURCE, tag_, comm_, &arrived, &status);
      if (!arrived) break;
      int bytes = 0;
      MPI_Get_count(&status, MPI_BYTE, &bytes);
      in_.resize(static_cast<std::size_t>(bytes) / sizeof(Record));
      MPI_Recv(in_.data(), bytes, MPI_BYTE, status.MPI_SOURCE, tag_, comm_, MPI_STATUS_IGNORE);
      ++messages;
      traffic_.messages_received++;
      traffic_.bytes_received += static_cast<std::uint64_t>(bytes);
      traffic_.records_received += in_.size();
      for (const Record& r : in_) on_record(r, status.MPI_SOURCE);
    }
    reap();
    return messages;
  }

  // Completes every outstanding send (call once the receivers are known to take them).
  void wait_all() {
    while (!in_flight_.empty()) {
      MPI_Wait(&in_flight_.front().request, MPI_STATUS_IGNORE);
      recycle(std::move(in_flight_.front().data));
      in_flight_.pop_front();
    }
  }

  const Traffic& traffic() const { return traffic_; }

 private:
  struct InFlight {
    std::vector<Record> data;
    MPI_Request request;
  };

  void send(int dest) {
    InFlight f{spare(), MPI_REQUEST_NULL};
    f.data.swap(out_[dest]);
    --pending_buffers_;
    const int bytes = static_cast<int>(f.data.size() * sizeof(Record));
    traffic_.messages_sent++;
    traffic_.bytes_sent += static_cast<std::uint64_t>(bytes);
    traffic_.records_sent += f.data.size();
    in_flight_.push_back(std::move(f));
    // The vector's heap buffer does not move when the deque grows, so it stays valid.
    MPI_Isend(in_flight_.back().data.data(), bytes, MPI_BYTE, dest, tag_, comm_,
              &in_flight_.back().request);
  }

  // Recycles the buffers of completed sends (in order; later ones are checked next time).
  void reap() {
    while (!in_flight_.empty()) {
      int done = 0;
      MPI_Test(&in_flight_.front().request, &done, MPI_STATUS_IGNORE);
      if (!done) break;
      recycle(std::move(in_flight_.front().data));
      in_flight_.pop_front();
    }
  }
  std::vector<Record> spare() {
    if (free_.empty()) {
      std::vector<Record> v;
      v.reserve(batch_);
      return v;
    }
    auto v = std::move(free_.back());
    free_.pop_back();
    return v;
  }
  void recycle(std::vector<Record>&& v) {
    v.clear();
    if (free_.size() < 64) free_.push_back(std::move(v));
  }

  MPI_Comm comm_;
  int tag_;
  std::size_t batch_;
  std::chrono::microseconds max_age_;
  std::vector<std::vector<Record>> out_;
  std::vector<Clock::time_point> first_at_;
  std::size_t pending_buffers_ = 0;
  std::deque<InFlight> in_flight_;
  std::vector<std::vector<Record>> free_;
  std::vector<Record> in_;
  Traffic traffic_;
};

}  // namespace hpcplan::mpi
