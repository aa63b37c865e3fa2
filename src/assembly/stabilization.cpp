// Viscous stabilization of a load increment (the idea of Abaqus's *STATIC, STABILIZE): a force
// k (u - u_n) on every free DOF, u_n the state the increment started from, k = relative * E h0
// per node (the film's nodal stiffness scale, so the same relative value acts alike on any mesh
// density). It resists the motion of the increment, so a film with slack or compressed parts
// (no out-of-plane stiffness, a near-mechanism) gets a well-posed increment; the converged state
// carries the force k (u - u_n), whose size and work the load stepper reports. Proximal passes
// (StabilizationMoveAnchor) shrink it: at a fixed point the stabilized state solves the
// unstabilized equations.
#include <algorithm>
#include <cmath>
#include <vector>

#include "etfe/assembly/assembly.h"

namespace etfe {

namespace {

// Active while stiffness > 0; the vectors exist once a run has used it.
struct Stabilization : PhysicsTerm {
  double stiffness = 0.0;   // N/mm per free DOF
  Vec anchor = nullptr;     // the state the force pulls towards (the increment's start)
  Vec diagonal = nullptr;   // stiffness on free DOFs, 0 on constrained ones
  Vec work = nullptr;

  const char *Name() const override { return "stabilization"; }
  PetscErrorCode AddGlobalForces(Problem &P, Vec U, Vec F) override;
  PetscErrorCode AddAssembledTangent(Problem &, Mat A) override {
    PetscFunctionBeginUser;
    if (stiffness > 0) PetscCall(MatDiagonalSet(A, diagonal, ADD_VALUES));
    PetscFunctionReturn(0);
  }
  PetscErrorCode Destroy(Problem &) override {
    PetscFunctionBeginUser;
    PetscCall(VecDestroy(&anchor));
    PetscCall(VecDestroy(&diagonal));
    PetscCall(VecDestroy(&work));
    stiffness = 0.0;
    PetscFunctionReturn(0);
  }
};

Stabilization &Of(Problem *P) { return *FindTerm<Stabilization>(*P); }

} // namespace

PetscErrorCode AddStabilizationTerm(Problem *P) {
  PetscFunctionBeginUser;
  P->terms.push_back(std::make_unique<Stabilization>());
  PetscFunctionReturn(0);
}

PetscErrorCode StabilizationBegin(Problem *P, double relative, Vec anchor) {
  Stabilization &s = Of(P);
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
  PetscCall(VecCopy(U, Of(P).anchor));
  PetscFunctionReturn(0);
}

void StabilizationEnd(Problem *P) { Of(P).stiffness = 0.0; }

namespace {
// s.work = k (U - anchor) on the free DOFs: the stabilizing force.
PetscErrorCode FormStabilizingForce(Problem *P, Vec U) {
  Stabilization &s = Of(P);
  PetscFunctionBeginUser;
  PetscCall(VecWAXPY(s.work, -1.0, s.anchor, U));
  PetscCall(VecPointwiseMult(s.work, s.work, s.diagonal));
  PetscFunctionReturn(0);
}
} // namespace

PetscErrorCode Stabilization::AddGlobalForces(Problem &P, Vec U, Vec F) {
  PetscFunctionBeginUser;
  if (stiffness <= 0) PetscFunctionReturn(0);
  PetscCall(FormStabilizingForce(&P, U));
  PetscCall(VecAXPY(F, 1.0, work));
  PetscFunctionReturn(0);
}

PetscErrorCode StabilizationForceNorm(Problem *P, Vec U, PetscReal *norm) {
  PetscFunctionBeginUser;
  PetscCall(FormStabilizingForce(P, U));
  PetscCall(VecNorm(Of(P).work, NORM_2, norm));
  PetscFunctionReturn(0);
}

PetscErrorCode StabilizationMeasure(Problem *P, Vec U, Vec Fint, StabilizingForce *force) {
  Stabilization &s = Of(P);
  const LocalMesh &m = P->mesh;
  const PetscScalar *f, *g, *u;
  PetscReal size;
  struct {
    double value;
    int rank;
  } mine{-1.0, (int)P->rank}, largest;
  PetscInt node = -1;
  // Sums over the owned nodes: positions and count (the centroid c), then f, (x - c) x f, |g| and
  // |x - c| |g| with g = Fint + f the forces the film takes from outside.
  double centre[4] = {0, 0, 0, (double)m.num_owned}, sums[8] = {0, 0, 0, 0, 0, 0, 0, 0};
  PetscFunctionBeginUser;
  PetscCall(FormStabilizingForce(P, U));
  PetscCall(VecGetArrayRead(U, &u));
  std::vector<double> x(3 * m.num_owned);
  for (PetscInt i = 0; i < 3 * m.num_owned; ++i) x[i] = m.X[i] + PetscRealPart(u[i]);
  PetscCall(VecRestoreArrayRead(U, &u));
  for (PetscInt l = 0; l < m.num_owned; ++l)
    for (int i = 0; i < 3; ++i) centre[i] += x[3 * l + i];
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, centre, 4, MPI_DOUBLE, MPI_SUM, P->comm));
  for (int i = 0; i < 3; ++i) centre[i] /= std::max(centre[3], 1.0);
  PetscCall(VecGetArrayRead(s.work, &f));
  PetscCall(VecGetArrayRead(Fint, &g));
  for (PetscInt l = 0; l < m.num_owned; ++l) {
    const PetscScalar *fn = &f[3 * l], *in = &g[3 * l];
    const double r[3] = {x[3 * l] - centre[0], x[3 * l + 1] - centre[1], x[3 * l + 2] - centre[2]};
    const double gn[3] = {in[0] + fn[0], in[1] + fn[1], in[2] + fn[2]};
    const double size_n = std::sqrt(fn[0] * fn[0] + fn[1] * fn[1] + fn[2] * fn[2]);
    const double g_n = std::sqrt(gn[0] * gn[0] + gn[1] * gn[1] + gn[2] * gn[2]);
    for (int i = 0; i < 3; ++i) sums[i] += fn[i];
    sums[3] += r[1] * fn[2] - r[2] * fn[1];
    sums[4] += r[2] * fn[0] - r[0] * fn[2];
    sums[5] += r[0] * fn[1] - r[1] * fn[0];
    sums[6] += g_n;
    sums[7] += std::sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2]) * g_n;
    if (size_n > mine.value) mine.value = size_n, node = m.natural_id[l];
  }
  PetscCall(VecRestoreArrayRead(Fint, &g));
  PetscCall(VecRestoreArrayRead(s.work, &f));
  PetscCallMPI(MPI_Allreduce(&mine, &largest, 1, MPI_DOUBLE_INT, MPI_MAXLOC, P->comm));
  PetscCallMPI(MPI_Bcast(&node, 1, MPIU_INT, largest.rank, P->comm));
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, sums, 8, MPI_DOUBLE, MPI_SUM, P->comm));
  for (int i = 0; i < 3; ++i) force->resultant[i] = sums[i], force->moment[i] = sums[3 + i];
  force->applied = sums[6];
  force->applied_moment = sums[7];
  force->largest = std::max(largest.value, 0.0);
  force->node = node;
  PetscCall(ProblemGetNodePosition(P, U, node, force->position));
  // f = k (U - anchor) with one k on every free DOF: f . (U - anchor) = |f|^2 / k.
  PetscCall(VecNorm(s.work, NORM_2, &size));
  force->norm = size;
  force->work = size * size / s.stiffness;
  PetscFunctionReturn(0);
}

} // namespace etfe
