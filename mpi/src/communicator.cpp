#include "hpcplan/mpi/communicator.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <climits>
#include <cstdlib>
#include <thread>

#include "hpcplan/core/cpu_set.hpp"
#include "hpcplan/core/error.hpp"

namespace hpcplan::mpi {

bool launched_by_mpi() {
  // Open MPI's mpirun, PMIx launchers (srun --mpi=pmix, prte) and PMI-1/2 launchers.
  for (const char* v : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK", "PMI_SIZE"})
    if (std::getenv(v) != nullptr) return true;
  return false;
}

Session::Session(int& argc, char**& argv) {
  int provided = 0;
  if (MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided) != MPI_SUCCESS)
    throw RunError("MPI_Init failed");
}

Session::~Session() {
  int finalized = 0;
  MPI_Finalized(&finalized);
  if (!finalized) MPI_Finalize();
}

Communicator::Communicator(MPI_Comm comm) : comm_(comm) {
  MPI_Comm_rank(comm_, &rank_);
  MPI_Comm_size(comm_, &size_);
  MPI_Comm node;
  MPI_Comm_split_type(comm_, MPI_COMM_TYPE_SHARED, rank_, MPI_INFO_NULL, &node);
  MPI_Comm_size(node, &ranks_on_node_);
  // The ranks of this node whose CPU sets overlap this one's: bound ranks (mpirun's default
  // binding, --map-by ...:PE=n, SLURM's cgroups) share none, unbound ones share every core.
  const CpuSet mine = CpuSet::of_this_process();
  std::vector<std::uint64_t> all(static_cast<std::size_t>(ranks_on_node_) * CpuSet::kWords);
  MPI_Allgather(mine.words().data(), CpuSet::kWords, MPI_UINT64_T, all.data(), CpuSet::kWords,
                MPI_UINT64_T, node);
  ranks_sharing_cpus_ = 0;
  for (int r = 0; r < ranks_on_node_; ++r) {
    std::array<std::uint64_t, CpuSet::kWords> w;
    std::copy_n(all.begin() + static_cast<std::ptrdiff_t>(r) * CpuSet::kWords, CpuSet::kWords,
                w.begin());
    if (CpuSet::from_words(w).overlaps(mine)) ++ranks_sharing_cpus_;
  }
  MPI_Comm_free(&node);
}

void Communicator::quiet_barrier() const {
  MPI_Request request;
  MPI_Ibarrier(comm_, &request);
  for (int done = 0;;) {
    MPI_Test(&request, &done, MPI_STATUS_IGNORE);
    if (done) return;
    std::this_thread::sleep_for(std::chrono::microseconds(200));
  }
}

double Communicator::allreduce_min(double v) const {
  double out = v;
  MPI_Allreduce(&v, &out, 1, MPI_DOUBLE, MPI_MIN, comm_);
  return out;
}

double Communicator::allreduce_max(double v) const {
  double out = v;
  MPI_Allreduce(&v, &out, 1, MPI_DOUBLE, MPI_MAX, comm_);
  return out;
}

std::uint64_t Communicator::allreduce_sum(std::uint64_t v) const {
  std::uint64_t out = v;
  MPI_Allreduce(&v, &out, 1, MPI_UINT64_T, MPI_SUM, comm_);
  return out;
}

void Communicator::allreduce_sum(std::span<std::uint64_t> values) const {
  MPI_Allreduce(MPI_IN_PLACE, values.data(), static_cast<int>(values.size()), MPI_UINT64_T, MPI_SUM,
                comm_);
}

void Communicator::allreduce_max(std::span<std::uint64_t> values) const {
  MPI_Allreduce(MPI_IN_PLACE, values.data(), static_cast<int>(values.size()), MPI_UINT64_T, MPI_MAX,
                comm_);
}

void Communicator::allreduce_min(std::span<double> values) const {
  MPI_Allreduce(MPI_IN_PLACE, values.data(), static_cast<int>(values.size()), MPI_DOUBLE, MPI_MIN,
                comm_);
}

std::vector<std::byte> Communicator::allgather(std::span<const std::byte> mine) const {
  if (mine.size() > static_cast<std::size_t>(INT_MAX))
    throw RunError("allgather: over 2 GiB from one rank");
  const int n = static_cast<int>(mine.size());
  std::vector<int> counts(size_), offsets(size_);
  MPI_Allgather(&n, 1, MPI_INT, counts.data(), 1, MPI_INT, comm_);
  std::size_t total = 0;
  for (int r = 0; r < size_; ++r) {
    offsets[r] = static_cast<int>(total);
    total += static_cast<std::size_t>(counts[r]);
  }
  if (total > static_cast<std::size_t>(INT_MAX)) throw RunError("allgather: over 2 GiB in all");
  std::vector<std::byte> out(total);
  MPI_Allgatherv(mine.data(), n, MPI_BYTE, out.data(), counts.data(), offsets.data(), MPI_BYTE,
                 comm_);
  return out;
}

void Communicator::broadcast(void* data, int bytes, int root) const {
  MPI_Bcast(data, bytes, MPI_BYTE, root, comm_);
}

std::vector<unsigned char> Communicator::gather(const void* data, int bytes, int root) const {
  std::vector<unsigned char> out(rank_ == root ? static_cast<std::size_t>(bytes) * size_ : 0);
  MPI_Gather(data, bytes, MPI_BYTE, out.data(), bytes, MPI_BYTE, root, comm_);
  return out;
}

void Communicator::abort(int code) const {
  MPI_Abort(comm_, code);
  std::abort();
}

}  // namespace hpcplan::mpi
