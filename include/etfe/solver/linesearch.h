// The "etfe" SNES line search (-snes_linesearch_type etfe, the default): refuses Newton steps
// that collapse or flip an element, caps the largest nodal update, checks the true residual of
// the linear solve, and backtracks on the residual norm.
#pragma once
#include <petscsnes.h>

namespace etfe {

struct Problem;

#define SNESLINESEARCHETFE "etfe"

PetscErrorCode SNESLineSearchRegisterEtfe(void);
// Gives the line search the problem whose elements it checks (a no-op for other types).
PetscErrorCode SNESLineSearchEtfeSetProblem(SNESLineSearch ls, Problem *problem);

} // namespace etfe
