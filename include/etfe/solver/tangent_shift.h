// The tangent shift (solver layer, -membrane_tangent_shift[_adaptive]): Newton solves with the
// assembled tangent plus a diagonal shift, which lets it take its first steps where a stress-free
// film has no out-of-plane stiffness. Only the tangent is shifted, not the residual, so the
// converged answer is unchanged. Read as a pseudo-transient (proximal-point) term, the step from
// x_k solves (K + s_k I) dx = -R, the step of a system with a viscous force s_k (x - x_k) that is
// gone at convergence; the energy that force would dissipate is reported next to the work.
#pragma once
#include <petscsnes.h>

#include "etfe/assembly/problem.h"

namespace etfe {

// The shift [N/mm] of the tangent of the current Newton iteration of snes: the problem's
// TangentShiftAbsolute(), with -membrane_tangent_shift_adaptive scaled by min(1, |F_k|/|F_0|) of
// the solve (F_0 recorded at its iteration 0), so that it vanishes as Newton converges. Without
// snes (a tangent outside a solve) the full shift.
PetscErrorCode TangentShiftForIteration(Problem *problem, SNES snes, double *shift);
// The shift [N/mm] of a converged state's tangent: 0 with -membrane_tangent_shift_adaptive (it has
// vanished), else TangentShiftAbsolute(). What a tangent taken between solves (the predictor's)
// uses, so that it does not depend on the last solve (a restart has had none).
double TangentShiftConverged(const Problem *problem);
// The SNES Jacobian callback (context: the Problem): FormJacobian's assembled tangent plus the
// shift of this iteration on its diagonal, remembered in problem->diagnostics.shift_applied.
PetscErrorCode FormShiftedJacobian(SNES snes, Vec U, Mat J, Mat Pmat, void *ctx);
// Adds the monitor that sums, over each solve's Newton iterations, the energy the shift would
// dissipate: problem->diagnostics.shift_work = sum_k s_k |x_{k+1} - x_k|^2 (N mm, all DOFs).
PetscErrorCode TangentShiftWorkMonitorSet(Problem *problem, SNES snes);

} // namespace etfe
