// Errors as a user meets them. A message says what is wrong and the way out, in one line or a
// few, without PETSc's option table and configure line and without where in the source it was
// raised: -etfe_traceback gives PETSc's full report instead. Every error's first message is kept
// for the results file's status, and an error exit marks an open results file failed.
#pragma once
#include <petscsys.h>

#include <vector>

#include "options_files.h"

namespace etfe {

// Pushes the run's error handler (once, right after PetscInitialize). requirements: the
// "# requires:" comments of the options files read; a message that names a missing required
// file also names the options file that makes it.
PetscErrorCode ErrorHandlersPush(const std::vector<OptionsFileRequirement> &requirements);
// -etfe_traceback (read with the program's options): PETSc's full report from now on.
void ErrorHandlersUseTraceback(bool traceback);
// Whether every rank is on its error path (they meet on agree, a communicator of their own).
bool AllRanksFailed(MPI_Comm agree);
// The process's exit status after an error (docs/scheduler.md, "Exit status"). A batch script
// acts on it, so an error never exits with a status that means something else: 0 (complete),
// 75 (interrupted or stopped: resubmit; interrupt.h) and 10 (-results_status: running) are never
// an error's. PETSc's error code is not an exit status: PETSC_ERR_ARG_INCOMP is 75.
enum ExitStatus {
  kExitRunFailed = 1,  // the run did not complete: not converged, not in equilibrium, a solver failed
  kExitInputRefused = 2,  // bad option, mesh, options file, checkpoint or results file
  kExitSystem = 3,  // out of memory, disk full, a write or a system call failed
  kExitInternal = 4,  // an error in the code (or one PETSc does not class)
};
// The exit status of an error with PETSc's code ierr; sys_errno (the errno the error left) makes a
// full disk or an I/O error a system error whatever the code.
int ExitStatusOf(PetscErrorCode ierr, int sys_errno);
// main's exit after Run failed with ierr: the results file (if open and every rank failed) gets
// status "failed: <first message>", a run of several ranks is aborted (one rank's error would
// leave the others waiting), the HDF5 library is closed (files an error left open would
// otherwise be closed inside MPI_Finalize, after MPI-IO is gone), PETSc is finalized. Returns the
// exit status (ExitStatusOf), also given to MPI_Abort.
int ErrorExit(MPI_Comm agree, PetscErrorCode ierr);

} // namespace etfe
