// The distributed problem (assembly layer): the local part of the mesh with its ghosts, the
// DOF layout (block size 3), the physics the scene described (material, pressure, constraints,
// contact), the load time and the vectors and matrix assembled from them. Built from a
// SceneSpec by ProblemCreate (src/assembly/problem.cpp); what is computed on it is in
// assembly.h.
#pragma once
#include <petscmat.h>

#include <cstdint>
#include <memory>
#include <vector>

#include "etfe/assembly/element_blocks.h"
#include "etfe/assembly/linear_path.h"
#include "etfe/material/material.h"
#include "etfe/mesh/local_mesh.h"
#include "etfe/assembly/physics_term.h"
#include "etfe/description/scene.h"
#include "etfe/assembly/solve_diagnostics.h"
#include "etfe/description/stage_clock.h"

namespace etfe {

struct Problem;

// What the scene that made the problem watches of a run: its report after the last increment,
// a monitor after every converged increment, and monitor state that a restart must restore
// (rank-independent). The scene's builder fills it (scenes layer), the app hands it to the
// problem, which owns ctx; the load stepper, the checkpoint and the app call it (collective).
// The builder sees the global mesh on rank 0 only: what the observer needs of the mesh (probe
// nodes and elements, node lists) it finds in setup, on the distributed problem.
struct SceneObserver {
  PetscErrorCode (*setup)(Problem *, void *ctx) = nullptr;
  PetscErrorCode (*report)(Problem *, void *ctx) = nullptr;
  // print_every: the load stepper's -load_monitor (0: quiet), so a monitor's lines thin alike.
  PetscErrorCode (*step_monitor)(Problem *, void *ctx, PetscInt step, double time, PetscInt print_every) = nullptr;
  void (*state_get)(void *ctx, std::vector<double> *state) = nullptr;
  void (*state_set)(void *ctx, const std::vector<double> &state) = nullptr;
  void (*destroy)(void *ctx) = nullptr;
  void *ctx = nullptr;
  // The results file without its extension, set by the app once it is open ("" without results):
  // a scene's own CSV histories go beside it.
  std::string results_stem;
};
// Frees ctx and clears the observer.
void SceneObserverDestroy(SceneObserver *observer);

struct Problem {
  MPI_Comm comm;
  PetscMPIInt rank = 0, size = 1;
  // The scene as built. Its global mesh and lists exist on rank 0 only (the reader), which
  // sends each rank its share (`mesh` and the lists below); a load history then drops them at
  // once (ProblemReleaseScene). The small fields (name, schedules, supports, ...) are on every rank.
  SceneSpec scene;
  bool scene_released = false;
  // Of the global description, the same on every rank (CheckpointFingerprintScene): the mesh,
  // and the state of the physics hash after the scene's part, for a restart's comparison.
  std::uint64_t scene_mesh_fingerprint = 0, scene_physics_state = 0;
  // Per stage end k = 0..stages: the state of a hash of the scene's physics with its loads up to
  // load time k only (LoadPathStates), which a branch restart (-restart_branch) compares.
  std::vector<std::uint64_t> load_path_states;
  bool has_initial_guess = false;            // the scene gave an initial displacement
  std::vector<double> element_stress_ratio;  // form finding: MD:TD per local element (empty: uniform)
  SceneObserver observer;
  LocalMesh mesh;
  double thickness = 0.25;  // mm
  // Per local element where the film's parts differ in thickness (empty: `thickness` everywhere).
  std::vector<double> element_thickness;
  double Thickness(PetscInt e) const { return element_thickness.empty() ? thickness : element_thickness[e]; }
  double min_area_ratio = 1e-4;
  // -membrane_tangent_shift: a tangent-only diagonal shift relative to E h (dimensionless); the
  // solver layer adds TangentShiftAbsolute() N/mm, scaled per Newton iteration when adaptive
  // (tangent_shift.h).
  double tangent_shift = 0.0;
  PetscBool tangent_shift_adaptive = PETSC_FALSE;  // shift x |F_k|/|F_0| (vanishes at convergence)
  // E h0 [N/mm]: the film's axial stiffness, the scale relative shifts and penalties are given in.
  double AxialStiffness() const {
    double young = 0.0, nu = 0.0;
    material->ElasticConstants(&young, &nu);
    return young * thickness;
  }
  double TangentShiftAbsolute() const { return tangent_shift * AxialStiffness(); }  // N/mm
  PetscBool tangent_tension_only = PETSC_FALSE;  // geometric stiffness from the tensile stress only
  PetscBool wrinkling = PETSC_FALSE;  // -membrane_wrinkling tension_field: the law is wrapped (material.h)
  PetscBool near_null_space = PETSC_FALSE;  // rigid-body modes attached to J (AMG preconditioners)
  // The linear solver path, decided before the problem is built (linear_path.h): the matrix
  // format, the memory check and the solver set-up read it.
  LinearPath linear_path;
  // J is unassembled (MATIS, -mat_type is: domain decomposition); constraint_unit: 1 at the owned
  // constrained DOFs, their diagonal (unassembled.cpp).
  PetscBool unassembled = PETSC_FALSE;
  Vec constraint_unit = nullptr;
  std::unique_ptr<Material> material;  // the film's law (-material_*)
  // The surface groups' own laws (-film_<group>_material_*, in the order of the scene's
  // material_prefixes; set before ProblemCreate), and per local element which law it takes: 0
  // `material`, k part_materials[k-1]. Both empty where the film has one law.
  std::vector<std::unique_ptr<Material>> part_materials;
  std::vector<int> element_material;
  const Material &MaterialOf(PetscInt e) const {
    return element_material.empty() || element_material[e] == 0 ? *material : *part_materials[element_material[e] - 1];
  }
  // Every law the elements use (the film's first): for what is set or asked of all of them.
  std::vector<Material *> Materials() const {
    std::vector<Material *> all{material.get()};
    for (const auto &m : part_materials) all.push_back(m.get());
    return all;
  }
  bool HasPlasticStrain() const {
    for (const Material *m : Materials())
      if (m->HasPlasticStrain()) return true;
    return false;
  }
  // Doubles of history per element: the largest HistorySize() of the laws (an element's law uses
  // the first of its own); 0: no history arrays.
  int history_size = 0;
  std::vector<double> history;        // committed history, history_size per local element
  std::vector<double> history_trial;  // scratch for the commit pass

  // Constraints on local DOFs (owned and ghost): the element loops drop their rows/columns.
  std::vector<char> dof_constrained;   // per local DOF
  std::vector<char> element_constrained;    // per local element: has a constrained DOF
  std::vector<PetscInt> element_global;     // per local element: PETSc block ids of its nodes
  ElementBlockMap element_blocks;           // where those blocks sit in a one-rank BAIJ matrix
  std::vector<PetscInt> con_owned_dof; // owned constrained DOFs (local index < 3*num_owned)
  std::vector<ScheduledValue> con_owned_value;
  // Prescribed displacement already absorbed into the reference (form finding moves the
  // reference to the current shape; the prescribed value is then measured from there).
  std::vector<double> con_owned_offset;

  // What acts on the film besides its elements and the constraints (physics_term.h): follower
  // pressure, gas chambers, nodal forces, rigid contact, the viscous stabilization, layer
  // contact; only those the scene uses, created by MakePhysicsTerms (physics_terms.cpp) in the
  // order their forces are summed; the cables last.
  PhysicsTermList terms;

  // Seconds of physical time at each load time (-load_stage_duration, -load_hold_*; stage_clock.h).
  StageClock clock;
  // Load time at which residual and Jacobian are evaluated; set with ProblemSetLoadTime only, so
  // that the prescribed values of the iterate always belong to it.
  double time = 0.0;

  ISLocalToGlobalMapping l2g = nullptr;  // block mapping, local node -> PETSc node id
  Vec U = nullptr;        // solution (ghosted, block size 3)
  Vec U_work = nullptr;   // ghosted scratch for residual/Jacobian evaluation
  Vec F_work = nullptr;   // ghosted residual accumulator
  Vec reaction = nullptr; // internal force at constrained DOFs after the last residual
  Mat J = nullptr;

  // What the last evaluations and solves left for their readers (element failures, force scale,
  // tangent shift, increment work): not part of the model.
  SolveDiagnostics diagnostics;

  PetscInt NumDofsLocal() const { return 3 * mesh.NumLocal(); }
};

// Distributes the scene (rank 0's global description: local_mesh.h, scene_share.h), builds
// vectors, the preallocated matrix and the local constraint/pressure/force lists, and puts U at
// the prescribed values of load time 0. Unless keep_scene, rank 0's global description is
// dropped as soon as it is distributed (ProblemReleaseScene); form finding keeps it. The surface
// groups' own laws are in problem->part_materials already (one per scene.material_prefixes).
PetscErrorCode ProblemCreate(MPI_Comm comm, SceneSpec &&scene, std::unique_ptr<Material> material, bool keep_scene,
                             Problem *problem);
// The membrane element's options (-membrane_*: thickness, collapse ratio, tangent shift and
// tension-only tangent, near-null space, wrinkling model) into problem, whose values are the
// defaults; read before ProblemCreate (src/assembly/membrane_options.cpp).
PetscErrorCode MembraneOptionsFromCommandLine(MPI_Comm comm, Problem *problem);
// Frees the scene's global description on rank 0 (mesh, constraints, forces, pressure elements,
// initial guess, element ratios and stress-free shapes: O(global mesh)); every small field stays.
// A form-finding run keeps it (rank 0 writes the found shape with the scene's topology and cuts
// its patterns).
PetscErrorCode ProblemReleaseScene(Problem *problem);
PetscErrorCode ProblemDestroy(Problem *problem);

// The problem's term of type T (nullptr: the scene does not use it): for code that reads one
// term's own data (a scene's report of contact forces, the chambers' pressure on their loads).
template <class T> T *FindTerm(const Problem &problem) {
  for (const auto &term : problem.terms)
    if (auto *t = dynamic_cast<T *>(term.get())) return t;
  return nullptr;
}

} // namespace etfe
