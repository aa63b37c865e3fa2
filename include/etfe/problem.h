// The distributed problem: the local part of the mesh with its ghosts, the DOF layout (block
// size 3), the physics the scene named (material, pressure, constraints) and the vectors and
// matrix assembled from them. Built from a SceneSpec by ProblemCreate (src/mesh/distribute.cpp).
#pragma once
#include <petscsnes.h>

#include <memory>
#include <string>
#include <vector>

#include "etfe/contact.h"
#include "etfe/kernels/membrane.h"
#include "etfe/material.h"
#include "etfe/scene.h"

namespace etfe {

struct LocalMesh {
  PetscInt num_nodes_global = 0, num_elements_global = 0;
  PetscInt num_owned = 0, num_ghost = 0;  // local nodes: owned first, then ghosts
  PetscInt owned_start = 0;               // PETSc (global) id of the first owned node
  std::vector<PetscInt> global_id;        // per local node: PETSc id
  std::vector<PetscInt> natural_id;       // per local node: id in the scene's mesh
  std::vector<double> X;                  // reference coordinates, 3 per local node
  PetscInt num_elements = 0;              // local elements (this rank's METIS part)
  PetscInt element_start = 0;             // PETSc-order id of the first local element
  std::vector<int> tri;                   // local node ids, 3 per local element
  std::vector<PetscInt> element_natural;  // per local element: id in the scene's mesh
  std::vector<MembraneReference> ref;     // reference geometry per local element
  PetscInt NumLocal() const { return num_owned + num_ghost; }
};

struct Problem {
  MPI_Comm comm;
  PetscMPIInt rank = 0, size = 1;
  SceneSpec scene;
  LocalMesh mesh;
  double thickness = 0.25;  // mm
  double min_area_ratio = 1e-4;
  double tangent_shift = 0.0;
  PetscBool tangent_shift_adaptive = PETSC_FALSE;  // shift x |F_k|/|F_0| (vanishes at convergence)
  double shift_fnorm0 = 0.0;
  PetscBool tangent_tension_only = PETSC_FALSE;  // geometric stiffness from the tensile stress only  // N/mm added to the tangent's diagonal (-membrane_tangent_shift x E h)
  std::unique_ptr<Material> material;
  std::vector<double> history;        // committed history, HistorySize() per local element
  std::vector<double> history_trial;  // scratch for the commit pass

  // Constraints on local DOFs (owned and ghost): the element loops drop their rows/columns.
  std::vector<char> dof_constrained;   // per local DOF
  std::vector<char> element_constrained;    // per local element: has a constrained DOF
  std::vector<PetscInt> element_global;     // per local element: PETSc block ids of its nodes
  std::vector<PetscInt> con_owned_dof; // owned constrained DOFs (local index < 3*num_owned)
  std::vector<ScheduledValue> con_owned_value;
  // Prescribed displacement already absorbed into the reference (form finding moves the
  // reference to the current shape; the prescribed value is then measured from there).
  std::vector<double> con_owned_offset;

  // Pressure (only when the scene has it)
  bool has_pressure = false;
  std::vector<PetscInt> pressure_elements;  // local element ids
  ScheduledValue pressure_value;

  // Dead nodal forces on owned DOFs (only when the scene has them).
  std::vector<PetscInt> force_owned_dof;
  std::vector<ScheduledValue> force_owned_value;

  // Contact with rigid supports (nullptr when the scene has none).
  ContactSet *contact = nullptr;

  double time = 0.0;  // load time at which residual and Jacobian are evaluated
  // Size of the forces in play at the last residual (reactions and external loads) [N]: the
  // scale for the force-balance convergence test (-load_force_rtol).
  double force_scale = 0.0;

  ISLocalToGlobalMapping l2g = nullptr;  // block mapping, local node -> PETSc node id
  Vec U = nullptr;        // solution (ghosted, block size 3)
  Vec U_work = nullptr;   // ghosted scratch for residual/Jacobian evaluation
  Vec F_work = nullptr;   // ghosted residual accumulator
  Vec reaction = nullptr; // internal force at constrained DOFs after the last residual
  Mat J = nullptr;

  // What went wrong in the last evaluation (for messages): element natural id and status.
  PetscInt bad_element = -1;
  int bad_status = 0;
  // While the line search evaluates trial points it handles domain errors itself, so the
  // residual does not flag them to SNES (the flag would outlive the refused trial).
  PetscBool in_linesearch = PETSC_FALSE;

  PetscInt NumDofsLocal() const { return 3 * mesh.NumLocal(); }
};

// Distributes the scene's mesh (METIS on rank 0), builds local numbering, vectors, the
// preallocated matrix and the local constraint/pressure lists.
PetscErrorCode ProblemCreate(MPI_Comm comm, SceneSpec &&scene, std::unique_ptr<Material> material,
                             Problem *problem);
PetscErrorCode ProblemDestroy(Problem *problem);

// Assembly (src/assembly/assemble.cpp): SNES callbacks with a Problem* context.
PetscErrorCode FormResidual(SNES snes, Vec U, Vec F, void *ctx);
PetscErrorCode FormJacobian(SNES snes, Vec U, Mat J, Mat P, void *ctx);
// Puts the prescribed values at load time t into the constrained owned DOFs of U.
PetscErrorCode ApplyConstraints(Problem *problem, double t, Vec U);
// Checks a Newton trial W against the accepted iterate X: no element may flip its normal or
// collapse. Collective; *ok false names the element in problem->bad_element.
PetscErrorCode CheckStep(Problem *problem, Vec X, Vec W, PetscBool *ok);
// Moves the reference configuration to the current one (X += U on owned and ghost nodes),
// rebuilds the element reference geometry and absorbs U into the constraint offsets. U is not
// changed; the caller zeroes it. Used by form finding's updated-reference iterations.
PetscErrorCode UpdateReference(Problem *problem, Vec U);
// Largest nodal (3-vector) norm of a block-3 vector (collective).
PetscErrorCode VecMaxNodalNorm(Vec v, PetscReal *max);
// Current position X + U of a scene node (collective).
PetscErrorCode ProblemGetNodePosition(Problem *problem, Vec U, PetscInt node, double x[3]);
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
};
PetscErrorCode ComputeCellFields(Problem *problem, Vec U, CellFields *fields);

// Collective look-ups by scene (natural) id, for scene reports and probes.
PetscErrorCode ProblemGetNodeDisplacement(Problem *problem, Vec U, PetscInt node, double u[3]);

} // namespace etfe
