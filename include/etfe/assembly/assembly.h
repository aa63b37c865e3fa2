// Assembly (assembly layer, src/assembly/): what is computed on a Problem. The residual and
// Jacobian are SNES callbacks with a Problem* context; the load time and the reactions are
// changed only through ProblemSetLoadTime and ProblemUpdateReactions.
#pragma once
#include <petscsnes.h>

#include <vector>

#include "etfe/assembly/problem.h"

namespace etfe {

// Sets the load time at which residual and Jacobian are evaluated and puts the prescribed
// values of that time into the constrained owned DOFs of U: the one place where either changes.
PetscErrorCode ProblemSetLoadTime(Problem *problem, double t, Vec U);
// Evaluates the residual at U (load time as set) for its side effects only: the reactions at
// the constrained DOFs (problem->reaction) and the force scale, as output and reports read them.
PetscErrorCode ProblemUpdateReactions(Problem *problem, Vec U);

PetscErrorCode FormResidual(SNES snes, Vec U, Vec F, void *ctx);
// The assembled tangent dR/dU (constrained rows and columns replaced by the identity); SNES
// solves with it plus the tangent shift (FormShiftedJacobian, tangent_shift.h).
PetscErrorCode FormJacobian(SNES snes, Vec U, Mat J, Mat P, void *ctx);
// What the problem's physics terms ask of the linear solver, over all of them (physics_terms.cpp).
TermSolverNeeds ProblemSolverNeeds(const Problem &problem);
// Whether a term's columns, fields or report read its last evaluation (PhysicsTerm::ReportsLastEvaluation):
// the residual is then evaluated at the state reported first (ProblemUpdateReactions).
bool TermsReportLastEvaluation(const Problem &problem);
// The checkpoint datasets of every term there is, whether a problem has it or not (the registry,
// physics_terms.cpp: each term's file gives its own): for reading a checkpoint without a problem.
const std::vector<TermDatasetInfo> &TermCheckpointDatasets();

// Viscous stabilization (stabilization.cpp), a physics term every problem has (any load history
// may need it): Begin makes the residual carry relative * E h0 * (U - anchor) on free DOFs and
// the tangent its diagonal, until End; MoveAnchor starts a proximal pass from U; Measure gives
// the force at U (StabilizingForce). AddStabilizationTerm: in the registry (MakePhysicsTerms).
PetscErrorCode AddStabilizationTerm(Problem *problem);
PetscErrorCode StabilizationBegin(Problem *problem, double relative, Vec anchor);
PetscErrorCode StabilizationMoveAnchor(Problem *problem, Vec U);
void StabilizationEnd(Problem *problem);
// The 2-norm of the stabilizing force at U (N).
PetscErrorCode StabilizationForceNorm(Problem *problem, Vec U, PetscReal *norm);
// The stabilizing force f at a converged state U, given the film's internal forces Fint at U:
// what the load stepper weighs to decide whether the state is an equilibrium. f is the out-of-
// balance force of the unstabilized equations there; g = Fint + f is what the film takes from
// outside (loads, contact, reactions), its nodal sizes summed are the forces in play. Collective.
struct StabilizingForce {
  double work = 0.0;                 // f . (U - anchor) [N mm]
  double norm = 0.0;                 // |f|_2 [N]
  double largest = 0.0;              // largest nodal |f| [N]
  PetscInt node = -1;                // its scene node id
  double position[3] = {0, 0, 0};    // that node's position at U [mm]
  double resultant[3] = {0, 0, 0};   // sum of f over the nodes [N]
  double moment[3] = {0, 0, 0};      // sum of (x - c) x f, c the nodes' centroid [N mm]
  double applied = 0.0;              // sum over the nodes of |g| [N]
  double applied_moment = 0.0;       // sum over the nodes of |x - c| |g| [N mm]
};
PetscErrorCode StabilizationMeasure(Problem *problem, Vec U, Vec Fint, StabilizingForce *force);
// The largest committed equivalent plastic strain, its element (natural id, -1 without a
// plastic law) and that element's reference centroid [mm] (collective).
PetscErrorCode LargestPlasticStrain(Problem *problem, double *value, PetscInt *element, double centroid[3]);
// The film's internal nodal forces at U with the committed history (the membrane part of the
// residual, constrained DOFs included): its work along an increment is the work done on the film.
PetscErrorCode FormInternalForce(Problem *problem, Vec U, Vec F);
// Checks a Newton trial W against the accepted iterate X: no element may flip its normal or
// collapse. Collective; *ok false names the element in problem->diagnostics.bad_element.
PetscErrorCode CheckStep(Problem *problem, Vec X, Vec W, PetscBool *ok);
// The largest relative change of an element edge an update Y would make to first order,
// max over edges |Y_a - Y_b| / |X_a - X_b| (reference edge lengths): the size of a Newton step in
// strain, the same on every mesh density (a nodal cap in mm is not). Collective.
PetscErrorCode LargestUpdateGradient(Problem *problem, Vec Y, PetscReal *gradient);
// Moves the reference configuration to the current one (X += U on owned and ghost nodes),
// rebuilds the element reference geometry and absorbs U into the constraint offsets. U is not
// changed; the caller zeroes it. Used by form finding's updated-reference iterations.
PetscErrorCode UpdateReference(Problem *problem, Vec U);
// Commits the material history at the converged U (history is updated only here).
PetscErrorCode CommitHistory(Problem *problem, Vec U);

// Per-element output fields at U, committed history: stress (3), strain (3), Mises, min
// principal stress, min principal strain, and (plastic laws) plastic strain (3) + equivalent.
struct CellFields {
  std::vector<double> stress, strain, mises, smin, emin, ep, ep_bar, area_ratio;
  // True stress (kernels/stress_measures.h): global tensor (6), its Mises, the in-plane principal
  // values (2: largest first) and their directions (3 each, global, current configuration).
  std::vector<double> cauchy, cauchy_mises, principal, dir1, dir2;
  std::vector<double> nodal_mises;  // per owned node, average of the elements around it
  // -membrane_wrinkling tension_field only (empty otherwise): state 0 taut / 1 wrinkled / 2 slack,
  // the wrinkle (= tension) direction as a global unit 3-vector in the current configuration (0
  // when not wrinkled) and the wrinkle strain, the GL strain lost to wrinkles (kernels/wrinkling.h).
  std::vector<double> wrinkle_state, wrinkle_dir, wrinkle_strain;
};
// with_true_stress: also the Cauchy fields (output and reports; per-increment probes skip them).
PetscErrorCode ComputeCellFields(Problem *problem, Vec U, CellFields *fields, bool with_true_stress = true);

// The unassembled tangent for domain decomposition (-mat_type is, PCBDDC; unassembled.cpp).
// UnassembledDefaultType: before MatSetFromOptions, the unassembled linear path (PC bddc,
// problem->linear_path) without -mat_type makes J a MATIS. UnassembledCheckType: after it, sets problem->unassembled and refuses bddc on an
// assembled matrix and MATIS with gas chambers. UnassembledMatrixSetUp: the local matrix over
// the rank's element nodes, exactly preallocated. UnassembledAddElement: one element block by
// local ids. UnassembledAddConstraintDiagonal: the constrained rows' unit diagonal, split over
// the subdomains sharing each node (after assembly).
PetscErrorCode UnassembledDefaultType(const Problem *problem);
PetscErrorCode UnassembledCheckType(Problem *problem);
PetscErrorCode UnassembledMatrixSetUp(Problem *problem);
PetscErrorCode UnassembledAddElement(Mat J, const int tri[3], const PetscScalar K[81]);
PetscErrorCode UnassembledAddConstraintDiagonal(Problem *problem, Mat J);
PetscErrorCode UnassembledDestroy(Problem *problem);

// U with its ghost values as one local array (owned nodes, then ghosts), read-only, through the
// ghosted vector `ghosted` (U itself, or a ghosted copy of its layout); every element loop starts
// with it. Collective (the ghost update). Pair with RestoreLocalArray.
PetscErrorCode GetLocalArray(Vec U, Vec ghosted, Vec *local, const PetscScalar **a);
PetscErrorCode RestoreLocalArray(Vec ghosted, Vec *local, const PetscScalar **a);

// Largest nodal (3-vector) norm of a block-3 vector (collective).
PetscErrorCode VecMaxNodalNorm(Vec v, PetscReal *max);
// Collective look-ups by scene (natural) id, for scene reports and probes: current position
// X + U (U null: the reference position X), displacement.
PetscErrorCode ProblemGetNodePosition(Problem *problem, Vec U, PetscInt node, double x[3]);
PetscErrorCode ProblemGetNodeDisplacement(Problem *problem, Vec U, PetscInt node, double u[3]);
// Collective look-ups on the distributed mesh for a scene observer's setup, in plan (X, Y of the
// reference coordinates): the scene id of the nearest node, of the element whose centroid is
// nearest (the lowest id among equals, as a scan of the global mesh finds), and every scene id
// of a named node set, ascending, on every rank (an unknown name is an error naming it).
PetscErrorCode ProblemNearestNode(Problem *problem, double x, double y, PetscInt *node);
PetscErrorCode ProblemNearestElement(Problem *problem, double x, double y, PetscInt *element);
PetscErrorCode ProblemNodeSetIds(Problem *problem, const char *name, std::vector<PetscInt> *ids);
// Per local node (owned and ghost): 1 in the named node set, else 0 (not collective).
PetscErrorCode ProblemNodeSetFlags(Problem *problem, const char *name, std::vector<char> *flags);

} // namespace etfe
