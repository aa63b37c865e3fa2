// The Problem built from a scene description: the local mesh (src/mesh/distribute.cpp), the
// history the material keeps, the constraints and loads on local DOFs, vectors and the matrix.
// Preallocation is exact: it is counted on the global mesh, which also sees the elements of
// other ranks that touch an owned node.
#include <petscsnes.h>

#include <algorithm>
#include <map>
#include <numeric>
#include <string>

#include "etfe/assembly.h"
#include "etfe/contact.h"

namespace etfe {

static PetscErrorCode CreateMatrix(Problem *P, const MeshData &gm,
                                   const std::vector<PetscInt> &petsc_id) {
  LocalMesh &m = P->mesh;
  const PetscInt n = m.num_owned, start = m.owned_start;
  PetscFunctionBeginUser;
  // Neighbour lists of owned nodes over all elements of the global mesh.
  std::vector<PetscInt> count(n + 1, 0);
  const int ne = gm.NumElements();
  for (int e = 0; e < ne; ++e)
    for (int a = 0; a < 3; ++a) {
      PetscInt row = petsc_id[gm.triangles[3 * e + a]] - start;
      if (row >= 0 && row < n) count[row + 1] += 3;
    }
  std::partial_sum(count.begin(), count.end(), count.begin());
  std::vector<PetscInt> cols(count[n]), fill(count.begin(), count.end() - 1);
  for (int e = 0; e < ne; ++e)
    for (int a = 0; a < 3; ++a) {
      PetscInt row = petsc_id[gm.triangles[3 * e + a]] - start;
      if (row < 0 || row >= n) continue;
      for (int b = 0; b < 3; ++b) cols[fill[row]++] = petsc_id[gm.triangles[3 * e + b]];
    }
  std::vector<PetscInt> d_nnz(n), o_nnz(n);
  for (PetscInt r = 0; r < n; ++r) {
    auto first = cols.begin() + count[r], last = cols.begin() + count[r + 1];
    std::sort(first, last);
    last = std::unique(first, last);
    PetscInt d = 0, o = 0;
    for (auto it = first; it != last; ++it) (*it >= start && *it < start + n) ? ++d : ++o;
    d_nnz[r] = d;
    o_nnz[r] = o;
  }
  PetscCall(MatCreate(P->comm, &P->J));
  PetscCall(MatSetSizes(P->J, 3 * n, 3 * n, PETSC_DETERMINE, PETSC_DETERMINE));
  PetscCall(MatSetBlockSize(P->J, 3));
  PetscCall(MatSetType(P->J, MATBAIJ));  // 3x3 blocks: insertion ~3x faster than AIJ here
  PetscCall(MatSetOptionsPrefix(P->J, nullptr));
  PetscCall(MatSetFromOptions(P->J));
  PetscCall(MatXAIJSetPreallocation(P->J, 3, d_nnz.data(), o_nnz.data(), nullptr, nullptr));
  PetscCall(MatSetLocalToGlobalMapping(P->J, P->l2g, P->l2g));
  // A new nonzero would mean a wrong preallocation: make it a hard error, never a malloc.
  PetscCall(MatSetOption(P->J, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_TRUE));
  PetscCall(MatSetOption(P->J, MAT_SYMMETRIC, P->has_pressure ? PETSC_FALSE : PETSC_TRUE));
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

PetscErrorCode ProblemCreate(MPI_Comm comm, SceneSpec &&scene, std::unique_ptr<Material> material,
                             Problem *P) {
  PetscFunctionBeginUser;
  P->comm = comm;
  PetscCallMPI(MPI_Comm_rank(comm, &P->rank));
  PetscCallMPI(MPI_Comm_size(comm, &P->size));
  P->scene = std::move(scene);
  P->material = std::move(material);
  const MeshData &gm = P->scene.mesh;
  LocalMesh &m = P->mesh;
  const int nn = gm.NumNodes(), ne = gm.NumElements();
  MeshNumbering numbering;
  PetscCall(LocalMeshCreate(comm, gm, P->scene.md_axis, P->scene.element_reference, &m, &numbering));
  const PetscInt nl = m.NumLocal();

  // History only when the material has one.
  const int nh = P->material->HistorySize();
  // The element loops keep a trial history on the stack (16 doubles).
  PetscCheck(nh <= 16, comm, PETSC_ERR_SUP, "material %s keeps %d history values per element; at most 16 are supported",
             P->material->Name(), nh);
  if (nh > 0) {
    P->history.resize((size_t)nh * m.num_elements);
    P->history_trial.resize((size_t)nh * m.num_elements);
    for (PetscInt e = 0; e < m.num_elements; ++e) P->material->InitHistory(&P->history[nh * e]);
  }

  // Constraints: every local DOF (owned or ghost) knows whether it is constrained.
  P->dof_constrained.assign(3 * nl, 0);
  for (const DofConstraint &c : P->scene.constraints) {
    PetscCheck(c.node >= 0 && c.node < nn && c.comp >= 0 && c.comp < 3, comm,
               PETSC_ERR_ARG_OUTOFRANGE,
               "scene %s: constraint on node %d component %d is outside the mesh (%d nodes)",
               P->scene.name.c_str(), c.node, c.comp, nn);
    PetscInt l = numbering.local_of[c.node];
    if (l < 0) continue;
    const PetscInt dof = 3 * l + c.comp;
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

  // Pressure only when the scene has it.
  if (P->scene.pressure.active) {
    P->has_pressure = true;
    P->pressure_value = P->scene.pressure.value;
    std::vector<char> loaded(ne, P->scene.pressure.elements.empty() ? 1 : 0);
    for (int e : P->scene.pressure.elements) {
      PetscCheck(e >= 0 && e < ne, comm, PETSC_ERR_ARG_OUTOFRANGE,
                 "scene %s: pressure element %d is outside the mesh (%d elements)",
                 P->scene.name.c_str(), e, ne);
      loaded[e] = 1;
    }
    for (PetscInt e = 0; e < m.num_elements; ++e)
      if (loaded[m.element_natural[e]]) P->pressure_elements.push_back(e);
  }

  // Dead nodal forces on owned DOFs.
  for (const NodalForce &f : P->scene.nodal_forces) {
    PetscCheck(f.node >= 0 && f.node < nn && f.comp >= 0 && f.comp < 3, comm, PETSC_ERR_ARG_OUTOFRANGE,
               "scene %s: nodal force on node %d component %d is outside the mesh (%d nodes)",
               P->scene.name.c_str(), f.node, f.comp, nn);
    const PetscInt l = numbering.local_of[f.node];
    if (l >= 0 && l < m.num_owned) {
      P->force_owned_dof.push_back(3 * l + f.comp);
      P->force_owned_value.push_back(f.value);
    }
  }

  // Vectors and matrix.
  std::vector<PetscInt> ghost_ids(m.num_ghost);
  for (PetscInt g = 0; g < m.num_ghost; ++g) ghost_ids[g] = m.global_id[m.num_owned + g];
  PetscCall(VecCreateGhostBlock(comm, 3, 3 * m.num_owned, PETSC_DECIDE, m.num_ghost,
                                ghost_ids.data(), &P->U));
  PetscCall(PetscObjectSetName((PetscObject)P->U, "displacement"));
  PetscCall(VecDuplicate(P->U, &P->U_work));
  PetscCall(VecDuplicate(P->U, &P->F_work));
  PetscCall(VecDuplicate(P->U, &P->reaction));
  PetscCall(ISLocalToGlobalMappingCreate(comm, 3, nl, m.global_id.data(), PETSC_COPY_VALUES,
                                         &P->l2g));
  PetscCall(CreateMatrix(P, gm, numbering.petsc_id));
  if (P->near_null_space) PetscCall(SetRigidBodyNearNullSpace(P));

  // Initial displacement (scene guess, then the prescribed values at t = 0).
  if (!P->scene.initial_guess.empty()) {
    PetscScalar *u;
    PetscCall(VecGetArray(P->U, &u));
    for (PetscInt l = 0; l < m.num_owned; ++l)
      for (int i = 0; i < 3; ++i) u[3 * l + i] = P->scene.initial_guess[3 * m.natural_id[l] + i];
    PetscCall(VecRestoreArray(P->U, &u));
  }
  PetscCall(ProblemSetLoadTime(P, 0.0, P->U));
  PetscFunctionReturn(0);
}

PetscErrorCode ProblemReleaseSceneMesh(Problem *P, std::uint64_t fingerprint) {
  MeshData &gm = P->scene.mesh;
  PetscFunctionBeginUser;
  // swap, not clear: clear keeps the capacity.
  std::vector<double>().swap(gm.coords);
  std::vector<int>().swap(gm.triangles);
  std::vector<long long>().swap(gm.node_tags);
  std::vector<long long>().swap(gm.element_tags);
  std::map<std::string, std::vector<int>>().swap(gm.element_sets);
  std::vector<double>().swap(P->scene.element_reference);
  P->scene_mesh_released = true;
  P->scene_mesh_fingerprint = fingerprint;
  PetscFunctionReturn(0);
}

PetscErrorCode ProblemSetContact(Problem *P, ContactSet *contact) {
  PetscFunctionBeginUser;
  P->contact = contact;
  if (contact->law != FrictionLaw::Fixed && contact->params.mu > 0)
    PetscCall(MatSetOption(P->J, MAT_SYMMETRIC, PETSC_FALSE));  // slip tangent, eq. 4.31
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
  PetscCall(VecDestroy(&P->U));
  PetscCall(VecDestroy(&P->U_work));
  PetscCall(VecDestroy(&P->F_work));
  PetscCall(VecDestroy(&P->reaction));
  PetscCall(MatDestroy(&P->J));
  PetscCall(ISLocalToGlobalMappingDestroy(&P->l2g));
  if (P->contact) PetscCall(ContactDestroy(&P->contact));
  SceneObserverDestroy(&P->observer);
  PetscFunctionReturn(0);
}

namespace {

// Collective look-up of one scene node: its displacement, plus its reference position if asked.
PetscErrorCode NodeValue(Problem *P, Vec U, PetscInt node, bool with_reference, double out[3]) {
  double mine[3] = {0, 0, 0};
  const PetscScalar *a;
  PetscFunctionBeginUser;
  PetscCall(VecGetArrayRead(U, &a));
  for (PetscInt l = 0; l < P->mesh.num_owned; ++l)
    if (P->mesh.natural_id[l] == node)
      for (int i = 0; i < 3; ++i) mine[i] = a[3 * l + i] + (with_reference ? P->mesh.X[3 * l + i] : 0.0);
  PetscCall(VecRestoreArrayRead(U, &a));
  PetscCallMPI(MPI_Allreduce(mine, out, 3, MPI_DOUBLE, MPI_SUM, P->comm));
  PetscFunctionReturn(0);
}

} // namespace

PetscErrorCode ProblemGetNodeDisplacement(Problem *P, Vec U, PetscInt node, double u[3]) {
  return NodeValue(P, U, node, false, u);
}

PetscErrorCode ProblemGetNodePosition(Problem *P, Vec U, PetscInt node, double x[3]) {
  return NodeValue(P, U, node, true, x);
}

} // namespace etfe
