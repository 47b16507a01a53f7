#pragma once
// Bulk-synchronous transport of fixed-size records: records for each destination collect
// locally and all ranks swap them at once in exchange() (MPI_Alltoall of counts, then
// MPI_Alltoallv of the records). Every exchange is a global synchronisation point; the time
// spent in it is reported as waiting. Knows nothing of searches.
#include <mpi.h>

#include <cstdint>
#include <type_traits>
#include <vector>

#include "hpcplan/core/stopwatch.hpp"
#include "hpcplan/mpi/communicator.hpp"
#include "hpcplan/mpi/traffic.hpp"

namespace hpcplan::mpi {

template <class Record>
class AllToAllExchange {
  static_assert(std::is_trivially_copyable_v<Record>, "records travel as raw bytes");

 public:
  explicit AllToAllExchange(const Communicator& comm)
      : comm_(comm.handle()),
        rank_(comm.rank()),
        out_(comm.size()),
        send_counts_(comm.size()),
        recv_counts_(comm.size()),
        send_displs_(comm.size()),
        recv_displs_(comm.size()) {}

  void post(int dest, const Record& r) { out_[dest].push_back(r); }

  // Swaps all buffered records between all ranks and calls on_record(record, source) for each
  // record received. Collective: every rank must call it the same number of times.
  template <class OnRecord>
  void exchange(OnRecord&& on_record) {
    Stopwatch wait;
    const int p = static_cast<int>(out_.size());
    std::size_t total = 0;
    for (int d = 0; d < p; ++d) {
      send_counts_[d] = static_cast<int>(out_[d].size() * sizeof(Record));
      send_displs_[d] = static_cast<int>(total * sizeof(Record));
      total += out_[d].size();
    }
    send_.resize(total);
    for (int d = 0, at = 0; d < p; ++d) {
      std::copy(out_[d].begin(), out_[d].end(), send_.begin() + at);
      at += static_cast<int>(out_[d].size());
      if (d != rank_ && !out_[d].empty()) {
        traffic_.messages_sent++;
        traffic_.bytes_sent += out_[d].size() * sizeof(Record);
        traffic_.records_sent += out_[d].size();
      }
      out_[d].clear();
    }
    MPI_Alltoall(send_counts_.data(), 1, MPI_INT, recv_counts_.data(), 1, MPI_INT, comm_);
    std::size_t in_bytes = 0;
    for (int s = 0; s < p; ++s) {
      recv_displs_[s] = static_cast<int>(in_bytes);
      in_bytes += static_cast<std::size_t>(recv_counts_[s]);
    }
    in_.resize(in_bytes / sizeof(Record));
    MPI_Alltoallv(send_.data(), send_counts_.data(), send_displs_.data(), MPI_BYTE, in_.data(),
                  recv_counts_.data(), recv_displs_.data(), MPI_BYTE, comm_);
    wait_ms_ += wait.milliseconds();
    for (int s = 0; s < p; ++s) {
      const std::size_t first = static_cast<std::size_t>(recv_displs_[s]) / sizeof(Record);
      const std::size_t count = static_cast<std::size_t>(recv_counts_[s]) / sizeof(Record);
      if (s != rank_ && count != 0) {
        traffic_.messages_received++;
        traffic_.bytes_received += count * sizeof(Record);
        traffic_.records_received += count;
      }
      for (std::size_t i = first; i < first + count; ++i) on_record(in_[i], s);
    }
  }

  const Traffic& traffic() const { return traffic_; }
  double wait_ms() const { return wait_ms_; }

 private:
  MPI_Comm comm_;
  int rank_;
  std::vector<std::vector<Record>> out_;
  std::vector<int> send_counts_, recv_counts_, send_displs_, recv_displs_;
  std::vector<Record> send_, in_;
  Traffic traffic_;
  double wait_ms_ = 0.0;
};

}  // namespace hpcplan::mpi
