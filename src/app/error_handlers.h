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
// main's exit after Run failed with ierr: the results file (if open and every rank failed) gets
// status "failed: <first message>", a run of several ranks is aborted (one rank's error would
// leave the others waiting), PETSc is finalized. Returns the exit code.
int ErrorExit(MPI_Comm agree, PetscErrorCode ierr);

} // namespace etfe
