// -analysis plan: the drawing planner (src/analyses/plan.cpp) over stretch runs of the case the
// options describe.
#pragma once
#include <petscsys.h>

namespace etfe {

// The case is built once to check it and its options (and to print what it is), then the
// planner runs it as often as its search needs. help_only: read the options, run nothing.
PetscErrorCode RunPlan(MPI_Comm comm, PetscBool help_only);

} // namespace etfe
