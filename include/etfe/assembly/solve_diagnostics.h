// What the last evaluations and solves on a Problem left behind for the ones that read them: the
// element that failed (assembly writes it, the line search, the load stepper and form finding
// name it), the size of the forces (the residual writes it, the convergence test scales by it),
// the tangent shift of the last tangent and the energy it would dissipate (the solver layer), and
// the work of the last converged increment (the load stepper writes it, scenes report it). None
// of it is part of the model or of the committed state: a restart recomputes what it needs.
#pragma once
#include <petscsys.h>

namespace etfe {

struct SolveDiagnostics {
  // The worst element status of the last residual, Jacobian or step check (KernelStatus, over
  // all ranks) and that element's scene (natural) id (-1 when all passed).
  PetscInt bad_element = -1;
  int bad_status = 0;
  // While the line search evaluates trial points it handles domain errors itself, so the
  // residual does not flag them to SNES (the flag would outlive the refused trial).
  PetscBool in_linesearch = PETSC_FALSE;
  // Size of the forces in play at the last residual (reactions and external loads) [N]: the
  // scale for the force-balance convergence test (-load_force_rtol).
  double force_scale = 0.0;

  // The shift as a pseudo-transient (proximal) term: the diagonal added to the last tangent
  // (N/mm, 0 without a shift), |F_0| of the solve the adaptive shift scales by, and, over the
  // Newton iterations of the last solve, the energy the term would dissipate,
  // sum_k shift_k |x_{k+1} - x_k|^2 over all DOFs (N mm).
  double shift_applied = 0.0;
  double shift_fnorm0 = 0.0;
  double shift_work = 0.0;

  // Of the last converged increment: the work done on the film by the prescribed boundary,
  // pressure, loads and contact (= its internal work, trapezoid rule) and the shift work (N mm).
  double increment_work = 0.0, increment_shift_work = 0.0;
};

} // namespace etfe
