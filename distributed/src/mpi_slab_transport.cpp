#include "hpcplan/distributed/mpi_slab_transport.hpp"

#include <mpi.h>

#include <algorithm>
#include <cstdint>

namespace hpcplan::distributed {
namespace {

// A tag of its own: the gather runs after the engine's last exchange, but a tag no other
// message uses keeps it apart from any halo traffic all the same.
constexpr int kGatherTag = 0x6a17;
constexpr std::size_t kPiece = std::size_t{1} << 30;

}  // namespace

std::vector<std::vector<std::byte>> MpiSlabTransport::gather_to_root(
    std::span<const std::byte> mine) {
  const Stopwatch clock;
  const MPI_Comm comm = comm_.handle();
  const int me = comm_.rank(), n = comm_.size();
  std::uint64_t size = mine.size();
  std::vector<std::uint64_t> sizes(me == 0 ? static_cast<std::size_t>(n) : 0);
  MPI_Gather(&size, 1, MPI_UINT64_T, sizes.data(), 1, MPI_UINT64_T, 0, comm);
  std::vector<std::vector<std::byte>> out;
  if (me == 0) {
    out.resize(static_cast<std::size_t>(n));
    out[0].assign(mine.begin(), mine.end());
    for (int r = 1; r < n; ++r) {
      std::vector<std::byte>& to = out[static_cast<std::size_t>(r)];
      to.resize(sizes[static_cast<std::size_t>(r)]);
      for (std::size_t at = 0; at < to.size(); at += kPiece) {
        const int k = static_cast<int>(std::min(kPiece, to.size() - at));
        MPI_Recv(to.data() + at, k, MPI_BYTE, r, kGatherTag, comm, MPI_STATUS_IGNORE);
      }
    }
  } else {
    for (std::size_t at = 0; at < mine.size(); at += kPiece) {
      const int k = static_cast<int>(std::min(kPiece, mine.size() - at));
      MPI_Send(mine.data() + at, k, MPI_BYTE, 0, kGatherTag, comm);
      ++messages_sent;
      bytes_sent += static_cast<std::uint64_t>(k);
    }
  }
  exchange_ms += clock.milliseconds();
  return out;
}

}  // namespace hpcplan::distributed
