// A physics term: one thing besides the membrane elements that adds forces and stiffness to the
// problem and may keep state of its own (rigid contact, gas chambers, layer contact, follower
// pressure, stabilization, cables, ...). Problem holds the terms a scene needs in one list
// (Problem::terms); the residual, the Jacobian, the commit, the checkpoint, the progress lines,
// the results file and the solver set-up each visit that list in one loop, so a new term is one
// file plus one line in the registry that creates the terms (MakePhysicsTerms). A scene that does
// not use a term never creates it: nothing of it runs or allocates.
//
// Every method has a default that does nothing, so a term implements only what it has. All of
// them are collective on the problem's communicator unless they say otherwise.
#pragma once
#include <petscmat.h>

#include <memory>
#include <string>
#include <vector>

#include "etfe/base/layout.h"

namespace etfe {

struct Problem;
class Fnv64;

// A block of a term's committed state for the checkpoint (or of its values for the results
// file): rows per owned node / element / contact pair in PETSc order (written in the scene's
// order), or with `replicated` the same values on every rank (written once).
struct TermData {
  std::string name;  // dataset name, unique among the terms ("chamber_state", "cable_force", ...)
  Layout layout = Layout::Nodes;
  bool replicated = false;
  int components = 1;
  std::vector<double> values;  // rows x components (replicated: any length, components = 1)
  const char *units = "1";     // for result fields
  const char *description = "";
};

// A dataset a term may write into the checkpoint (what its State gives, without the values): the
// checkpoint's integrity check, which has no problem, reads the file by this list
// (TermCheckpointDatasets, assembly.h). Rows by layout as in TermData (Nodes, Cells or Pairs, or
// replicated); a Layout::Pairs dataset is
// in every checkpoint that has pairs (only a term numbers them), any other only with its term.
struct TermDatasetInfo {
  const char *name;
  Layout layout = Layout::Nodes;
  bool replicated = false;
  int components = 1;

  // A block of this dataset holding values (what a term's State gives).
  TermData Block(std::vector<double> values) const {
    TermData d;
    d.name = name, d.layout = layout, d.replicated = replicated, d.components = components;
    d.values = std::move(values);
    return d;
  }
  // This dataset's values among the blocks a checkpoint gave back (nullptr: not there).
  const std::vector<double> *Find(const std::vector<TermData> &blocks) const {
    for (const TermData &d : blocks)
      if (d.name == name) return &d.values;
    return nullptr;
  }
};

// What a term asks of the linear solver.
struct TermSolverNeeds {
  // The term's tangent is not in the assembled matrix alone (a rank-one or low-rank part, a
  // sliding cable's or a sealed chamber's): the outer solve must be a Krylov method around the
  // assembled part's preconditioner.
  bool krylov_outer = false;
  // Penalties that delay pivots: MUMPS needs more workspace than its default.
  bool penalty = false;
  // With krylov_outer: Newton's matrix, the assembled tangent plus the term's part (the problem's
  // J is its preconditioning matrix); nullptr: J itself.
  Mat outer = nullptr;
};

// A progress column (the load stepper's increment lines and the history CSV).
struct TermColumn {
  std::string name, unit;
  double value = 0.0;
};

class PhysicsTerm {
public:
  virtual ~PhysicsTerm() = default;
  virtual const char *Name() const = 0;

  // After ProblemCreate has distributed the mesh and the constraints: allocate what the term
  // needs on this problem.
  virtual PetscErrorCode SetUp(Problem &) { return 0; }

  // Before the element loop of each residual and Jacobian, with the local (ghosted) displacement
  // u (3 per local node): what other terms and the pressure loads read (chamber volumes).
  virtual PetscErrorCode Prepare(Problem &, const PetscScalar * /*u*/) { return 0; }

  // Residual, local part: forces added into the local (ghosted) array f, 3 per local node, before
  // the ghosts are summed into their owners. *status: the worst KernelStatus met (kernels.h);
  // *external2: add the squares of external loads the term applies (the force scale).
  virtual PetscErrorCode AddLocalForces(Problem &, const PetscScalar * /*u*/, PetscScalar * /*f*/, int * /*status*/,
                                        double * /*external2*/) {
    return 0;
  }
  // The term's internal (elastic) forces alone at the local displacement u, into the local array
  // f, without the loads it applies: FormInternalForce (the increment work, the equilibrium check
  // of stabilized increments) counts them with the film's. A term that is a load adds nothing.
  virtual PetscErrorCode AddInternalForces(Problem &, const PetscScalar * /*u*/, PetscScalar * /*f*/) { return 0; }
  // Residual, global part: after the ghost sum, into the global residual F at the state U.
  virtual PetscErrorCode AddGlobalForces(Problem &, Vec /*U*/, Vec /*F*/) { return 0; }

  // Jacobian into the matrix A before its final assembly (MatSetValues*Local or blocked global
  // ids, ADD_VALUES), rows and columns of constrained DOFs left out. u: local displacement.
  virtual PetscErrorCode AddTangent(Problem &, Vec /*U*/, const PetscScalar * /*u*/, Mat /*A*/) { return 0; }
  // After A's final assembly (a diagonal added with MatDiagonalSet, a low-rank update).
  virtual PetscErrorCode AddAssembledTangent(Problem &, Mat /*A*/) { return 0; }

  // The load stepper: an increment begins from the committed state (t0 -> t1); a converged
  // increment is committed at time t.
  virtual PetscErrorCode BeginIncrement(Problem &, double /*t0*/, double /*t1*/) { return 0; }
  virtual PetscErrorCode Commit(Problem &, double /*t*/) { return 0; }

  // Committed state for the checkpoint; Restore gets back the blocks State gave (same names,
  // layouts and sizes) and sets the term as it was at the commit.
  virtual PetscErrorCode State(const Problem &, std::vector<TermData> * /*blocks*/) const { return 0; }
  virtual PetscErrorCode Restore(Problem &, const std::vector<TermData> & /*blocks*/) { return 0; }

  // What a run reports of the term: columns of the increment lines and the history CSV, fields
  // of the results file (per step), and the lines of the end-of-run report.
  virtual PetscErrorCode Columns(const Problem &, std::vector<TermColumn> * /*columns*/) const { return 0; }
  virtual PetscErrorCode Fields(const Problem &, std::vector<TermData> * /*fields*/) const { return 0; }
  virtual PetscErrorCode Report(const Problem &, std::vector<std::string> * /*lines*/) const { return 0; }

  // The run's set-up report (after the solver's lines): the term's lines, without their indent
  // or newline, as rank 0 prints them (formatted with PetscSNPrintf, as PetscPrintf would).
  virtual PetscErrorCode SetupLines(const Problem &, std::vector<std::string> * /*lines*/) const { return 0; }
  // A converged increment, committed: the term's part of the progress line (from its two leading
  // spaces; "": none). Called after every commit; printed: the line is printed now, so a term may
  // sum what happened since the last printed line (contact's lift-offs) and start again.
  virtual std::string Progress(bool /*printed*/) { return ""; }
  // A converged increment, committed: the term's own files beside the results (stem: theirs).
  virtual PetscErrorCode IncrementOutput(Problem &, const std::string & /*stem*/, PetscInt /*step*/, double /*t*/) {
    return 0;
  }
  // An increment's Newton solve found no step along its direction and no element problem: what
  // the term knows may cause it and the way out (its penalties far stiffer than the film); "": nothing.
  virtual std::string LineSearchHint(const Problem &) const { return ""; }
  // The DOF constraints leave rigid motions free: what of the term may hold them ("the rigid
  // contact supports"; the check then only says so); nullptr: nothing.
  virtual const char *RigidMotionHolder() const { return nullptr; }

  virtual TermSolverNeeds SolverNeeds() const { return {}; }
  // Its Columns, Fields and Report read what its last evaluation left (the cables' segment
  // forces): the reader evaluates the residual at the state it reports first.
  virtual bool ReportsLastEvaluation() const { return false; }

  // Frees what the term holds of PETSc (before the problem's vectors and matrix are destroyed:
  // a term's matrix may hold a reference to the problem's).
  virtual PetscErrorCode Destroy(Problem &) { return 0; }

  // Jacobian, inside the element loop: a follower pressure per local element (added into
  // pressure, num_elements long, allocated by the first term that has one) whose load stiffness
  // the membrane element adds to its own tangent before the element is assembled.
  virtual PetscErrorCode AddElementPressure(Problem &, std::vector<double> * /*pressure*/) { return 0; }

  // A restart has set the committed state (U and the load time of the checkpoint): what the term
  // derives from the state after a commit, derived again (layer contact's pairs).
  virtual PetscErrorCode Restarted(Problem &) { return 0; }
  // After every term's Restarted, when the restart is a branch (its own loads from the
  // checkpoint's stage end on, time t): what the term decides at a stage end from the scene,
  // decided again from the branch's scene (which chambers are sealed).
  virtual PetscErrorCode Branched(Problem &, double /*t*/) { return 0; }

  // A term whose commit revises a state the solve held fixed (the lagged friction law's
  // statuses) may have a converged increment solved again, at most RepeatLimit() times (0:
  // never). BeginRepeats: the increment's start state is the committed one. Revise: *changed,
  // over all ranks, the parts revised for the next solve (0: settled). UndoRevise: back to the
  // state the last converged solve used (a repeat failed).
  virtual PetscInt RepeatLimit() const { return 0; }
  virtual PetscErrorCode BeginRepeats(Problem &) { return 0; }
  virtual PetscErrorCode Revise(Problem &, PetscInt *changed) {
    *changed = 0;
    return 0;
  }
  virtual PetscErrorCode UndoRevise(Problem &) { return 0; }

  // The convergence test's force tolerance: the round-off floor [N] below which the term's forces
  // cannot balance at the iterate X (a penalty's); *floor is raised to it, never lowered. fnorm,
  // tol: the residual and the tolerance the test holds it to (a floor too large a part of the
  // forces to check an answer against is an error).
  virtual PetscErrorCode ForceFloor(Problem &, Vec /*X*/, double /*fnorm*/, double /*tol*/, double * /*floor*/) {
    return 0;
  }

  // What a restart must agree on with its checkpoint, beyond the scene (parameters read from the
  // options): added to the physics fingerprint.
  virtual void Fingerprint(Fnv64 &) const {}

  // The rows of Layout::Pairs datasets this term numbers (global count, this rank's first row
  // and, per local row, its global id): contact pairs. False: the term has none.
  virtual bool PairRows(PetscInt * /*num_global*/, PetscInt * /*first*/, std::vector<PetscInt> * /*ids*/) const {
    return false;
  }
};

using PhysicsTermList = std::vector<std::unique_ptr<PhysicsTerm>>;

} // namespace etfe
