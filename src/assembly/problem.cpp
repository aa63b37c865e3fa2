// The Problem built from a scene description: the local mesh and this rank's share of the
// scene's lists (scene_share.cpp, sent by rank 0, the only rank that holds the global
// description), the history the material keeps, the constraints and loads on local DOFs,
// vectors and the exactly preallocated matrix.
#include <petscsnes.h>
#ifdef __GLIBC__
#include <malloc.h>
#endif

#include <algorithm>
#include <cmath>
#include <string>

#include "etfe/assembly/assembly.h"
#include "etfe/base/gather.h"
#include "physics_terms.h"
#include "scene_share.h"

namespace etfe {

static PetscErrorCode CreateMatrix(Problem *P, const std::vector<PetscInt> &d_nnz, const std::vector<PetscInt> &o_nnz) {
  const PetscInt n = P->mesh.num_owned;
  PetscFunctionBeginUser;
  PetscCall(MatCreate(P->comm, &P->J));
  PetscCall(MatSetSizes(P->J, 3 * n, 3 * n, PETSC_DETERMINE, PETSC_DETERMINE));
  PetscCall(MatSetBlockSize(P->J, 3));
  // 3x3 blocks: insertion ~3x faster than AIJ here. Contact between film layers adds nonzeros
  // as it starts, which PETSc 3.18's MUMPS interface mishandles for parallel BAIJ (heap corruption
  // on 2 ranks): AIJ then.
  PetscBool layers = PETSC_FALSE;
  PetscCall(PetscOptionsHasName(nullptr, nullptr, "-layer_contact", &layers));
  PetscCall(MatSetType(P->J, layers ? MATAIJ : MATBAIJ));
  PetscCall(MatSetOptionsPrefix(P->J, nullptr));
  PetscCall(UnassembledDefaultType(P));
  PetscCall(MatSetFromOptions(P->J));
  PetscCall(UnassembledCheckType(P));
  if (P->unassembled) {
    PetscCall(UnassembledMatrixSetUp(P));
  } else {
    PetscCall(MatXAIJSetPreallocation(P->J, 3, d_nnz.data(), o_nnz.data(), nullptr, nullptr));
    PetscCall(MatSetLocalToGlobalMapping(P->J, P->l2g, P->l2g));
  }
  // A new nonzero would mean a wrong preallocation: make it a hard error, never a malloc.
  PetscCall(MatSetOption(P->J, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_TRUE));
  // The follower pressure's load stiffness is not symmetric.
  PetscCall(MatSetOption(P->J, MAT_SYMMETRIC, P->scene.pressures.empty() ? PETSC_TRUE : PETSC_FALSE));
  PetscFunctionReturn(0);
}

// AMG (GAMG) builds its coarse spaces from the near-null space; without one it takes the 3
// translations per node, and a membrane's rotations then look like high-energy modes to it.
static PetscErrorCode SetRigidBodyNearNullSpace(Problem *P) {
  const LocalMesh &m = P->mesh;
  Vec coords;
  PetscScalar *c;
  MatNullSpace nsp;
  PetscFunctionBeginUser;
  PetscCall(VecCreateMPI(P->comm, 3 * m.num_owned, PETSC_DETERMINE, &coords));
  PetscCall(VecSetBlockSize(coords, 3));
  PetscCall(VecGetArray(coords, &c));
  for (PetscInt i = 0; i < 3 * m.num_owned; ++i) c[i] = m.X[i];  // owned nodes come first
  PetscCall(VecRestoreArray(coords, &c));
  PetscCall(MatNullSpaceCreateRigidBody(coords, &nsp));
  PetscCall(MatSetNearNullSpace(P->J, nsp));
  PetscCall(MatNullSpaceDestroy(&nsp));
  PetscCall(VecDestroy(&coords));
  PetscFunctionReturn(0);
}

PetscErrorCode ProblemCreate(MPI_Comm comm, SceneSpec &&scene, std::unique_ptr<Material> material, bool keep_scene,
                             Problem *P) {
  PetscFunctionBeginUser;
  P->comm = comm;
  PetscCallMPI(MPI_Comm_rank(comm, &P->rank));
  PetscCallMPI(MPI_Comm_size(comm, &P->size));
  P->scene = std::move(scene);
  P->material = std::move(material);
  LocalMesh &m = P->mesh;
  SceneShare share;
  PetscCall(SceneDistribute(comm, P->scene, &m, &share));
  int guess = P->scene.initial_guess.empty() ? 0 : 1;
  PetscCallMPI(MPI_Bcast(&guess, 1, MPI_INT, 0, comm));
  P->has_initial_guess = guess;
  // From here on each rank works on its share: rank 0's global description goes before the
  // matrix and the factors are made.
  if (!keep_scene) PetscCall(ProblemReleaseScene(P));
  m.md = std::move(share.element_md);
  P->element_thickness = std::move(share.element_thickness);
  for (double &h : P->element_thickness)
    if (h == 0.0) h = P->thickness;  // an element no part gave a thickness: the film's
  PetscCall(LocalMeshBuildReference(comm, P->scene.md_axis, share.element_reference, &m));
  std::vector<double>().swap(share.element_reference);
  const PetscInt nl = m.NumLocal();
  P->element_stress_ratio = std::move(share.element_stress_ratio);

  PetscCheck(P->part_materials.size() == P->scene.material_prefixes.size(), comm, PETSC_ERR_PLIB,
             "the scene names %zu surface groups with their own law but %zu laws were made",
             P->scene.material_prefixes.size(), P->part_materials.size());
  P->element_material = std::move(share.element_material);
  // History only when a law has one: as many doubles per element as the largest keeps.
  int nh = 0;
  for (const Material *law : P->Materials()) {
    // The element loops keep a trial history on the stack (kMaxHistorySize doubles).
    PetscCheck(law->HistorySize() <= kMaxHistorySize, comm, PETSC_ERR_SUP,
               "material %s keeps %d history values per element; at most %d are supported", law->Name(),
               law->HistorySize(), kMaxHistorySize);
    nh = std::max(nh, law->HistorySize());
  }
  P->history_size = nh;
  if (nh > 0) {
    P->history.resize((size_t)nh * m.num_elements);
    P->history_trial.resize((size_t)nh * m.num_elements);
    for (PetscInt e = 0; e < m.num_elements; ++e) P->MaterialOf(e).InitHistory(&P->history[nh * e]);
  }

  // Constraints: every local DOF (owned or ghost) knows whether it is constrained.
  P->dof_constrained.assign(3 * nl, 0);
  for (const DofConstraint &c : share.constraints) {
    const PetscInt l = c.node, dof = 3 * l + c.comp;
    if (l < m.num_owned && !P->dof_constrained[dof]) {
      P->con_owned_dof.push_back(dof);
      P->con_owned_value.push_back(c.value);
      P->con_owned_offset.push_back(0.0);
    } else if (l < m.num_owned) {  // a later constraint on the same DOF wins
      for (size_t k = 0; k < P->con_owned_dof.size(); ++k)
        if (P->con_owned_dof[k] == dof) P->con_owned_value[k] = c.value;
    }
    P->dof_constrained[dof] = 1;
  }

  P->element_constrained.assign(m.num_elements, 0);
  P->element_global.resize(3 * m.num_elements);
  for (PetscInt e = 0; e < m.num_elements; ++e)
    for (int a = 0; a < 3; ++a) {
      const int l = m.tri[3 * e + a];
      P->element_global[3 * e + a] = m.global_id[l];
      for (int i = 0; i < 3; ++i) P->element_constrained[e] |= P->dof_constrained[3 * l + i];
    }

  // Vectors and matrix.
  std::vector<PetscInt> ghost_ids(m.global_id.begin() + m.num_owned, m.global_id.end());
  PetscCall(VecCreateGhostBlock(comm, 3, 3 * m.num_owned, PETSC_DECIDE, m.num_ghost,
                                ghost_ids.data(), &P->U));
  PetscCall(PetscObjectSetName((PetscObject)P->U, "displacement"));
  PetscCall(VecDuplicate(P->U, &P->U_work));
  PetscCall(VecDuplicate(P->U, &P->F_work));
  PetscCall(VecDuplicate(P->U, &P->reaction));
  PetscCall(ISLocalToGlobalMappingCreate(comm, 3, nl, m.global_id.data(), PETSC_COPY_VALUES,
                                         &P->l2g));
  PetscCall(CreateMatrix(P, share.d_nnz, share.o_nnz));
  if (P->near_null_space) PetscCall(SetRigidBodyNearNullSpace(P));

  // Initial displacement (scene guess, then the prescribed values at t = 0).
  if (!share.initial_guess.empty()) {
    PetscScalar *u;
    PetscCall(VecGetArray(P->U, &u));
    for (PetscInt i = 0; i < 3 * m.num_owned; ++i) u[i] = share.initial_guess[i];
    PetscCall(VecRestoreArray(P->U, &u));
  }
  PetscCall(ProblemSetLoadTime(P, 0.0, P->U));
  PetscCall(MakePhysicsTerms(P, &share.pressure_elements, share.forces));
  PetscFunctionReturn(0);
}

PetscErrorCode ProblemReleaseScene(Problem *P) {
  SceneSpec &s = P->scene;
  PetscFunctionBeginUser;
  // Assigned or swapped empty, not cleared: clear keeps the capacity.
  s.mesh = MeshData();
  std::vector<DofConstraint>().swap(s.constraints);
  std::vector<NodalForce>().swap(s.nodal_forces);
  for (PressureSpec &p : s.pressures) std::vector<int>().swap(p.elements);
  std::vector<double>().swap(s.initial_guess);
  std::vector<double>().swap(s.element_reference);
  std::vector<double>().swap(s.element_stress_ratio);
  std::vector<double>().swap(s.element_thickness);
  std::vector<double>().swap(s.element_md);
  std::vector<int>().swap(s.element_material);
#ifdef __GLIBC__
  // The reader's mesh and its parsing left freed blocks all over the heap (each below the mmap
  // threshold): hand their pages back before the matrix and the factors are made.
  if (P->rank == 0) malloc_trim(0);
#endif
  P->scene_released = true;
  PetscFunctionReturn(0);
}

PetscErrorCode ProblemSetLoadTime(Problem *P, double t, Vec U) {
  PetscScalar *u;
  PetscFunctionBeginUser;
  P->time = t;
  if (!P->mesh.ref_free.empty()) {
    const double s = P->scene.reference_blend.At(P->scene.schedules, t);
    if (s != P->mesh.ref_blend) PetscCall(LocalMeshBlendReference(P->comm, &P->mesh, s));
  }
  PetscCall(VecGetArray(U, &u));
  for (size_t k = 0; k < P->con_owned_dof.size(); ++k)
    u[P->con_owned_dof[k]] = P->con_owned_value[k].At(P->scene.schedules, t) - P->con_owned_offset[k];
  PetscCall(VecRestoreArray(U, &u));
  PetscFunctionReturn(0);
}

PetscErrorCode ProblemUpdateReactions(Problem *P, Vec U) {
  Vec R;
  PetscFunctionBeginUser;
  PetscCall(VecDuplicate(U, &R));
  PetscCall(FormResidual(nullptr, U, R, P));
  PetscCall(VecDestroy(&R));
  PetscFunctionReturn(0);
}

void SceneObserverDestroy(SceneObserver *o) {
  if (o->ctx && o->destroy) o->destroy(o->ctx);
  *o = SceneObserver();
}

PetscErrorCode ProblemDestroy(Problem *P) {
  PetscFunctionBeginUser;
  for (auto &term : P->terms) PetscCall(term->Destroy(*P));  // the chambers' LRC holds a reference to J
  P->terms.clear();
  PetscCall(VecDestroy(&P->U));
  PetscCall(VecDestroy(&P->U_work));
  PetscCall(VecDestroy(&P->F_work));
  PetscCall(VecDestroy(&P->reaction));
  PetscCall(MatDestroy(&P->J));
  PetscCall(UnassembledDestroy(P));
  PetscCall(ISLocalToGlobalMappingDestroy(&P->l2g));
  SceneObserverDestroy(&P->observer);
  PetscFunctionReturn(0);
}

namespace {

// Collective look-up of one scene node: its displacement, plus its reference position if asked.
PetscErrorCode NodeValue(Problem *P, Vec U, PetscInt node, bool with_reference, double out[3]) {
  double mine[3] = {0, 0, 0};
  const PetscScalar *a = nullptr;
  PetscFunctionBeginUser;
  if (U) PetscCall(VecGetArrayRead(U, &a));
  for (PetscInt l = 0; l < P->mesh.num_owned; ++l)
    if (P->mesh.natural_id[l] == node)
      for (int i = 0; i < 3; ++i) mine[i] = (a ? a[3 * l + i] : 0.0) + (with_reference ? P->mesh.X[3 * l + i] : 0.0);
  if (U) PetscCall(VecRestoreArrayRead(U, &a));
  PetscCallMPI(MPI_Allreduce(mine, out, 3, MPI_DOUBLE, MPI_SUM, P->comm));
  PetscFunctionReturn(0);
}

// The lowest (distance, id) over the ranks.
PetscErrorCode Nearest(MPI_Comm comm, double d, PetscInt id, PetscInt *best) {
  struct {
    double d;
    int id;
  } mine{d, (int)id}, all;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Allreduce(&mine, &all, 1, MPI_DOUBLE_INT, MPI_MINLOC, comm));
  *best = all.id;
  PetscFunctionReturn(0);
}

} // namespace

PetscErrorCode ProblemGetNodeDisplacement(Problem *P, Vec U, PetscInt node, double u[3]) {
  return NodeValue(P, U, node, false, u);
}

PetscErrorCode ProblemGetNodePosition(Problem *P, Vec U, PetscInt node, double x[3]) {
  return NodeValue(P, U, node, true, x);
}

PetscErrorCode ProblemNearestNode(Problem *P, double x, double y, PetscInt *node) {
  const LocalMesh &m = P->mesh;
  double d = 1e300;
  PetscInt best = PETSC_MAX_INT;
  PetscFunctionBeginUser;
  for (PetscInt l = 0; l < m.num_owned; ++l) {
    const double dd = std::hypot(m.X[3 * l] - x, m.X[3 * l + 1] - y);
    if (dd < d) d = dd, best = m.natural_id[l];  // owned nodes in ascending scene ids
  }
  PetscCall(Nearest(P->comm, d, best, node));
  PetscFunctionReturn(0);
}

PetscErrorCode ProblemNearestElement(Problem *P, double x, double y, PetscInt *element) {
  const LocalMesh &m = P->mesh;
  double d = 1e300;
  PetscInt best = PETSC_MAX_INT;
  PetscFunctionBeginUser;
  for (PetscInt e = 0; e < m.num_elements; ++e) {  // ascending scene ids
    double cx = 0, cy = 0;
    for (int a = 0; a < 3; ++a) cx += m.X[3 * m.tri[3 * e + a]] / 3, cy += m.X[3 * m.tri[3 * e + a] + 1] / 3;
    const double dd = std::hypot(cx - x, cy - y);
    if (dd < d) d = dd, best = m.element_natural[e];
  }
  PetscCall(Nearest(P->comm, d, best, element));
  PetscFunctionReturn(0);
}

namespace {

PetscErrorCode FindNodeSet(Problem *P, const char *name, const std::vector<PetscInt> **set) {
  auto it = P->mesh.node_sets.find(name);
  PetscFunctionBeginUser;
  PetscCheck(it != P->mesh.node_sets.end(), PETSC_COMM_SELF, PETSC_ERR_ARG_WRONG,
             "%s has no node set \"%s\" (check its physical groups)", P->mesh.source.c_str(), name);
  *set = &it->second;
  PetscFunctionReturn(0);
}

} // namespace

PetscErrorCode ProblemNodeSetFlags(Problem *P, const char *name, std::vector<char> *flags) {
  const std::vector<PetscInt> *set;
  PetscFunctionBeginUser;
  PetscCall(FindNodeSet(P, name, &set));
  flags->assign(P->mesh.NumLocal(), 0);
  for (PetscInt l : *set) (*flags)[l] = 1;
  PetscFunctionReturn(0);
}

PetscErrorCode ProblemNodeSetIds(Problem *P, const char *name, std::vector<PetscInt> *ids) {
  const LocalMesh &m = P->mesh;
  const std::vector<PetscInt> *set;
  PetscFunctionBeginUser;
  PetscCall(FindNodeSet(P, name, &set));
  std::vector<PetscInt> mine;
  for (PetscInt l : *set)
    if (l < m.num_owned) mine.push_back(m.natural_id[l]);
  PetscCall(AllGatherConcat(P->comm, mine, ids));
  std::sort(ids->begin(), ids->end());
  PetscFunctionReturn(0);
}

} // namespace etfe
