// What a run prints about itself: the header (scene, mesh, ranks, physics, solver, set-up),
// the summary line at the end and the peak memory per rank.
#pragma once
#include <petscsnes.h>

#include "etfe/solver/load_stepper.h"
#include "etfe/assembly/problem.h"

namespace etfe {

// Peak resident memory of each rank so far (the kernel's high-water mark, set-up included), as
// max / min over the ranks in MB; with now, also what each rank holds at this moment.
PetscErrorCode PrintPeakMemory(MPI_Comm comm, const char *when, bool now = false);
// What the run computes and with what, after set-up (ends with the peak memory).
PetscErrorCode PrintHeader(Problem *P, SNES snes);
// "etfe: completed after N increments ...", then the peak memory over the run.
PetscErrorCode PrintRunSummary(MPI_Comm comm, const LoadStepperResult &res);

} // namespace etfe
