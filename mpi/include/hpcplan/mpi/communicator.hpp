#pragma once
// The small set of MPI operations the distributed searches need, behind one type, so the
// search code never calls MPI itself (as Graph500's reference BFS keeps its communication
// layer apart from the algorithm).
#include <mpi.h>

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace hpcplan::mpi {

// True when this process was started by an MPI launcher (mpirun, mpiexec, srun): only then
// does hpcplan initialise MPI, so plain runs stay free of MPI start-up cost.
bool launched_by_mpi();

// MPI_Init / MPI_Finalize for the process's lifetime. Errors on MPI calls return codes
// (MPI_ERRORS_RETURN is not used: a failed call aborts the job, which is what a rank
// failure must do so that no other rank waits forever).
class Session {
 public:
  Session(int& argc, char**& argv);
  ~Session();
  Session(const Session&) = delete;
  Session& operator=(const Session&) = delete;
};

class Communicator {
 public:
  explicit Communicator(MPI_Comm comm = MPI_COMM_WORLD);

  int rank() const { return rank_; }
  int size() const { return size_; }
  MPI_Comm handle() const { return comm_; }
  // Ranks of this job on this node (they share its memory).
  int ranks_on_node() const { return ranks_on_node_; }
  // Ranks of this node whose CPU sets (core/cpu_set.hpp) overlap this one's, itself included:
  // 1 for ranks mpirun or SLURM bound to cores of their own, every rank of the node for
  // unbound ones. A rank's default thread count is its set's CPUs over this.
  int ranks_sharing_cpus() const { return ranks_sharing_cpus_; }

  // A barrier that sleeps between polls instead of spinning: for ranks waiting while another
  // rank works alone (a spinning rank steals the core, or its SMT sibling, from the worker).
  void quiet_barrier() const;
  double allreduce_min(double v) const;
  double allreduce_max(double v) const;
  std::uint64_t allreduce_sum(std::uint64_t v) const;
  // Element-wise sum / max / min of a small vector on every rank, in place.
  void allreduce_sum(std::span<std::uint64_t> values) const;
  void allreduce_max(std::span<std::uint64_t> values) const;
  void allreduce_min(std::span<double> values) const;
  // Every rank's bytes (any length each), concatenated in rank order, on every rank.
  std::vector<std::byte> allgather(std::span<const std::byte> mine) const;
  void broadcast(void* data, int bytes, int root) const;
  // Gathers `bytes` from every rank on `root` (result.size() == size*bytes there).
  std::vector<unsigned char> gather(const void* data, int bytes, int root) const;
  // Ends the whole job: for failures one rank cannot recover from alone.
  [[noreturn]] void abort(int code) const;

 private:
  MPI_Comm comm_;
  int rank_ = 0;
  int size_ = 1;
  int ranks_on_node_ = 1;
  int ranks_sharing_cpus_ = 1;
};

}  // namespace hpcplan::mpi
