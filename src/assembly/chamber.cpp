// Gas chambers (see chamber.h and kernels/chamber.h).
#include "etfe/chamber.h"

#include <cmath>

#include "etfe/assembly.h"
#include "etfe/kernels/chamber.h"
#include "etfe/kernels/pressure.h"
#include "etfe/problem.h"

namespace etfe {

namespace {

void Coordinates(const LocalMesh &m, PetscInt e, const PetscScalar *u, double x[9]) {
  for (int a = 0; a < 3; ++a)
    for (int i = 0; i < 3; ++i) {
      const int l = m.tri[3 * e + a];
      x[3 * a + i] = m.X[3 * l + i] + PetscRealPart(u[3 * l + i]);
    }
}

double SuppliedGauge(const Problem *P, int k) {
  return P->scene.chambers[k].supplied.At(P->scene.schedules, P->time);
}

// The gauge pressure of chamber k at volume V: supplied, or from its sealed amount.
double Gauge(const Problem *P, int k, double V) {
  const ChamberSet &c = *P->chambers;
  if (!c.sealed[k]) return SuppliedGauge(P, k);
  return SealedGauge(c.amount[k], c.atmosphere, V, P->scene.chambers[k].kappa);
}

} // namespace

PetscErrorCode ChamberUpdate(Problem *P, Vec U) {
  const PetscScalar *u;
  Vec Ul;
  PetscFunctionBeginUser;
  PetscCall(GetLocalArray(U, P->U_work, &Ul, &u));
  PetscCall(ChamberEvaluate(P, u));
  PetscCall(RestoreLocalArray(P->U_work, &Ul, &u));
  PetscFunctionReturn(0);
}

PetscErrorCode ChamberCreate(Problem *P) {
  const size_t n = P->scene.chambers.size();
  PetscFunctionBeginUser;
  if (n == 0) PetscFunctionReturn(0);
  auto *c = new ChamberSet();
  P->chambers = c;
  c->atmosphere = P->scene.atmosphere;
  c->volume.assign(n, 0.0), c->gauge.assign(n, 0.0), c->sealed.assign(n, 0), c->amount.assign(n, 0.0);
  PetscBool rank_one = PETSC_TRUE;
  PetscOptionsBegin(P->comm, nullptr, "Gas chambers", "Chamber");
  PetscCall(PetscOptionsBool("-chamber_rank_one",
                             "Newton's tangent includes the sealed gas's stiffness (kappa p_abs / V) g g^T (off: the "
                             "pressure is updated between iterations only, and Newton converges linearly)",
                             "", rank_one, &rank_one, nullptr));
  PetscOptionsEnd();
  for (const ChamberSpec &s : P->scene.chambers) c->may_seal |= s.sealed_from_stage > 0 && rank_one;
  if (c->may_seal) {
    PetscInt nlocal, N;
    PetscCall(VecGetLocalSize(P->U, &nlocal));
    PetscCall(VecGetSize(P->U, &N));
    PetscCall(MatCreateDense(P->comm, nlocal, PETSC_DECIDE, N, (PetscInt)n, nullptr, &c->U));
    PetscCall(MatZeroEntries(c->U));
    PetscCall(MatAssemblyBegin(c->U, MAT_FINAL_ASSEMBLY));
    PetscCall(MatAssemblyEnd(c->U, MAT_FINAL_ASSEMBLY));
    PetscCall(VecCreateSeq(PETSC_COMM_SELF, (PetscInt)n, &c->c));
    PetscCall(VecZeroEntries(c->c));
    PetscCall(MatCreateLRC(P->J, c->U, c->c, nullptr, &c->J));
    PetscCall(VecDuplicate(P->U, &c->g_work));
  }
  // Sealed from the start: the gas the chamber holds at load time 0.
  PetscCall(ChamberUpdate(P, P->U));
  for (size_t k = 0; k < n; ++k)
    if (P->scene.chambers[k].sealed_from_stage == 1) {
      PetscCheck(c->volume[k] > 0, P->comm, PETSC_ERR_ARG_WRONG,
                 "chamber %s is sealed from stage 1 but encloses %g mm^3 at the start: inflate it in a stage before "
                 "sealing it, or check the orientation of its surfaces (-chamber_%s_signs)",
                 P->scene.chambers[k].name.c_str(), c->volume[k], P->scene.chambers[k].name.c_str());
      c->amount[k] = SealedAmount(SuppliedGauge(P, (int)k), c->atmosphere, c->volume[k], P->scene.chambers[k].kappa);
      c->sealed[k] = 1;
    }
  PetscFunctionReturn(0);
}

PetscErrorCode ChamberEvaluate(Problem *P, const PetscScalar *u) {
  ChamberSet &c = *P->chambers;
  const size_t n = c.volume.size();
  PetscFunctionBeginUser;
  std::vector<double> V(n, 0.0);
  for (const Problem::PressureLoad &load : P->pressures) {
    if (load.chamber < 0) continue;
    const double *o = P->scene.chambers[load.chamber].origin;
    for (PetscInt e : load.elements) {
      double x[9];
      Coordinates(P->mesh, e, u, x);
      V[load.chamber] += load.sign * ChamberTetVolume(x, o);
    }
  }
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, V.data(), (int)n, MPI_DOUBLE, MPI_SUM, P->comm));
  for (size_t k = 0; k < n; ++k) {
    c.volume[k] = V[k] + P->scene.chambers[k].extra_volume;
    c.gauge[k] = c.sealed[k] && !(c.volume[k] > 0) ? NAN : Gauge(P, (int)k, c.volume[k]);
  }
  PetscFunctionReturn(0);
}

double ChamberLoadPressure(const Problem *P, int chamber, double sign) { return sign * P->chambers->gauge[chamber]; }

PetscErrorCode ChamberTangent(Problem *P, const PetscScalar *u) {
  ChamberSet &c = *P->chambers;
  const size_t n = c.volume.size();
  PetscFunctionBeginUser;
  if (!c.may_seal) PetscFunctionReturn(0);
  for (size_t k = 0; k < n; ++k) {
    Vec gl, col;
    PetscScalar *g;
    PetscCall(VecGhostGetLocalForm(c.g_work, &gl));
    PetscCall(VecZeroEntries(gl));
    PetscCall(VecGetArray(gl, &g));
    for (const Problem::PressureLoad &load : P->pressures) {
      if (load.chamber != (int)k) continue;
      for (PetscInt e : load.elements) {
        double x[9], f[9];
        Coordinates(P->mesh, e, u, x);
        PressureLoad(load.sign, x, f, nullptr);  // dV/dx per unit pressure
        for (int a = 0; a < 3; ++a)
          for (int i = 0; i < 3; ++i) g[3 * P->mesh.tri[3 * e + a] + i] += f[3 * a + i];
      }
    }
    PetscCall(VecRestoreArray(gl, &g));
    PetscCall(VecGhostRestoreLocalForm(c.g_work, &gl));
    PetscCall(VecGhostUpdateBegin(c.g_work, ADD_VALUES, SCATTER_REVERSE));
    PetscCall(VecGhostUpdateEnd(c.g_work, ADD_VALUES, SCATTER_REVERSE));
    {  // prescribed DOFs do not move: no volume change through them
      PetscScalar *a;
      PetscCall(VecGetArray(c.g_work, &a));
      for (PetscInt d : P->con_owned_dof) a[d] = 0.0;
      PetscCall(VecRestoreArray(c.g_work, &a));
    }
    PetscCall(MatDenseGetColumnVecWrite(c.U, (PetscInt)k, &col));
    PetscCall(VecCopy(c.g_work, col));
    PetscCall(MatDenseRestoreColumnVecWrite(c.U, (PetscInt)k, &col));
    const double stiff = c.sealed[k] ? SealedStiffness(c.amount[k], c.volume[k], P->scene.chambers[k].kappa) : 0.0;
    PetscCall(VecSetValue(c.c, (PetscInt)k, stiff, INSERT_VALUES));
  }
  PetscCall(VecAssemblyBegin(c.c));
  PetscCall(VecAssemblyEnd(c.c));
  // U and c are the LRC matrix's own (it multiplies with them as they are now).
  PetscFunctionReturn(0);
}

PetscErrorCode ChamberCommit(Problem *P, double t) {
  ChamberSet &c = *P->chambers;
  PetscFunctionBeginUser;
  PetscCall(ChamberUpdate(P, P->U));
  for (size_t k = 0; k < c.volume.size(); ++k)
    PetscCheck(c.volume[k] > 0, P->comm,
               PETSC_ERR_NOT_CONVERGED,
               "chamber %s turned inside out at load time %g (volume %g m^3): its foils passed through each other "
               "(a load heavier than the inflation pressure); contact between the layers is not modelled, so the "
               "state cannot be trusted from here. Lower the load or raise the pressure, or seal the chamber",
               P->scene.chambers[k].name.c_str(), t, 1e-9 * c.volume[k]);
  for (size_t k = 0; k < c.volume.size(); ++k) {
    const ChamberSpec &s = P->scene.chambers[k];
    if (c.sealed[k] || s.sealed_from_stage <= 1 || std::fabs(t - (s.sealed_from_stage - 1)) > 1e-9) continue;
    PetscCheck(c.volume[k] > 0, P->comm, PETSC_ERR_ARG_WRONG,
               "chamber %s is sealed from stage %d but encloses %g mm^3 then: inflate it first, or check the "
               "orientation of its surfaces (-chamber_%s_signs)",
               s.name.c_str(), s.sealed_from_stage, c.volume[k], s.name.c_str());
    c.amount[k] = SealedAmount(SuppliedGauge(P, (int)k), c.atmosphere, c.volume[k], s.kappa);
    c.sealed[k] = 1;
    PetscCall(PetscPrintf(P->comm, "chamber %s: sealed at load time %g with %.6g kPa gauge in %.6g m^3\n", s.name.c_str(),
                          t, 1e3 * (c.amount[k] * std::pow(c.volume[k], -s.kappa) - c.atmosphere), 1e-9 * c.volume[k]));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode ChamberDestroy(Problem *P) {
  PetscFunctionBeginUser;
  if (!P->chambers) PetscFunctionReturn(0);
  PetscCall(MatDestroy(&P->chambers->J));
  PetscCall(MatDestroy(&P->chambers->U));
  PetscCall(VecDestroy(&P->chambers->c));
  PetscCall(VecDestroy(&P->chambers->g_work));
  delete P->chambers;
  P->chambers = nullptr;
  PetscFunctionReturn(0);
}

void ChamberStateGet(const Problem *P, std::vector<double> *state) {
  state->clear();
  if (!P->chambers) return;
  for (size_t k = 0; k < P->chambers->sealed.size(); ++k) state->push_back(P->chambers->sealed[k]), state->push_back(P->chambers->amount[k]);
}

void ChamberStateSet(Problem *P, const std::vector<double> &state) {
  if (!P->chambers) return;
  for (size_t k = 0; k < P->chambers->sealed.size() && 2 * k + 1 < state.size(); ++k)
    P->chambers->sealed[k] = state[2 * k] != 0, P->chambers->amount[k] = state[2 * k + 1];
}

} // namespace etfe
