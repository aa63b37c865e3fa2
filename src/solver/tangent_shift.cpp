// The tangent shift's policy, the Jacobian callback that applies it and the work it would
// dissipate (see tangent_shift.h).
#include "etfe/solver/tangent_shift.h"

#include <algorithm>

#include "etfe/assembly/assembly.h"

namespace etfe {

PetscErrorCode TangentShiftForIteration(Problem *P, SNES snes, double *shift) {
  PetscFunctionBeginUser;
  *shift = P->TangentShiftAbsolute();
  if (snes && P->tangent_shift_adaptive) {
    PetscInt it;
    PetscReal fnorm;
    PetscCall(SNESGetIterationNumber(snes, &it));
    PetscCall(SNESGetFunctionNorm(snes, &fnorm));
    if (it == 0) P->diagnostics.shift_fnorm0 = fnorm;
    if (P->diagnostics.shift_fnorm0 > 0) *shift *= std::min(1.0, (double)(fnorm / P->diagnostics.shift_fnorm0));
  }
  PetscFunctionReturn(0);
}

double TangentShiftConverged(const Problem *P) {
  return P->tangent_shift_adaptive ? 0.0 : P->TangentShiftAbsolute();
}

PetscErrorCode FormShiftedJacobian(SNES snes, Vec U, Mat J, Mat Pmat, void *ctx) {
  Problem *P = (Problem *)ctx;
  PetscFunctionBeginUser;
  PetscCall(FormJacobian(snes, U, J, Pmat, ctx));
  if (P->TangentShiftAbsolute() > 0) {
    double shift;
    PetscCall(TangentShiftForIteration(P, snes, &shift));
    PetscCall(MatShift(Pmat, shift));
    P->diagnostics.shift_applied = shift;
  }
  PetscFunctionReturn(0);
}

namespace {

// s_k is the diagonal of the tangent the step was solved with and x_{k+1} the iterate the line
// search accepted (all DOFs; the constrained ones do not move in a solve). The tangent
// predictor's extra shift is not in it: the predictor only chooses where Newton starts.
struct ShiftWorkMonitor {
  Problem *problem;
  Vec x_prev = nullptr;
};

PetscErrorCode ShiftWorkMonitorCall(SNES snes, PetscInt it, PetscReal, void *ctx) {
  auto *m = (ShiftWorkMonitor *)ctx;
  SolveDiagnostics &d = m->problem->diagnostics;
  Vec X;
  PetscFunctionBeginUser;
  PetscCall(SNESGetSolution(snes, &X));
  if (!m->x_prev) PetscCall(VecDuplicate(X, &m->x_prev));
  if (it == 0) {
    d.shift_work = 0.0;
  } else if (d.shift_applied > 0) {
    PetscReal dx;
    PetscCall(VecAXPY(m->x_prev, -1.0, X));
    PetscCall(VecNorm(m->x_prev, NORM_2, &dx));
    d.shift_work += d.shift_applied * dx * dx;
  }
  PetscCall(VecCopy(X, m->x_prev));
  PetscFunctionReturn(0);
}

PetscErrorCode DestroyShiftWorkMonitor(void **ctx) {
  auto *m = (ShiftWorkMonitor *)*ctx;
  PetscFunctionBeginUser;
  PetscCall(VecDestroy(&m->x_prev));
  delete m;
  *ctx = nullptr;
  PetscFunctionReturn(0);
}

} // namespace

PetscErrorCode TangentShiftWorkMonitorSet(Problem *P, SNES snes) {
  PetscFunctionBeginUser;
  PetscCall(SNESMonitorSet(snes, ShiftWorkMonitorCall, new ShiftWorkMonitor{P}, DestroyShiftWorkMonitor));
  PetscFunctionReturn(0);
}

} // namespace etfe
