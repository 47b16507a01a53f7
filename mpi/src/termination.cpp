#include "hpcplan/mpi/termination.hpp"

namespace hpcplan::mpi {

TerminationDetector::~TerminationDetector() {
  // A wave still pending here belongs to a search that ended by an error: it is left to the
  // job's abort rather than waited for (the other ranks may never join). It is not freed
  // either: MPI forbids MPI_Request_free on a non-blocking collective's request, and Open MPI
  // then aborted the job with its own error before the failing rank could say why
  // (tests/mpi/test_mpi_failures.sh, the rank that throws).
}

bool TerminationDetector::poll(bool passive, std::uint64_t sent, std::uint64_t received) {
  if (pending_) {
    int done = 0;
    MPI_Test(&request_, &done, MPI_STATUS_IGNORE);
    if (!done) return false;
    pending_ = false;
    ++waves_;
    const bool ended = have_previous_ && previous_received_ == out_[0];
    have_previous_ = true;
    previous_received_ = out_[1];
    if (ended) return true;
  }
  if (passive) {
    in_ = {sent, received};
    MPI_Iallreduce(in_.data(), out_.data(), 2, MPI_UINT64_T, MPI_SUM, comm_, &request_);
    pending_ = true;
  }
  return false;
}

}  // namespace hpcplan::mpi
