// Residual and Jacobian of the membrane and the physics terms (physics_term.h) as SNES callbacks.
//
// R(u) = f_int(u) - f_ext(u) on free DOFs; R = u - u_prescribed(t) on constrained DOFs. The
// Jacobian drops the rows and columns of constrained DOFs element by element and puts 1 on their
// diagonal, so a symmetric operator stays symmetric; this is exact because every Newton iterate
// already carries the prescribed values (ProblemSetLoadTime before each increment).
// Values go through ghosted vectors: element contributions to ghost nodes are added to their
// owners by the reverse scatter; matrix entries of ghost rows travel in PETSc's stash.
#include <algorithm>
#include <cmath>

#include "etfe/assembly/assembly.h"
#include "etfe/kernels/pressure.h"
#include "etfe/kernels/status.h"
#include "etfe/kernels/stress_measures.h"
#include "etfe/kernels/wrinkling.h"
#include "etfe/base/log_events.h"

namespace etfe {

namespace {

inline void GatherCoordinates(const LocalMesh &m, PetscInt e, const PetscScalar *u, double x[9]) {
  for (int a = 0; a < 3; ++a) {
    const int l = m.tri[3 * e + a];
    for (int i = 0; i < 3; ++i) x[3 * a + i] = m.X[3 * l + i] + u[3 * l + i];
  }
}

inline bool AllFinite(const double *v, int n) {
  for (int i = 0; i < n; ++i)
    if (!std::isfinite(v[i])) return false;
  return true;
}

// Evaluates one membrane element at x. Returns a KernelStatus.
inline int MembraneElement(const Problem *P, PetscInt e, const double x[9], double S[3],
                           double D[9], double F[6], double E[3]) {
  const MembraneReference &ref = P->mesh.ref[e];
  if (!AllFinite(x, 9)) return KERNEL_NONFINITE;
  MembraneKinematics(ref, x, F, E);
  if (MembraneAreaRatio(ref, x, nullptr) < P->min_area_ratio) return KERNEL_COLLAPSED;
  const Material &law = P->MaterialOf(e);
  const int nh = law.HistorySize();
  double hist_new[kMaxHistorySize];
  const double *hist_old = nh ? &P->history[(size_t)P->history_size * e] : nullptr;
  return law.Evaluate(E, hist_old, nh ? hist_new : nullptr, S, D);
}

// The tensile part of a membrane stress: negative principal values set to zero. Used for the
// geometric stiffness only (-membrane_tangent_tension_only): a compressed membrane has a
// negative geometric stiffness that makes Newton wander where the film wrinkles; dropping it
// changes the iteration path, not the residual, so not the converged answer.
inline void TensilePart(const double S[3], double T[3]) {
  const double m = 0.5 * (S[0] + S[1]), r = std::sqrt(0.25 * (S[0] - S[1]) * (S[0] - S[1]) + S[2] * S[2]);
  const double s1 = m + r, s2 = m - r;
  if (s2 >= 0.0) {
    T[0] = S[0], T[1] = S[1], T[2] = S[2];
    return;
  }
  if (s1 <= 0.0) {
    T[0] = T[1] = T[2] = 0.0;
    return;
  }
  // direction of s1: (S - s2 I) v = (s1 - s2) v
  double vx = S[0] - s2, vy = S[2];
  if (std::fabs(vx) + std::fabs(vy) < 1e-300) vx = S[2], vy = S[1] - s2;
  const double n = std::sqrt(vx * vx + vy * vy);
  vx /= n, vy /= n;
  T[0] = s1 * vx * vx, T[1] = s1 * vy * vy, T[2] = s1 * vx * vy;
}

PetscErrorCode ScatterToLocal(Vec global, Vec ghosted) {
  PetscFunctionBeginUser;
  if (global != ghosted) PetscCall(VecCopy(global, ghosted));
  PetscCall(VecGhostUpdateBegin(ghosted, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecGhostUpdateEnd(ghosted, INSERT_VALUES, SCATTER_FORWARD));
  PetscFunctionReturn(0);
}

// Agrees on the worst element status over all ranks and remembers which element it was.
PetscErrorCode ReduceStatus(Problem *P, int status, PetscInt element) {
  int local[2] = {status, (int)element}, global[2];
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Allreduce(local, global, 1, MPI_2INT, MPI_MAXLOC, P->comm));
  P->diagnostics.bad_status = global[0];
  P->diagnostics.bad_element = -1;
  if (global[0] != KERNEL_OK) {
    // MAXLOC returned the rank holding the worst status; fetch its element id from there.
    PetscInt id = status == global[0] ? element : -1, g;
    PetscCallMPI(MPI_Allreduce(&id, &g, 1, MPIU_INT, MPI_MAX, P->comm));
    P->diagnostics.bad_element = g;
  }
  PetscFunctionReturn(0);
}

} // namespace

// U with its ghost values as one local array (owned nodes, then ghosts), read-only; every
// element loop starts with it. Pair with RestoreLocalArray.
PetscErrorCode GetLocalArray(Vec U, Vec ghosted, Vec *local, const PetscScalar **a) {
  PetscFunctionBeginUser;
  PetscCall(ScatterToLocal(U, ghosted));
  PetscCall(VecGhostGetLocalForm(ghosted, local));
  PetscCall(VecGetArrayRead(*local, a));
  PetscFunctionReturn(0);
}

PetscErrorCode RestoreLocalArray(Vec ghosted, Vec *local, const PetscScalar **a) {
  PetscFunctionBeginUser;
  PetscCall(VecRestoreArrayRead(*local, a));
  PetscCall(VecGhostRestoreLocalForm(ghosted, local));
  PetscFunctionReturn(0);
}

PetscErrorCode VecMaxNodalNorm(Vec v, PetscReal *max) {
  const PetscScalar *a;
  PetscInt n;
  PetscReal local = 0.0;
  PetscFunctionBeginUser;
  PetscCall(VecGetLocalSize(v, &n));
  PetscCall(VecGetArrayRead(v, &a));
  for (PetscInt i = 0; i + 2 < n; i += 3)
    local = PetscMax(local, std::sqrt(a[i] * a[i] + a[i + 1] * a[i + 1] + a[i + 2] * a[i + 2]));
  PetscCall(VecRestoreArrayRead(v, &a));
  PetscCallMPI(MPI_Allreduce(&local, max, 1, MPIU_REAL, MPIU_MAX, PetscObjectComm((PetscObject)v)));
  PetscFunctionReturn(0);
}

// The local (ghosted) forms of U and of the zeroed force work vector, for an element loop that
// adds into f; EndLocalForces sums the ghosts' parts into their owners and copies to Fout.
static PetscErrorCode BeginLocalForces(Problem *P, Vec U, Vec *Ul, const PetscScalar **u, Vec *Fl,
                                       PetscScalar **f) {
  PetscFunctionBeginUser;
  PetscCall(GetLocalArray(U, P->U_work, Ul, u));
  PetscCall(VecGhostGetLocalForm(P->F_work, Fl));
  PetscCall(VecZeroEntries(*Fl));
  PetscCall(VecGetArray(*Fl, f));
  PetscFunctionReturn(0);
}

static PetscErrorCode EndLocalForces(Problem *P, Vec *Ul, const PetscScalar **u, Vec *Fl, PetscScalar **f,
                                     Vec Fout) {
  PetscFunctionBeginUser;
  PetscCall(VecRestoreArray(*Fl, f));
  PetscCall(VecGhostRestoreLocalForm(P->F_work, Fl));
  PetscCall(RestoreLocalArray(P->U_work, Ul, u));
  PetscCall(VecGhostUpdateBegin(P->F_work, ADD_VALUES, SCATTER_REVERSE));
  PetscCall(VecGhostUpdateEnd(P->F_work, ADD_VALUES, SCATTER_REVERSE));
  PetscCall(VecCopy(P->F_work, Fout));
  PetscFunctionReturn(0);
}

// The membrane elements' internal forces (committed history) added into the local array f; an
// element whose kernel fails is skipped, the worst status and its element kept in *status, *bad.
static void AddMembraneForces(Problem *P, const PetscScalar *u, PetscScalar *f, int *status, PetscInt *bad) {
  const LocalMesh &m = P->mesh;
  for (PetscInt e = 0; e < m.num_elements; ++e) {
    double x[9], F[6], E[3], S[3], D[9], fe[9];
    GatherCoordinates(m, e, u, x);
    const int st = MembraneElement(P, e, x, S, D, F, E);
    if (st != KERNEL_OK) {
      if (st > *status) *status = st, *bad = m.element_natural[e];
      continue;
    }
    MembraneForce(m.ref[e], P->Thickness(e), F, S, nullptr, fe, nullptr);
    for (int a = 0; a < 3; ++a)
      for (int i = 0; i < 3; ++i) f[3 * m.tri[3 * e + a] + i] += fe[3 * a + i];
  }
}

PetscErrorCode FormResidual(SNES snes, Vec U, Vec Fout, void *ctx) {
  Problem *P = (Problem *)ctx;
  const LocalMesh &m = P->mesh;
  Vec Ul, Fl;
  const PetscScalar *u;
  PetscScalar *f;
  int status = KERNEL_OK;
  PetscInt bad = -1;
  double ext2 = 0.0;  // sum of squares of external nodal loads (an estimate of their norm)
  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(LogEvents().residual, 0, 0, 0, 0));
  PetscCall(BeginLocalForces(P, U, &Ul, &u, &Fl, &f));
  AddMembraneForces(P, u, f, &status, &bad);
  // The terms in the list's order (physics_terms.cpp): what they evaluate for the others first.
  for (auto &term : P->terms) PetscCall(term->Prepare(*P, u));
  for (auto &term : P->terms) PetscCall(term->AddLocalForces(*P, u, f, &status, &ext2));
  PetscCall(EndLocalForces(P, &Ul, &u, &Fl, &f, Fout));
  for (auto &term : P->terms) PetscCall(term->AddGlobalForces(*P, U, Fout));

  // Constrained DOFs: keep the internal force as the reaction, then R = u - u_prescribed.
  {
    PetscScalar *fo, *r;
    const PetscScalar *ug;
    PetscCall(VecGetArray(Fout, &fo));
    PetscCall(VecGetArray(P->reaction, &r));
    PetscCall(VecGetArrayRead(U, &ug));
    for (PetscInt i = 0; i < 3 * m.num_owned; ++i) r[i] = 0.0;
    for (size_t k = 0; k < P->con_owned_dof.size(); ++k) {
      const PetscInt d = P->con_owned_dof[k];
      r[d] = fo[d];
      ext2 += fo[d] * fo[d];
      fo[d] = ug[d] - (P->con_owned_value[k].At(P->scene.schedules, P->time) - P->con_owned_offset[k]);
    }
    PetscCall(VecRestoreArrayRead(U, &ug));
    PetscCall(VecRestoreArray(P->reaction, &r));
    PetscCall(VecRestoreArray(Fout, &fo));
  }
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &ext2, 1, MPI_DOUBLE, MPI_SUM, P->comm));
  P->diagnostics.force_scale = std::sqrt(ext2);
  PetscCall(ReduceStatus(P, status, bad));
  if (P->diagnostics.bad_status != KERNEL_OK && snes && !P->diagnostics.in_linesearch)
    PetscCall(SNESSetFunctionDomainError(snes));
  PetscCall(PetscLogEventEnd(LogEvents().residual, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

// The element loop of FormResidual (committed history) and the terms' internal forces (cables):
// no loads, contact or constraint rows, and no side effects on the reactions or the force scale.
PetscErrorCode FormInternalForce(Problem *P, Vec U, Vec Fout) {
  Vec Ul, Fl;
  const PetscScalar *u;
  PetscScalar *f;
  int status = KERNEL_OK;  // a converged state has no failed element
  PetscInt bad = -1;
  PetscFunctionBeginUser;
  PetscCall(BeginLocalForces(P, U, &Ul, &u, &Fl, &f));
  AddMembraneForces(P, u, f, &status, &bad);
  for (auto &term : P->terms) PetscCall(term->AddInternalForces(*P, u, f));
  PetscCall(EndLocalForces(P, &Ul, &u, &Fl, &f, Fout));
  PetscFunctionReturn(0);
}

PetscErrorCode FormJacobian(SNES snes, Vec U, Mat J, Mat Pmat, void *ctx) {
  Problem *P = (Problem *)ctx;
  const LocalMesh &m = P->mesh;
  Vec Ul;
  const PetscScalar *u;
  int status = KERNEL_OK;
  PetscInt bad = -1;
  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(LogEvents().jacobian, 0, 0, 0, 0));
  PetscCall(MatZeroEntries(Pmat));
  PetscCall(GetLocalArray(U, P->U_work, &Ul, &u));
  // Per element the pressure of every load on it (the load stiffness is linear in p). The terms
  // are prepared here again (the chambers' pressures): the tangent predictor asks for J at a load
  // time the last residual was not evaluated at.
  for (auto &term : P->terms) PetscCall(term->Prepare(*P, u));
  std::vector<double> pressure;
  for (auto &term : P->terms) PetscCall(term->AddElementPressure(*P, &pressure));
  ElementBlockValues direct;  // the matrix's values when the blocks' places are known
  if (!P->unassembled) PetscCall(ElementBlocksGet(Pmat, P->element_global, &P->element_blocks, &direct));
  for (PetscInt e = 0; e < m.num_elements; ++e) {
    double x[9], F[6], E[3], S[3], D[9], K[81];  // K only: no force is formed here
    GatherCoordinates(m, e, u, x);
    int st = MembraneElement(P, e, x, S, D, F, E);
    if (st != KERNEL_OK) {
      if (st > status) status = st, bad = m.element_natural[e];
      continue;
    }
    if (P->tangent_tension_only) {
      double T[3];
      TensilePart(S, T);
      MembraneForce(m.ref[e], P->Thickness(e), F, T, D, nullptr, K);
    } else {
      MembraneForce(m.ref[e], P->Thickness(e), F, S, D, nullptr, K);
    }
    if (!pressure.empty() && pressure[e] != 0.0) PressureLoadSubtractTangent(pressure[e], x, nullptr, K);
    const int *tri = &m.tri[3 * e];
    if (P->element_constrained[e])
      for (int r = 0; r < 9; ++r) {
        if (!P->dof_constrained[3 * tri[r / 3] + r % 3]) continue;
        for (int c = 0; c < 9; ++c) K[9 * r + c] = K[9 * c + r] = 0.0;
      }
    if (P->unassembled) {
      PetscCall(UnassembledAddElement(Pmat, tri, K));
      continue;
    }
    if (direct.diag && ElementBlocksAdd(P->element_blocks, e, K, direct)) continue;
    // Global block ids precomputed: no local-to-global lookup per element.
    PetscCall(MatSetValuesBlocked(Pmat, 3, &P->element_global[3 * e], 3, &P->element_global[3 * e], K, ADD_VALUES));
  }
  PetscCall(ElementBlocksRestore(&direct));
  for (auto &term : P->terms) PetscCall(term->AddTangent(*P, U, u, Pmat));
  PetscCall(RestoreLocalArray(P->U_work, &Ul, &u));
  if (!P->unassembled)  // unassembled: after the assembly, split over the subdomains
    for (PetscInt d : P->con_owned_dof) {
      const PetscScalar one = 1.0;
      PetscCall(MatSetValuesLocal(Pmat, 1, &d, 1, &d, &one, ADD_VALUES));
    }
  PetscCall(MatAssemblyBegin(Pmat, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(Pmat, MAT_FINAL_ASSEMBLY));
  if (P->unassembled) PetscCall(UnassembledAddConstraintDiagonal(P, Pmat));
  for (auto &term : P->terms) PetscCall(term->AddAssembledTangent(*P, Pmat));
  if (J != Pmat) {
    PetscCall(MatAssemblyBegin(J, MAT_FINAL_ASSEMBLY));
    PetscCall(MatAssemblyEnd(J, MAT_FINAL_ASSEMBLY));
  }
  PetscCall(ReduceStatus(P, status, bad));
  PetscCall(PetscLogEventEnd(LogEvents().jacobian, 0, 0, 0, 0));
  PetscCheck(P->diagnostics.bad_status == KERNEL_OK, P->comm, PETSC_ERR_NOT_CONVERGED,
             "Jacobian: element %" PetscInt_FMT ": %s (the residual at the same state passed)",
             P->diagnostics.bad_element, KernelStatusName(P->diagnostics.bad_status));
  PetscFunctionReturn(0);
}

PetscErrorCode CheckStep(Problem *P, Vec X, Vec W, PetscBool *ok) {
  const LocalMesh &m = P->mesh;
  Vec Xl, Wl;
  const PetscScalar *xa, *wa;
  int status = KERNEL_OK;
  PetscInt bad = -1;
  PetscFunctionBeginUser;
  PetscCall(GetLocalArray(X, P->F_work, &Xl, &xa));
  PetscCall(GetLocalArray(W, P->U_work, &Wl, &wa));
  for (PetscInt e = 0; e < m.num_elements; ++e) {
    double x0[9], x1[9], n0[3], n1[3];
    GatherCoordinates(m, e, xa, x0);
    GatherCoordinates(m, e, wa, x1);
    MembraneAreaRatio(m.ref[e], x0, n0);
    const double ratio = MembraneAreaRatio(m.ref[e], x1, n1);
    const bool flipped = n0[0] * n1[0] + n0[1] * n1[1] + n0[2] * n1[2] <= 0.0;
    if (!(ratio >= P->min_area_ratio) || flipped) {
      status = KERNEL_COLLAPSED;
      bad = m.element_natural[e];
      break;
    }
  }
  PetscCall(RestoreLocalArray(P->U_work, &Wl, &wa));
  PetscCall(RestoreLocalArray(P->F_work, &Xl, &xa));
  PetscCall(ReduceStatus(P, status, bad));
  *ok = P->diagnostics.bad_status == KERNEL_OK ? PETSC_TRUE : PETSC_FALSE;
  PetscFunctionReturn(0);
}

PetscErrorCode LargestUpdateGradient(Problem *P, Vec Y, PetscReal *gradient) {
  const LocalMesh &m = P->mesh;
  Vec Yl;
  const PetscScalar *y;
  PetscReal g = 0.0;
  PetscFunctionBeginUser;
  PetscCall(GetLocalArray(Y, P->U_work, &Yl, &y));
  for (PetscInt e = 0; e < m.num_elements; ++e)
    for (int a = 0; a < 3; ++a) {
      const int i = m.tri[3 * e + a], j = m.tri[3 * e + (a + 1) % 3];
      double dy = 0.0, dx = 0.0;
      for (int c = 0; c < 3; ++c) {
        dy += (y[3 * i + c] - y[3 * j + c]) * (y[3 * i + c] - y[3 * j + c]);
        dx += (m.X[3 * i + c] - m.X[3 * j + c]) * (m.X[3 * i + c] - m.X[3 * j + c]);
      }
      if (dx > 0.0) g = std::max(g, std::sqrt(dy / dx));
    }
  PetscCall(RestoreLocalArray(P->U_work, &Yl, &y));
  PetscCallMPI(MPI_Allreduce(&g, gradient, 1, MPIU_REAL, MPIU_MAX, P->comm));
  PetscFunctionReturn(0);
}

PetscErrorCode UpdateReference(Problem *P, Vec U) {
  LocalMesh &m = P->mesh;
  Vec Ul;
  const PetscScalar *u;
  int status = KERNEL_OK;
  PetscInt bad = -1;
  PetscFunctionBeginUser;
  PetscCall(GetLocalArray(U, P->U_work, &Ul, &u));
  for (PetscInt i = 0; i < 3 * m.NumLocal(); ++i) m.X[i] += u[i];
  for (size_t k = 0; k < P->con_owned_dof.size(); ++k) P->con_owned_offset[k] += u[P->con_owned_dof[k]];
  PetscCall(RestoreLocalArray(P->U_work, &Ul, &u));
  for (PetscInt e = 0; e < m.num_elements; ++e) {
    double X[9];
    for (int a = 0; a < 3; ++a)
      for (int i = 0; i < 3; ++i) X[3 * a + i] = m.X[3 * m.tri[3 * e + a] + i];
    const int st = MembraneReferenceBuild(X, m.MdAxis(e, P->scene.md_axis), 0.0, &m.ref[e]);
    if (st != KERNEL_OK) status = st, bad = m.element_natural[e];
  }
  PetscCall(ReduceStatus(P, status, bad));
  PetscFunctionReturn(0);
}

PetscErrorCode CommitHistory(Problem *P, Vec U) {
  const LocalMesh &m = P->mesh;
  const int nh = P->history_size;
  Vec Ul;
  const PetscScalar *u;
  int status = KERNEL_OK;
  PetscInt bad = -1;
  PetscFunctionBeginUser;
  if (nh == 0) PetscFunctionReturn(0);
  PetscCall(GetLocalArray(U, P->U_work, &Ul, &u));
  for (PetscInt e = 0; e < m.num_elements; ++e) {
    // An element whose law keeps no history (an elastic part beside a plastic one) skips it.
    const Material &law = P->MaterialOf(e);
    if (law.HistorySize() == 0) continue;
    double x[9], F[6], E[3], S[3], D[9];
    GatherCoordinates(m, e, u, x);
    MembraneKinematics(m.ref[e], x, F, E);
    int st = law.Evaluate(E, &P->history[(size_t)nh * e], &P->history_trial[(size_t)nh * e], S, D);
    if (st != KERNEL_OK) status = st, bad = m.element_natural[e];
  }
  PetscCall(RestoreLocalArray(P->U_work, &Ul, &u));
  PetscCall(ReduceStatus(P, status, bad));
  PetscCheck(P->diagnostics.bad_status == KERNEL_OK, P->comm, PETSC_ERR_NOT_CONVERGED,
             "committing the history: element %" PetscInt_FMT ": %s", P->diagnostics.bad_element,
             KernelStatusName(P->diagnostics.bad_status));
  P->history.swap(P->history_trial);
  PetscFunctionReturn(0);
}

PetscErrorCode ComputeCellFields(Problem *P, Vec U, CellFields *c, bool with_true_stress) {
  const LocalMesh &m = P->mesh;
  const PetscInt ne = m.num_elements;
  const int nh = P->history_size;
  Vec Ul, acc, accl;
  const PetscScalar *u;
  PetscScalar *a;
  PetscFunctionBeginUser;
  c->stress.assign(3 * ne, 0);
  c->strain.assign(3 * ne, 0);
  c->mises.assign(ne, 0);
  c->smin.assign(ne, 0);
  c->emin.assign(ne, 0);
  c->area_ratio.assign(ne, 0);
  const PetscInt nt = with_true_stress ? ne : 0;
  c->cauchy.assign(6 * nt, 0);
  c->cauchy_mises.assign(nt, 0);
  c->principal.assign(2 * nt, 0);
  c->dir1.assign(3 * nt, 0);
  c->dir2.assign(3 * nt, 0);
  const bool plastic = P->HasPlasticStrain();
  c->ep.assign(plastic ? 3 * ne : 0, 0);
  c->ep_bar.assign(plastic ? ne : 0, 0);
  const bool wrinkling = P->wrinkling;
  c->wrinkle_state.assign(wrinkling ? ne : 0, 0);
  c->wrinkle_dir.assign(wrinkling ? 3 * ne : 0, 0);
  c->wrinkle_strain.assign(wrinkling ? ne : 0, 0);
  // Nodal averages: (sum, count) per node in a ghosted block-2 vector.
  std::vector<PetscInt> ghost_ids(m.num_ghost);
  for (PetscInt g = 0; g < m.num_ghost; ++g) ghost_ids[g] = m.global_id[m.num_owned + g];
  PetscCall(VecCreateGhostBlock(P->comm, 2, 2 * m.num_owned, PETSC_DECIDE, m.num_ghost,
                                ghost_ids.data(), &acc));
  PetscCall(VecGhostGetLocalForm(acc, &accl));
  PetscCall(VecZeroEntries(accl));
  PetscCall(VecGetArray(accl, &a));
  PetscCall(GetLocalArray(U, P->U_work, &Ul, &u));
  for (PetscInt e = 0; e < ne; ++e) {
    double x[9], F[6], E[3], S[3], D[9], hist[kMaxHistorySize];
    GatherCoordinates(m, e, u, x);
    MembraneKinematics(m.ref[e], x, F, E);
    const Material &law = P->MaterialOf(e);
    const double *h = law.HistorySize() ? &P->history[(size_t)nh * e] : nullptr;
    law.Evaluate(E, h, h ? hist : nullptr, S, D);
    for (int i = 0; i < 3; ++i) c->stress[3 * e + i] = S[i];
    c->strain[3 * e + 0] = E[0];
    c->strain[3 * e + 1] = E[1];
    c->strain[3 * e + 2] = 0.5 * E[2];
    c->mises[e] = MisesPlaneStress(S);
    c->smin[e] = MinPrincipalStress(S);
    c->emin[e] = MinPrincipalStrain(E);
    c->area_ratio[e] = MembraneAreaRatio(m.ref[e], x, nullptr);
    if (with_true_stress) {
      CauchyStress(F, S, &c->cauchy[6 * e]);
      c->cauchy_mises[e] = MisesStress3(&c->cauchy[6 * e]);
      PrincipalStresses(F, &c->cauchy[6 * e], &c->principal[2 * e], &c->dir1[3 * e], &c->dir2[3 * e]);
    }
    double ep[3] = {0, 0, 0}, epb = 0.0;
    if (plastic && law.PlasticStrain(h, ep, &epb)) {
      c->ep[3 * e] = ep[0], c->ep[3 * e + 1] = ep[1], c->ep[3 * e + 2] = 0.5 * ep[2];
      c->ep_bar[e] = epb;
    }
    WrinkleInfo wi;
    if (wrinkling && law.Wrinkling(E, h, &wi)) {
      c->wrinkle_state[e] = wi.state;
      c->wrinkle_strain[e] = wi.strain;
      if (wi.state == WRINKLE_WRINKLED) {
        // Pushed forward (F n) so ParaView glyphs it on the deformed film.
        double v[3], n2 = 0.0;
        for (int i = 0; i < 3; ++i) v[i] = F[2 * i] * wi.dir[0] + F[2 * i + 1] * wi.dir[1], n2 += v[i] * v[i];
        const double inv = n2 > 0.0 ? 1.0 / std::sqrt(n2) : 0.0;
        for (int i = 0; i < 3; ++i) c->wrinkle_dir[3 * e + i] = v[i] * inv;
      }
    }
    for (int k = 0; k < 3; ++k) {
      a[2 * m.tri[3 * e + k]] += c->mises[e];
      a[2 * m.tri[3 * e + k] + 1] += 1.0;
    }
  }
  PetscCall(RestoreLocalArray(P->U_work, &Ul, &u));
  PetscCall(VecRestoreArray(accl, &a));
  PetscCall(VecGhostRestoreLocalForm(acc, &accl));
  PetscCall(VecGhostUpdateBegin(acc, ADD_VALUES, SCATTER_REVERSE));
  PetscCall(VecGhostUpdateEnd(acc, ADD_VALUES, SCATTER_REVERSE));
  PetscCall(VecGetArray(acc, &a));
  c->nodal_mises.assign(m.num_owned, 0);
  for (PetscInt l = 0; l < m.num_owned; ++l)
    c->nodal_mises[l] = a[2 * l + 1] > 0 ? a[2 * l] / a[2 * l + 1] : 0.0;
  PetscCall(VecRestoreArray(acc, &a));
  PetscCall(VecDestroy(&acc));
  PetscFunctionReturn(0);
}

} // namespace etfe
