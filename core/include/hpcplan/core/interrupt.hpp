#pragma once
// Requests from outside to end a long run early: SIGUSR1 (the warning SLURM sends before a
// job's time limit with `#SBATCH --signal=B:USR1@SECONDS`, or `scancel --signal=USR1`),
// SIGTERM (SLURM at the limit, preemption, `kill`), SIGINT (Ctrl-C). The handler only records
// the signal; a long loop asks at its safe boundaries (the fluid's frame ends, the
// simulator's frames) and ends there, after saving what a restart needs (its checkpoint), so
// that a requeued job continues where this one stopped. Nothing is half-written: files are
// written whole between boundaries.
//
// Threads: install() from the main thread before the run; requested() from any thread.
namespace hpcplan::interrupt {

// Installs the handlers (once; later calls do nothing). Until then the signals keep their
// default actions. The SIGTERM and SIGINT handlers restore their signal's default action once
// they have run, so a second Ctrl-C (or SIGTERM) ends a run that is slow to reach its next
// boundary at once; a second SIGUSR1 only repeats the request (SLURM's warning may arrive both
// directly and forwarded by mpirun or the batch shell).
void install();

// The signal that asked the run to end (SIGUSR1, SIGTERM or SIGINT), 0 while none has.
int requested();

// "SIGUSR1", "SIGTERM", "SIGINT", or "a signal".
const char* name(int signal);

}  // namespace hpcplan::interrupt
