// Which options a run did not use, and what that means. This project's own options (its
// prefixes: -scene, -mesh_, -material_, -contact_, ...) are checked against the names its sources
// define (generated at build time): an unknown one is a typo and stops the run before it computes,
// with the closest known name; a known one the chosen configuration does not read (e.g.
// -material_yield with -material_type elastic) gets a one-line warning. An option whose first word
// (before the first '_') neither this program nor PETSc uses (-cable_edge_1_EA) is a typo too,
// stopped before the run with the closest known name. PETSc's own options (-snes_*, -ksp_*,
// -log_view, -options_view, ...) are PETSc's business: ones never read by the end of the run get
// a warning then.
#pragma once
#include <petscsys.h>

namespace etfe {

// -options_allow_unused as the program's options read it (once): unknown names are accepted.
void CheckUnusedOptionsAllow(PetscBool allow);
// before_run: the check before computing (errors for typos); otherwise the end-of-run warning.
PetscErrorCode CheckUnusedOptions(MPI_Comm comm, PetscBool before_run);

} // namespace etfe
