// Follower pressures and nodal forces as physics terms (pressure_term.h).
#include "etfe/assembly/pressure_term.h"

#include "etfe/assembly/chamber.h"
#include "etfe/kernels/pressure.h"
#include "etfe/assembly/problem.h"

namespace etfe {

namespace {

inline void GatherCoordinates(const LocalMesh &m, PetscInt e, const PetscScalar *u, double x[9]) {
  for (int a = 0; a < 3; ++a) {
    const int l = m.tri[3 * e + a];
    for (int i = 0; i < 3; ++i)
      x[3 * a + i] = m.X[3 * l + i] + u[3 * l + i];
  }
}

// The pressure of a load now: its chamber's (evaluated by the chamber term's Prepare, before the
// loads in the list's loops) or its schedule's.
double LoadPressure(const Problem &P, const FollowerPressure &load) {
  return load.chamber >= 0 ? ChamberLoadPressure(&P, load.chamber, load.sign)
                           : load.value.At(P.scene.schedules, P.time);
}

} // namespace

PetscErrorCode PressureTerm::AddLocalForces(Problem &P, const PetscScalar *u, PetscScalar *f, int *,
                                            double *ext2) {
  const LocalMesh &m = P.mesh;
  PetscFunctionBeginUser;
  for (const FollowerPressure &load : loads) {
    const double p = LoadPressure(P, load);
    for (PetscInt e : load.elements) {
      double x[9], fe[9];
      GatherCoordinates(m, e, u, x);
      PressureLoad(p, x, fe, nullptr); // the residual needs no load stiffness
      for (int a = 0; a < 3; ++a)
        for (int i = 0; i < 3; ++i)
          f[3 * m.tri[3 * e + a] + i] -= fe[3 * a + i];
      for (int k = 0; k < 9; ++k)
        *ext2 += fe[k] * fe[k];
    }
  }
  PetscFunctionReturn(0);
}

// The load stiffness is linear in p: the element loop takes the sum of the pressures on it.
PetscErrorCode PressureTerm::AddElementPressure(Problem &P, std::vector<double> *pressure) {
  PetscFunctionBeginUser;
  for (const FollowerPressure &load : loads) {
    const double p = LoadPressure(P, load);
    if (p == 0.0) continue;
    if (pressure->empty()) pressure->assign(P.mesh.num_elements, 0.0);
    for (PetscInt e : load.elements)
      (*pressure)[e] += p;
  }
  PetscFunctionReturn(0);
}

PetscErrorCode NodalForceTerm::AddLocalForces(Problem &P, const PetscScalar *, PetscScalar *f,
                                              int *, double *ext2) {
  PetscFunctionBeginUser;
  for (size_t k = 0; k < owned_dof.size(); ++k) {
    const double v = value[k].At(P.scene.schedules, P.time);
    f[owned_dof[k]] -= v;
    *ext2 += v * v;
  }
  PetscFunctionReturn(0);
}

const std::vector<FollowerPressure> &PressureLoads(const Problem &P) {
  static const std::vector<FollowerPressure> none;
  const PressureTerm *t = FindTerm<PressureTerm>(P);
  return t ? t->loads : none;
}

PetscErrorCode AddPressureTerm(Problem *P, std::vector<std::vector<PetscInt>> *elements) {
  PetscFunctionBeginUser;
  if (P->scene.pressures.empty()) PetscFunctionReturn(0);
  auto t = std::make_unique<PressureTerm>();
  // Every rank has the small list, each its own elements.
  for (size_t k = 0; k < P->scene.pressures.size(); ++k)
    t->loads.push_back({std::move((*elements)[k]), P->scene.pressures[k].value,
                        P->scene.pressures[k].chamber, P->scene.pressures[k].sign});
  P->terms.push_back(std::move(t));
  PetscFunctionReturn(0);
}

PetscErrorCode AddNodalForceTerm(Problem *P, const std::vector<NodalForce> &forces) {
  int any = !forces.empty();
  PetscFunctionBeginUser;
  // Each rank holds its own nodes' forces: the term exists on every rank or on none.
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &any, 1, MPI_INT, MPI_MAX, P->comm));
  if (!any) PetscFunctionReturn(0);
  auto t = std::make_unique<NodalForceTerm>();
  for (const NodalForce &f : forces) {
    t->owned_dof.push_back(3 * f.node + f.comp);
    t->value.push_back(f.value);
  }
  P->terms.push_back(std::move(t));
  PetscFunctionReturn(0);
}

} // namespace etfe
