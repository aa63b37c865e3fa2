// From the global scene mesh to this rank's part of it (local_mesh.h).
//
// Every rank holds the scene's global mesh during set-up (generators run everywhere; a file is
// read on rank 0 and broadcast). Rank 0 partitions the elements with METIS and broadcasts the
// part of each element; a node belongs to the lowest rank among its elements. PETSc ids number
// nodes rank by rank (owned nodes contiguous), keeping the scene's order inside a rank, so the
// matrix rows of a rank are contiguous.
#include <petscsys.h>

#include <algorithm>
#include <numeric>
#include <string>

#include "etfe/kernels/status.h"
#include "etfe/mesh/local_mesh.h"
#include "etfe/mesh/partition.h"

namespace etfe {

static PetscErrorCode PartitionAndBroadcast(MPI_Comm comm, const MeshData &mesh,
                                            std::vector<int> *part) {
  PetscMPIInt rank, size;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCallMPI(MPI_Comm_size(comm, &size));
  part->assign(mesh.NumElements(), 0);
  if (size == 1) PetscFunctionReturn(0);
  int ok = 1;
  std::string err;
  if (rank == 0) ok = PartitionElementsMetis(mesh, size, part, &err) ? 1 : 0;
  PetscCallMPI(MPI_Bcast(&ok, 1, MPI_INT, 0, comm));
  PetscCheck(ok, comm, PETSC_ERR_LIB, "%s", err.c_str());
  PetscCallMPI(MPI_Bcast(part->data(), (int)part->size(), MPI_INT, 0, comm));
  PetscFunctionReturn(0);
}

// A triangle in its own MD frame (the frame of ref): node 0 at the origin, 2 coordinates a node.
static void LocalTriangle(const double X[9], const MembraneReference &ref, double T[6]) {
  for (int a = 0; a < 3; ++a)
    for (int j = 0; j < 2; ++j) {
      double v = 0.0;
      for (int i = 0; i < 3; ++i) v += (X[3 * a + i] - X[i]) * ref.frame[3 * j + i];
      T[2 * a + j] = v;
    }
}

static PetscErrorCode BuildReferenceGeometry(const MeshData &gm, const double md_axis[3],
                                            const std::vector<double> &element_reference, LocalMesh *lm) {
  LocalMesh &m = *lm;
  PetscFunctionBeginUser;
  m.ref.resize(m.num_elements);
  if (!element_reference.empty()) m.ref_placed.resize(6 * m.num_elements), m.ref_free.resize(6 * m.num_elements);
  for (PetscInt e = 0; e < m.num_elements; ++e) {
    double X[9];
    for (int a = 0; a < 3; ++a)
      for (int i = 0; i < 3; ++i) X[3 * a + i] = m.X[3 * m.tri[3 * e + a] + i];
    int st = MembraneReferenceBuild(X, md_axis, 0.0, &m.ref[e]);
    if (st == KERNEL_OK && !element_reference.empty()) {
      const double *Y = &element_reference[9 * m.element_natural[e]];
      double md[3];
      MembraneReference free_ref;
      LocalTriangle(X, m.ref[e], &m.ref_placed[6 * e]);
      st = MembraneCarryAxis(X, Y, md_axis, md);
      if (st == KERNEL_OK) st = MembraneReferenceBuild(Y, md, 0.0, &free_ref);
      if (st == KERNEL_OK) LocalTriangle(Y, free_ref, &m.ref_free[6 * e]);
    }
    PetscCheck(st == KERNEL_OK, PETSC_COMM_SELF, PETSC_ERR_ARG_WRONG,
               "%s: element %" PetscInt_FMT " (nodes %" PetscInt_FMT " %" PetscInt_FMT
               " %" PetscInt_FMT "): %s; fix the mesh (remove or merge the element)",
               gm.source.c_str(), m.element_natural[e],
               m.natural_id[m.tri[3 * e]], m.natural_id[m.tri[3 * e + 1]],
               m.natural_id[m.tri[3 * e + 2]], KernelStatusName(st));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode LocalMeshCreate(MPI_Comm comm, const MeshData &gm, const double md_axis[3],
                               const std::vector<double> &element_reference, LocalMesh *lm,
                               MeshNumbering *numbering) {
  LocalMesh &m = *lm;
  PetscMPIInt rank, size;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCallMPI(MPI_Comm_size(comm, &size));
  const int nn = gm.NumNodes(), ne = gm.NumElements();
  m.num_nodes_global = nn;
  m.num_elements_global = ne;

  std::vector<int> part;
  PetscCall(PartitionAndBroadcast(comm, gm, &part));

  // Node owner = lowest rank among its elements; PETSc ids rank by rank.
  std::vector<int> owner(nn, size);
  for (int e = 0; e < ne; ++e)
    for (int a = 0; a < 3; ++a) {
      int &o = owner[gm.triangles[3 * e + a]];
      o = std::min(o, part[e]);
    }
  std::vector<PetscInt> first(size + 1, 0);
  for (int i = 0; i < nn; ++i) first[owner[i] + 1]++;
  std::partial_sum(first.begin(), first.end(), first.begin());
  std::vector<PetscInt> petsc_id(nn), next(first.begin(), first.end() - 1);
  for (int i = 0; i < nn; ++i) petsc_id[i] = next[owner[i]]++;
  m.owned_start = first[rank];
  m.num_owned = first[rank + 1] - first[rank];

  // Local elements and nodes.
  std::vector<PetscInt> local_of(nn, -1);
  m.natural_id.assign(m.num_owned, 0);
  for (int i = 0; i < nn; ++i)
    if (owner[i] == rank) {
      local_of[i] = petsc_id[i] - m.owned_start;
      m.natural_id[local_of[i]] = i;
    }
  std::vector<int> ghosts;
  for (int e = 0; e < ne; ++e) {
    if (part[e] != rank) continue;
    m.element_natural.push_back(e);
    for (int a = 0; a < 3; ++a) {
      int v = gm.triangles[3 * e + a];
      if (local_of[v] < 0) {
        local_of[v] = -2;  // ghost, numbered below
        ghosts.push_back(v);
      }
    }
  }
  std::sort(ghosts.begin(), ghosts.end(),
            [&](int a, int b) { return petsc_id[a] < petsc_id[b]; });
  m.num_ghost = (PetscInt)ghosts.size();
  for (PetscInt g = 0; g < m.num_ghost; ++g) {
    local_of[ghosts[g]] = m.num_owned + g;
    m.natural_id.push_back(ghosts[g]);
  }
  const PetscInt nl = m.NumLocal();
  m.global_id.resize(nl);
  m.X.resize(3 * nl);
  for (PetscInt l = 0; l < nl; ++l) {
    m.global_id[l] = petsc_id[m.natural_id[l]];
    for (int i = 0; i < 3; ++i) m.X[3 * l + i] = gm.coords[3 * m.natural_id[l] + i];
  }
  m.num_elements = (PetscInt)m.element_natural.size();
  m.tri.resize(3 * m.num_elements);
  for (PetscInt e = 0; e < m.num_elements; ++e)
    for (int a = 0; a < 3; ++a)
      m.tri[3 * e + a] = (int)local_of[gm.triangles[3 * m.element_natural[e] + a]];
  PetscCallMPI(MPI_Exscan(&m.num_elements, &m.element_start, 1, MPIU_INT, MPI_SUM, comm));
  if (rank == 0) m.element_start = 0;
  PetscCheck(element_reference.empty() || element_reference.size() == 9 * (size_t)ne, comm, PETSC_ERR_PLIB,
             "%s: %zu stress-free element coordinates for %d elements (9 each)", gm.source.c_str(),
             element_reference.size(), ne);
  PetscCall(BuildReferenceGeometry(gm, md_axis, element_reference, lm));
  numbering->petsc_id = std::move(petsc_id);
  numbering->local_of = std::move(local_of);
  PetscFunctionReturn(0);
}

PetscErrorCode LocalMeshBlendReference(MPI_Comm comm, LocalMesh *lm, double s) {
  LocalMesh &m = *lm;
  const double md[3] = {1.0, 0.0, 0.0};  // the triangles are in their MD frames
  PetscInt bad = -1, bad_global;
  PetscFunctionBeginUser;
  PetscCheck(!m.ref_free.empty(), comm, PETSC_ERR_PLIB, "no stress-free shapes to blend to");
  for (PetscInt e = 0; e < m.num_elements; ++e) {
    double Y[9] = {0.0};
    for (int a = 0; a < 3; ++a)
      for (int j = 0; j < 2; ++j) Y[3 * a + j] = (1.0 - s) * m.ref_placed[6 * e + 2 * a + j] + s * m.ref_free[6 * e + 2 * a + j];
    if (MembraneReferenceBuild(Y, md, 0.0, &m.ref[e]) != KERNEL_OK && bad < 0) bad = m.element_natural[e];
  }
  PetscCallMPI(MPI_Allreduce(&bad, &bad_global, 1, MPIU_INT, MPI_MAX, comm));
  PetscCheck(bad_global < 0, comm, PETSC_ERR_ARG_WRONG,
             "element %" PetscInt_FMT ": its stress-free shape blended %.3g of the way from the placed one is "
             "degenerate (the pattern folds this triangle over): check the cutting pattern of its strip",
             bad_global, s);
  m.ref_blend = s;
  PetscFunctionReturn(0);
}

} // namespace etfe
