// The load stepper's convergence test (see LoadStepperSetConvergenceTest in load_stepper.h):
// SNES's own test, plus force balance against the size of the forces in play, with the
// round-off floors of the physics terms' forces (contact's penalties: PhysicsTerm::ForceFloor)
// and of the membrane forces as the tolerance's lower bounds where they are set.
#include <algorithm>
#include <cmath>

#include "etfe/assembly/assembly.h"
#include "etfe/solver/interrupt.h"
#include "etfe/solver/load_stepper.h"
#include "etfe/solver/tangent_shift.h"

namespace etfe {

namespace {

struct ForceTest {
  Problem *problem;
  PetscReal rtol;
  PetscReal roundoff;        // factor of the membrane round-off floor (0: off)
  PetscReal floor = -1.0;    // N, computed at the first test
  PetscReal signal_grace;    // s (-etfe_signal_grace)
};

// eps |x|max E h0 sqrt(n): a force from element edges x_a - x_b of coordinates of size |x|
// carries a strain round-off eps |x| / l_e, i.e. eps |x| E h0 per element (l_e cancels), summed
// in 2-norm over n elements. Measured floors of |R| (DD1511 increment 1): 1.1e-8 N at 10^5,
// 3.5e-8 at 10^6 triangles; this estimate gives 1.4e-8 and 4.4e-8.
PetscErrorCode MembraneRoundoffFloor(Problem *P, PetscReal *floor) {
  PetscReal xmax = 0.0;
  PetscFunctionBeginUser;
  for (double x : P->mesh.X) xmax = std::max(xmax, (PetscReal)std::fabs(x));
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &xmax, 1, MPIU_REAL, MPIU_MAX, P->comm));
  *floor = PETSC_MACHINE_EPSILON * xmax * P->AxialStiffness() * std::sqrt((double)P->mesh.num_elements_global);
  PetscFunctionReturn(0);
}

PetscErrorCode ConvergedForceBalance(SNES snes, PetscInt it, PetscReal xnorm, PetscReal ynorm,
                                     PetscReal fnorm, SNESConvergedReason *reason, void *ctx) {
  auto *t = (ForceTest *)ctx;
  bool interrupted;
  PetscFunctionBeginUser;
  // A signal's grace has run out: the increment is given up (the load stepper stops at the last
  // converged one).
  PetscCall(InterruptGraceSpent(t->problem->comm, t->signal_grace, &interrupted));
  if (interrupted) {
    *reason = SNES_DIVERGED_FUNCTION_COUNT;  // InterruptGaveUp() tells it from a real one
    PetscFunctionReturn(0);
  }
  PetscCall(SNESConvergedDefault(snes, it, xnorm, ynorm, fnorm, reason, nullptr));
  // SNES's relative tests only propose convergence: a residual small against the first one (which
  // a wild start, a huge initial bulge, makes huge) or a small step is no equilibrium while the
  // forces do not balance, so both go through the force balance below. Its failures stay, and so
  // does its absolute test (|R| below -snes_atol N is balance by any measure).
  if (*reason < 0 || *reason == SNES_CONVERGED_FNORM_ABS || it == 0) PetscFunctionReturn(0);
  const bool step_small = *reason == SNES_CONVERGED_SNORM_RELATIVE;
  Problem *P = t->problem;
  PetscReal tol = t->rtol * P->diagnostics.force_scale;
  if (!P->terms.empty()) {  // round-off floors of the terms' forces (a penalty's)
    Vec X;
    double floor = 0.0;
    PetscCall(SNESGetSolution(snes, &X));
    for (auto &term : P->terms) PetscCall(term->ForceFloor(*P, X, fnorm, tol, &floor));
    tol = std::max(tol, floor);
  }
  if (t->roundoff > 0) {
    if (t->floor < 0) PetscCall(MembraneRoundoffFloor(P, &t->floor));
    tol = std::max(tol, t->roundoff * t->floor);
  }
  if (fnorm <= tol) *reason = SNES_CONVERGED_FNORM_ABS;
  // A step small against |x| is no equilibrium while the forces do not balance: a film thrown
  // far away (|x| huge) makes every step relatively small, and SNES's test would accept it.
  else if (step_small) *reason = SNES_DIVERGED_LINE_SEARCH;
  // SNES's relative residual test passed above the force tolerance: Newton goes on, to the force
  // balance or to its iteration limit (a cut-back).
  else *reason = SNES_CONVERGED_ITERATING;
  PetscFunctionReturn(0);
}

PetscErrorCode DestroyForceTest(void *ctx) {
  delete (ForceTest *)ctx;
  return 0;
}

} // namespace

PetscErrorCode LoadStepperSetConvergenceTest(Problem *P, SNES snes, const LoadStepperOptions &o) {
  PetscFunctionBeginUser;
  PetscCall(SNESSetConvergenceTest(snes, ConvergedForceBalance, new ForceTest{P, o.force_rtol, o.force_roundoff, -1.0, o.signal_grace},
                                   DestroyForceTest));
  PetscCall(TangentShiftWorkMonitorSet(P, snes));
  PetscFunctionReturn(0);
}

} // namespace etfe
