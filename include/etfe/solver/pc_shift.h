// A regularized preconditioning matrix for Krylov paths (-etfe_pc_shift s): the Krylov solve keeps
// Newton's tangent J (with the tangent shift FormShiftedJacobian applies), so the converged answer
// and the line search's |J y - F| test do not move, while the preconditioner (AMG, ILU, a lagged
// factorization) is built from P = J + k M: M the lumped area matrix of the film (a mass-like
// foundation, zero at constrained DOFs) and k = s E h / A, A the film's reference area, so that
// the foundation over the whole film is s times its axial stiffness whatever the mesh. A slack
// film's tangent has almost no out-of-plane stiffness at the coarse scales AMG builds; the
// foundation gives them some. With -etfe_pc_shift_adaptive (default) k is scaled by
// min(1, |F_k|/|F_0|) of the Newton solve: it fades as the solve converges.
#pragma once
#include <petscsnes.h>

#include "etfe/assembly/problem.h"

namespace etfe {

// When -etfe_pc_shift > 0: gives snes a separate preconditioning matrix and the Jacobian callback
// that fills it (J's near-null space goes with it). Without the option nothing changes.
PetscErrorCode PcShiftSetUp(Problem *problem, SNES snes);

} // namespace etfe
