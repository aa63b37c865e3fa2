// A preconditioner kept while it works (-etfe_pc_refresh_its n): a factorization (MUMPS, with
// block low-rank compression or not) or an AMG hierarchy is built once and reused by the Krylov
// solves of later Newton iterations and increments, and rebuilt at the next Newton iteration once
// a solve needed more than n iterations or failed (Code_Aster's lagged preconditioner). A solve
// that ran out of iterations does not fail the Newton iteration: its direction goes to the etfe
// line search, which refuses it when |J y - F|/|F| > 1e-2, and the next iteration has a fresh
// preconditioner.
#pragma once
#include <petscsnes.h>

#include "etfe/assembly/problem.h"

namespace etfe {

// When -etfe_pc_refresh_its > 0: sets snes's preconditioner lag to "never", and a post-solve
// hook on its KSP that asks for one rebuild when a solve struggled. Without the option nothing
// changes.
PetscErrorCode PcRefreshSetUp(Problem *problem, SNES snes);

// Whether snes's last solve failed because its Krylov method ran out of iterations or diverged
// (not a direct solver's failure, not a nonlinear one): such an increment is cut back rather than
// solved again stabilized, whose answer differs from Newton's by the stabilization's tolerance.
PetscErrorCode KrylovSolveFailed(SNES snes, PetscBool *failed);

} // namespace etfe
