#pragma once
#include <cstdint>

namespace hpcplan::mpi {

// What one rank's transport moved. A "message" is one MPI message (a batch of records).
struct Traffic {
  std::uint64_t messages_sent = 0;
  std::uint64_t messages_received = 0;
  std::uint64_t bytes_sent = 0;
  std::uint64_t bytes_received = 0;
  std::uint64_t records_sent = 0;
  std::uint64_t records_received = 0;

  Traffic& operator+=(const Traffic& o) {
    messages_sent += o.messages_sent;
    messages_received += o.messages_received;
    bytes_sent += o.bytes_sent;
    bytes_received += o.bytes_received;
    records_sent += o.records_sent;
    records_received += o.records_received;
    return *this;
  }
};

}  // namespace hpcplan::mpi
