// Gas chambers as a component of the problem (assembly layer, src/assembly/chamber.cpp): exists
// only when the scene has chambers (SceneSpec::chambers); without them nothing here is allocated
// or run. Each chamber's volume and gauge pressure are evaluated at every residual (collective:
// one reduction), the pressure acting on its boundary's pressure loads (pressure_term.h, with
// its index). A chamber that can be sealed adds the rank-one stiffness (kappa p_abs / V) g g^T to
// the tangent without densifying the sparse matrix: Newton solves with J = A + U diag(c) U^T
// (MATLRC, U the chambers' volume gradients g) preconditioned by the factored sparse A, which
// GMRES inverts exactly in (chambers + 1) iterations.
#pragma once
#include <petscmat.h>

#include <vector>

#include "etfe/assembly/physics_term.h"

namespace etfe {

struct Problem;

struct ChamberSet : PhysicsTerm {
  double atmosphere = 0.101325;            // MPa, absolute
  std::vector<double> volume, gauge;       // at the last evaluation (mm^3, MPa)
  std::vector<char> sealed;                // committed: the gas amount is fixed
  std::vector<double> amount;              // p_abs V^kappa at sealing
  // Supply on again after a sealed stage: at release_time (-1: none) the supply takes over from
  // release_gauge, reaching the supplied pressure at the end of that stage.
  std::vector<double> release_time, release_gauge;
  bool per_stage = false;                  // some chamber is sealed per stage (the state keeps the release)
  bool may_seal = false;                   // some chamber is sealed at some stage (and -chamber_rank_one): J is the LRC
  Mat J = nullptr;                         // A + U diag(c) U^T (may_seal)
  Mat U = nullptr;                         // dense, one column per chamber: dV/dx on free DOFs
  Vec c = nullptr;                         // kappa p_abs / V per sealed chamber, 0 otherwise
  Vec g_work = nullptr;                    // ghosted scratch for assembling g

  // As a physics term (chamber_term.cpp): the volumes evaluated before the pressure loads read
  // them, the rank-one tangent, the commit (sealing, release), the checkpoint's chamber_state,
  // the pressures and volumes in the results and the Krylov solve around the sparse tangent.
  const char *Name() const override { return "chambers"; }
  PetscErrorCode Prepare(Problem &, const PetscScalar *u) override;
  PetscErrorCode AddLocalForces(Problem &, const PetscScalar *u, PetscScalar *f, int *status, double *external2) override;
  PetscErrorCode AddTangent(Problem &, Vec U, const PetscScalar *u, Mat A) override;
  PetscErrorCode Commit(Problem &, double t) override;
  // A branch's chambers follow its own scene from the next stage on (sealed or supplied), decided
  // as the commit of the increment that ended the base's stage does.
  PetscErrorCode Branched(Problem &P, double t) override { return Commit(P, t); }
  // The block State writes (TermCheckpointDatasets).
  static const TermDatasetInfo kCheckpoint;
  PetscErrorCode State(const Problem &, std::vector<TermData> *blocks) const override;
  PetscErrorCode Restore(Problem &, const std::vector<TermData> &blocks) override;
  PetscErrorCode Fields(const Problem &, std::vector<TermData> *fields) const override;
  TermSolverNeeds SolverNeeds() const override;
  PetscErrorCode Destroy(Problem &) override;
};

// Adds the chambers of P->scene as a term (nothing without them; after the pressure loads, which
// it reads); those sealed from stage 1 are sealed with the supplied pressure at load time 0.
// Refuses two chambers on the same side of one foil.
PetscErrorCode AddChamberTerm(Problem *P);
// Volumes and gauge pressures at the local displacement array u (owned and ghost nodes, the
// element loops' array). Collective.
PetscErrorCode ChamberEvaluate(Problem *P, const PetscScalar *u);
// The same at the vector U (its ghosts updated first): for reports between evaluations.
PetscErrorCode ChamberUpdate(Problem *P, Vec U);
// The pressure on a chamber's boundary load (sign times its gauge pressure).
double ChamberLoadPressure(const Problem *P, int chamber, double sign);
// The rank-one part of the tangent at u: the gradients into U, the stiffnesses into c. Collective.
PetscErrorCode ChamberTangent(Problem *P, const PetscScalar *u);
// After a converged increment ending at load time t: a chamber whose sealed stage starts at t is
// sealed with the gas it holds (volume now, supplied pressure at t); one sealed until t whose
// next stage is not is supplied again. Fails (PETSC_ERR_NOT_CONVERGED) where a chamber's volume is
// not positive, unless it is supplied and layer contact between its own foils keeps them apart
// (LayerContactKeepsApart): its foils have passed through each other. Collective.
PetscErrorCode ChamberCommit(Problem *P, double t);
// The committed state a checkpoint keeps: per chamber sealed (0/1) and amount (then, with sealing
// per stage, per chamber the release time and gauge).
void ChamberStateGet(const Problem *P, std::vector<double> *state);
void ChamberStateSet(Problem *P, const std::vector<double> &state);

} // namespace etfe
