// Signals that end a run from outside: a batch scheduler's time limit (Slurm sends SIGTERM, then
// SIGKILL after its grace period; many sites send SIGUSR1 or SIGTERM a set time before the
// limit), CPU-time limits (SIGXCPU) and Ctrl-C (SIGINT). While a load history runs they are
// caught: the handler only notes the signal, and the load stepper acts at its next safe point
// (load_stepper_interrupt.cpp): a checkpoint of the last converged state, the results marked
// "interrupted", exit status kExitInterrupted. A second signal ends the process at once (the
// signal's default action), leaving the files as a kill would.
#pragma once
#include <petscsys.h>

namespace etfe {

// The exit status of a run stopped by a signal at a safe point (sysexits.h's EX_TEMPFAIL: try
// again, i.e. restart from the checkpoint).
constexpr int kExitInterrupted = 75;

// Catches SIGTERM, SIGINT, SIGUSR1 and SIGXCPU (on) or gives them back to the handlers they had
// before (off). Forgets any signal noted before.
PetscErrorCode InterruptCatch(bool on);
// The run is over and its results closed: the caught signals are ignored until the process exits,
// so one arriving while PETSc and MPI shut down cannot turn a completed run into a killed one.
// PETSc's own handlers are popped first: PetscFinalize would otherwise put the default actions
// back before MPI_Finalize.
PetscErrorCode InterruptHoldUntilExit();
// The signal noted on this rank (0: none). Not collective: ranks agree on it at safe points.
int InterruptNoted();
// "SIGTERM", "SIGUSR1", ...
const char *InterruptSignalName(int signal);
// Collective (one MPI_Allreduce of an int when signals are caught on several ranks, nothing
// otherwise): whether a signal was noted on some rank more than grace seconds ago (as that rank
// first looked), so that the increment under way is to be given up.
PetscErrorCode InterruptGraceSpent(MPI_Comm comm, double grace, bool *spent);
// Whether InterruptGraceSpent has said so since the signals were caught (the same on every rank):
// the Newton solve that ended then was given up, not failed.
bool InterruptGaveUp();

} // namespace etfe
