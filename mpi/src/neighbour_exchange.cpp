#include "hpcplan/mpi/neighbour_exchange.hpp"

#include <climits>
#include <cstdint>
#include <stdexcept>

#include "hpcplan/core/error.hpp"

namespace hpcplan::mpi {
namespace {

// Tags of this exchange only, apart from the other transports' messages. A pair of ranks
// trades one buffer each way per exchange, so the tag need not say which buffer it is.
constexpr int kSize = 7101, kData = 7103;

int checked_count(std::size_t bytes) {
  if (bytes > static_cast<std::size_t>(INT_MAX))
    throw RunError("halo exchange: a buffer over 2 GiB (" + std::to_string(bytes) + " bytes)");
  return static_cast<int>(bytes);
}

}  // namespace

void NeighbourExchange::exchange(std::span<const int> peers,
                                 const std::vector<std::vector<std::byte>>& to,
                                 std::vector<std::vector<std::byte>>& from) {
  if (to.size() != peers.size())
    throw std::logic_error("halo exchange: one buffer per neighbour expected");
  const MPI_Comm comm = comm_.handle();
  const std::size_t n = peers.size();
  std::vector<std::uint64_t> send_size(n), recv_size(n, 0);
  std::vector<MPI_Request> req;
  req.reserve(2 * n);
  for (std::size_t i = 0; i < n; ++i) {
    send_size[i] = to[i].size();
    req.emplace_back();
    MPI_Irecv(&recv_size[i], 1, MPI_UINT64_T, peers[i], kSize, comm, &req.back());
    req.emplace_back();
    MPI_Isend(&send_size[i], 1, MPI_UINT64_T, peers[i], kSize, comm, &req.back());
  }
  MPI_Waitall(static_cast<int>(req.size()), req.data(), MPI_STATUSES_IGNORE);
  from.resize(n);
  req.clear();
  for (std::size_t i = 0; i < n; ++i) {
    from[i].resize(recv_size[i]);
    if (recv_size[i] > 0) {
      req.emplace_back();
      MPI_Irecv(from[i].data(), checked_count(recv_size[i]), MPI_BYTE, peers[i], kData, comm,
                &req.back());
      ++traffic_.messages_received;
      traffic_.bytes_received += recv_size[i];
    }
    if (!to[i].empty()) {
      req.emplace_back();
      MPI_Isend(to[i].data(), checked_count(to[i].size()), MPI_BYTE, peers[i], kData, comm,
                &req.back());
      ++traffic_.messages_sent;
      traffic_.bytes_sent += to[i].size();
    }
  }
  MPI_Waitall(static_cast<int>(req.size()), req.data(), MPI_STATUSES_IGNORE);
}

}  // namespace hpcplan::mpi
