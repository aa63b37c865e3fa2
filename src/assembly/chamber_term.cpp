// The gas chambers as a physics term (chamber.h): what the problem's loops ask of them.
#include <algorithm>
#include <cmath>

#include "etfe/assembly/chamber.h"
#include "etfe/kernels/status.h"
#include "etfe/assembly/problem.h"

namespace etfe {

// Evaluated before the pressure loads, which read the chambers' gauge pressures.
PetscErrorCode ChamberSet::Prepare(Problem &P, const PetscScalar *u) {
  return ChamberEvaluate(&P, u);
}

PetscErrorCode ChamberSet::AddLocalForces(Problem &, const PetscScalar *, PetscScalar *,
                                          int *status, double *) {
  for (double g : gauge)
    if (!std::isfinite(g))
      *status = std::max(*status, (int)KERNEL_NONFINITE); // a chamber turned inside out
  return 0;
}

// The rank-one part goes into the LRC matrix's own U and c, not into A.
PetscErrorCode ChamberSet::AddTangent(Problem &P, Vec, const PetscScalar *u, Mat) {
  return ChamberTangent(&P, u);
}

PetscErrorCode ChamberSet::Commit(Problem &P, double t) {
  return ChamberCommit(&P, t);
}

// Which chambers are sealed and the gas they hold: the same on every rank.
const TermDatasetInfo ChamberSet::kCheckpoint = {"chamber_state", Layout::Nodes, true, 1};

PetscErrorCode ChamberSet::State(const Problem &P, std::vector<TermData> *blocks) const {
  std::vector<double> values;
  ChamberStateGet(&P, &values);
  blocks->push_back(kCheckpoint.Block(std::move(values)));
  return 0;
}

PetscErrorCode ChamberSet::Restore(Problem &P, const std::vector<TermData> &blocks) {
  if (const std::vector<double> *values = kCheckpoint.Find(blocks)) ChamberStateSet(&P, *values);
  return 0;
}

// At the last evaluation: the written state's (its residual, or the commit's ChamberUpdate).
PetscErrorCode ChamberSet::Fields(const Problem &, std::vector<TermData> *fields) const {
  TermData p, v;
  p.name = "gauge_pressure", p.replicated = true, p.values = gauge, p.units = "MPa";
  p.description = "gauge pressure of each gas chamber";
  v.name = "volume", v.replicated = true, v.values = volume, v.units = "mm^3";
  v.description = "volume each gas chamber encloses";
  fields->push_back(std::move(p));
  fields->push_back(std::move(v));
  return 0;
}

TermSolverNeeds ChamberSet::SolverNeeds() const {
  TermSolverNeeds n;
  n.krylov_outer = may_seal;
  n.outer = may_seal ? J : nullptr;
  return n;
}

PetscErrorCode ChamberSet::Destroy(Problem &) {
  PetscFunctionBeginUser;
  PetscCall(MatDestroy(&J));
  PetscCall(MatDestroy(&U));
  PetscCall(VecDestroy(&c));
  PetscCall(VecDestroy(&g_work));
  PetscFunctionReturn(0);
}

} // namespace etfe
