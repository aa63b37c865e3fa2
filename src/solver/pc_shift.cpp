// The regularized preconditioning matrix P = J + k M (pc_shift.h).
#include "etfe/solver/pc_shift.h"

#include <algorithm>

#include "etfe/assembly/assembly.h"
#include "etfe/base/log_events.h"
#include "etfe/base/owned_context.h"
#include "etfe/solver/tangent_shift.h"

namespace etfe {

namespace {

struct PcShift {
  ~PcShift() {
    VecDestroy(&mass);
    VecDestroy(&work);
  }
  Problem *problem = nullptr;
  Vec mass = nullptr;  // lumped reference area per DOF [mm^2], 0 at constrained DOFs
  Vec work = nullptr;
  double k = 0.0;      // foundation stiffness [N/mm^3]
  PetscBool adaptive = PETSC_TRUE;
  PetscReal fnorm0 = 0.0;
  PetscObjectState nz_state = -1;  // J's nonzero state when P last took J's pattern
};

// The lumped area matrix's diagonal: a third of each element's reference area to each of its
// nodes' 3 DOFs (summed over the ranks through the ghosts), and the film's total area.
PetscErrorCode LumpedArea(Problem *P, Vec mass, double *total) {
  const LocalMesh &m = P->mesh;
  Vec ml;
  PetscScalar *a;
  PetscFunctionBeginUser;
  *total = 0.0;
  PetscCall(VecZeroEntries(mass));
  PetscCall(VecGhostGetLocalForm(mass, &ml));
  PetscCall(VecGetArray(ml, &a));
  for (PetscInt e = 0; e < m.num_elements; ++e) {
    *total += m.ref[e].area;
    for (int n = 0; n < 3; ++n)
      for (int i = 0; i < 3; ++i) a[3 * m.tri[3 * e + n] + i] += m.ref[e].area / 3.0;
  }
  PetscCall(VecRestoreArray(ml, &a));
  PetscCall(VecGhostRestoreLocalForm(mass, &ml));
  PetscCall(VecGhostUpdateBegin(mass, ADD_VALUES, SCATTER_REVERSE));
  PetscCall(VecGhostUpdateEnd(mass, ADD_VALUES, SCATTER_REVERSE));
  PetscCall(VecGetArray(mass, &a));
  for (PetscInt d : P->con_owned_dof) a[d] = 0.0;  // their rows are the identity
  PetscCall(VecRestoreArray(mass, &a));
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, total, 1, MPI_DOUBLE, MPI_SUM, P->comm));
  PetscFunctionReturn(0);
}

// P takes J's values (and its pattern and near-null space when J's pattern is new to it).
PetscErrorCode CopyTangent(PcShift *c, Mat J, Mat Pmat) {
  PetscObjectState nz;
  PetscFunctionBeginUser;
  PetscCall(MatGetNonzeroState(J, &nz));
  if (nz == c->nz_state) {
    PetscCall(MatCopy(J, Pmat, SAME_NONZERO_PATTERN));
    PetscFunctionReturn(0);
  }
  Mat D;
  MatNullSpace nns;
  PetscCall(MatDuplicate(J, MAT_COPY_VALUES, &D));
  PetscCall(MatHeaderReplace(Pmat, &D));  // the SNES keeps its Pmat object
  PetscCall(MatGetNearNullSpace(J, &nns));
  if (nns) PetscCall(MatSetNearNullSpace(Pmat, nns));
  c->nz_state = nz;
  PetscFunctionReturn(0);
}

PetscErrorCode FormPcShiftedJacobian(SNES snes, Vec U, Mat J, Mat Pmat, void *ctx) {
  auto *c = (PcShift *)ctx;
  double f = 1.0;
  PetscFunctionBeginUser;
  PetscCall(FormShiftedJacobian(snes, U, J, J, c->problem));
  PetscCall(PetscLogEventBegin(LogEvents().pmat, 0, 0, 0, 0));
  PetscCall(CopyTangent(c, J, Pmat));
  if (c->adaptive && snes) {
    PetscInt it;
    PetscReal fnorm;
    PetscCall(SNESGetIterationNumber(snes, &it));
    PetscCall(SNESGetFunctionNorm(snes, &fnorm));
    if (it == 0) c->fnorm0 = fnorm;
    if (c->fnorm0 > 0) f = std::min(1.0, (double)(fnorm / c->fnorm0));
  }
  PetscCall(VecAXPBY(c->work, c->k * f, 0.0, c->mass));
  PetscCall(MatDiagonalSet(Pmat, c->work, ADD_VALUES));
  PetscCall(PetscLogEventEnd(LogEvents().pmat, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

} // namespace

PetscErrorCode PcShiftSetUp(Problem *P, SNES snes) {
  PetscReal s = 0.0;
  PetscBool adaptive = PETSC_TRUE;
  PetscFunctionBeginUser;
  PetscOptionsBegin(P->comm, nullptr, "Regularized preconditioning matrix (Krylov paths)", "PC");
  PetscCall(PetscOptionsReal("-etfe_pc_shift",
                             "Build the preconditioner from J + k M (M: lumped area matrix, k = s E h / film area); "
                             "the Krylov solve keeps J, so Newton's answer does not move. 0: from J",
                             "", s, &s, nullptr));
  PetscCall(PetscOptionsBool("-etfe_pc_shift_adaptive",
                             "Scale k by min(1, |F_k|/|F_0|) of the Newton solve (it fades as the solve converges)", "",
                             adaptive, &adaptive, nullptr));
  PetscOptionsEnd();
  PetscCheck(s >= 0, P->comm, PETSC_ERR_ARG_OUTOFRANGE,
             "-etfe_pc_shift %g: the foundation is relative to E h and must be >= 0", (double)s);
  if (s == 0) PetscFunctionReturn(0);
  PetscCheck(!ProblemSolverNeeds(*P).krylov_outer, P->comm, PETSC_ERR_SUP,
             "-etfe_pc_shift does not combine with sealed gas chambers (their rank-one tangent is Newton's matrix "
             "already): drop the option");
  auto *c = new PcShift;
  Mat Pmat;
  double area;
  c->problem = P;
  c->adaptive = adaptive;
  PetscCall(ComposeOwnedContext((PetscObject)snes, "etfe_pc_shift", c));
  PetscCall(VecDuplicate(P->U, &c->mass));
  PetscCall(VecDuplicate(P->U, &c->work));
  PetscCall(LumpedArea(P, c->mass, &area));
  c->k = s * P->AxialStiffness() / area;
  {
    // A placeholder of J's sizes and type (an unassembled BAIJ matrix cannot be duplicated): the
    // first Jacobian evaluation puts a copy of J in its place (CopyTangent).
    PetscInt m, n, M, N;
    MatType type;
    PetscCall(MatGetLocalSize(P->J, &m, &n));
    PetscCall(MatGetSize(P->J, &M, &N));
    PetscCall(MatGetType(P->J, &type));
    PetscCall(MatCreate(P->comm, &Pmat));
    PetscCall(MatSetSizes(Pmat, m, n, M, N));
    PetscCall(MatSetBlockSize(Pmat, 3));
    PetscCall(MatSetType(Pmat, type));
  }
  PetscCall(SNESSetJacobian(snes, P->J, Pmat, FormPcShiftedJacobian, c));
  PetscCall(MatDestroy(&Pmat));
  PetscFunctionReturn(0);
}

} // namespace etfe
