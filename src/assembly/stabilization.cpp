// Viscous stabilization of a load increment (the idea of Abaqus's *STATIC, STABILIZE): a force
// k (u - u_n) on every free DOF, u_n the state the increment started from, k = relative * E h0
// per node (the film's nodal stiffness scale, so the same relative value acts alike on any mesh
// density). It resists the motion of the increment, so a film with slack or compressed parts
// (no out-of-plane stiffness, a near-mechanism) gets a well-posed increment; the converged state
// carries the force k (u - u_n), whose size and work the load stepper reports. Proximal passes
// (StabilizationMoveAnchor) shrink it: at a fixed point the stabilized state solves the
// unstabilized equations.
#include "etfe/assembly.h"

namespace etfe {

PetscErrorCode StabilizationBegin(Problem *P, double relative, Vec anchor) {
  Stabilization &s = P->stabilization;
  PetscFunctionBeginUser;
  if (!s.anchor) {
    PetscCall(VecDuplicate(P->U, &s.anchor));
    PetscCall(VecDuplicate(P->U, &s.diagonal));
    PetscCall(VecDuplicate(P->U, &s.work));
  }
  s.stiffness = relative * P->AxialStiffness();
  PetscCall(VecSet(s.diagonal, s.stiffness));
  // Constrained rows keep their unit diagonal and prescribed-value residual.
  PetscScalar *d;
  PetscCall(VecGetArray(s.diagonal, &d));
  for (PetscInt dof : P->con_owned_dof) d[dof] = 0.0;
  PetscCall(VecRestoreArray(s.diagonal, &d));
  PetscCall(VecCopy(anchor, s.anchor));
  PetscFunctionReturn(0);
}

PetscErrorCode StabilizationMoveAnchor(Problem *P, Vec U) {
  PetscFunctionBeginUser;
  PetscCall(VecCopy(U, P->stabilization.anchor));
  PetscFunctionReturn(0);
}

void StabilizationEnd(Problem *P) { P->stabilization.stiffness = 0.0; }

namespace {
// s.work = k (U - anchor) on the free DOFs: the stabilizing force.
PetscErrorCode StabilizingForce(Problem *P, Vec U) {
  Stabilization &s = P->stabilization;
  PetscFunctionBeginUser;
  PetscCall(VecWAXPY(s.work, -1.0, s.anchor, U));
  PetscCall(VecPointwiseMult(s.work, s.work, s.diagonal));
  PetscFunctionReturn(0);
}
} // namespace

PetscErrorCode AddStabilizationForce(Problem *P, Vec U, Vec F) {
  PetscFunctionBeginUser;
  PetscCall(StabilizingForce(P, U));
  PetscCall(VecAXPY(F, 1.0, P->stabilization.work));
  PetscFunctionReturn(0);
}

PetscErrorCode StabilizationForceNorm(Problem *P, Vec U, PetscReal *norm) {
  PetscFunctionBeginUser;
  PetscCall(StabilizingForce(P, U));
  PetscCall(VecNorm(P->stabilization.work, NORM_2, norm));
  PetscFunctionReturn(0);
}

PetscErrorCode AddStabilizationTangent(Problem *P, Mat J) {
  PetscFunctionBeginUser;
  PetscCall(MatDiagonalSet(J, P->stabilization.diagonal, ADD_VALUES));
  PetscFunctionReturn(0);
}

PetscErrorCode StabilizationMeasure(Problem *P, Vec U, double *work, double *force_max) {
  Stabilization &s = P->stabilization;
  PetscReal size;
  PetscFunctionBeginUser;
  PetscCall(StabilizingForce(P, U));
  PetscCall(VecMaxNodalNorm(s.work, force_max));
  // f = k (U - anchor) with one k on every free DOF: f . (U - anchor) = |f|^2 / k.
  PetscCall(VecNorm(s.work, NORM_2, &size));
  *work = size * size / s.stiffness;
  PetscFunctionReturn(0);
}

PetscErrorCode StabilizationDestroy(Problem *P) {
  Stabilization &s = P->stabilization;
  PetscFunctionBeginUser;
  PetscCall(VecDestroy(&s.anchor));
  PetscCall(VecDestroy(&s.diagonal));
  PetscCall(VecDestroy(&s.work));
  s.stiffness = 0.0;
  PetscFunctionReturn(0);
}

} // namespace etfe
