// Gas chambers as a component of the problem (assembly layer, src/assembly/chamber.cpp): exists
// only when the scene has chambers (SceneSpec::chambers); without them nothing here is allocated
// or run. Each chamber's volume and gauge pressure are evaluated at every residual (collective:
// one reduction), the pressure acting on its boundary's pressure loads (Problem::pressures with
// its index). A chamber that can be sealed adds the rank-one stiffness (kappa p_abs / V) g g^T to
// the tangent without densifying the sparse matrix: Newton solves with J = A + U diag(c) U^T
// (MATLRC, U the chambers' volume gradients g) preconditioned by the factored sparse A, which
// GMRES inverts exactly in (chambers + 1) iterations.
#pragma once
#include <petscmat.h>

#include <vector>

namespace etfe {

struct Problem;

struct ChamberSet {
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
};

// Creates the chambers of P->scene (after ProblemCreate); those sealed from stage 1 are sealed
// with the supplied pressure at load time 0. Refuses two chambers on the same side of one foil.
PetscErrorCode ChamberCreate(Problem *P);
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
PetscErrorCode ChamberDestroy(Problem *P);
// The committed state a checkpoint keeps: per chamber sealed (0/1) and amount (then, with sealing
// per stage, per chamber the release time and gauge).
void ChamberStateGet(const Problem *P, std::vector<double> *state);
void ChamberStateSet(Problem *P, const std::vector<double> &state);

} // namespace etfe
