#include "hpcplan/mpi/neighbour_exchange.hpp"

#include <climits>
#include <cstdint>

#include "hpcplan/core/error.hpp"

namespace hpcplan::mpi {
namespace {

// Tags of this exchange only, apart from the other transports' messages, one per direction:
// with two ranks the rank below is also the rank above, and the tag tells which buffer is which.
constexpr int kSizeDown = 7101, kSizeUp = 7102;  // sizes sent to the rank below / above
constexpr int kDataDown = 7103, kDataUp = 7104;

int checked_count(std::size_t bytes) {
  if (bytes > static_cast<std::size_t>(INT_MAX))
    throw RunError("halo exchange: a buffer over 2 GiB (" + std::to_string(bytes) + " bytes)");
  return static_cast<int>(bytes);
}

}  // namespace

void NeighbourExchange::exchange(int below, std::span<const std::byte> to_below, int above,
                                 std::span<const std::byte> to_above,
                                 std::vector<std::byte>& from_below,
                                 std::vector<std::byte>& from_above) {
  const MPI_Comm comm = comm_.handle();
  std::uint64_t send_size[2] = {to_below.size(), to_above.size()};
  std::uint64_t recv_size[2] = {0, 0};
  const int peer[2] = {below, above};
  MPI_Request req[4];
  int n = 0;
  // side 0: the rank below (we send it "down", it sent us "up"); side 1: the rank above.
  const int size_out[2] = {kSizeDown, kSizeUp}, size_in[2] = {kSizeUp, kSizeDown};
  const int data_out[2] = {kDataDown, kDataUp}, data_in[2] = {kDataUp, kDataDown};
  for (int side = 0; side < 2; ++side) {
    if (peer[side] < 0) continue;
    MPI_Irecv(&recv_size[side], 1, MPI_UINT64_T, peer[side], size_in[side], comm, &req[n++]);
    MPI_Isend(&send_size[side], 1, MPI_UINT64_T, peer[side], size_out[side], comm, &req[n++]);
  }
  MPI_Waitall(n, req, MPI_STATUSES_IGNORE);
  from_below.resize(below >= 0 ? recv_size[0] : 0);
  from_above.resize(above >= 0 ? recv_size[1] : 0);
  std::vector<std::byte>* into[2] = {&from_below, &from_above};
  const std::span<const std::byte> out[2] = {to_below, to_above};
  n = 0;
  for (int side = 0; side < 2; ++side) {
    if (peer[side] < 0) continue;
    if (recv_size[side] > 0)
      MPI_Irecv(into[side]->data(), checked_count(recv_size[side]), MPI_BYTE, peer[side],
                data_in[side], comm, &req[n++]);
    if (!out[side].empty()) {
      MPI_Isend(out[side].data(), checked_count(out[side].size()), MPI_BYTE, peer[side],
                data_out[side], comm, &req[n++]);
      ++traffic_.messages_sent;
      traffic_.bytes_sent += out[side].size();
    }
    if (recv_size[side] > 0) {
      ++traffic_.messages_received;
      traffic_.bytes_received += recv_size[side];
    }
  }
  MPI_Waitall(n, req, MPI_STATUSES_IGNORE);
}

}  // namespace hpcplan::mpi
