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

static PetscErrorCode BuildReferenceGeometry(const MeshData &gm, const double md_axis[3], LocalMesh *lm) {
  LocalMesh &m = *lm;
  PetscFunctionBeginUser;
  m.ref.resize(m.num_elements);
  for (PetscInt e = 0; e < m.num_elements; ++e) {
    double X[9];
    for (int a = 0; a < 3; ++a)
      for (int i = 0; i < 3; ++i) X[3 * a + i] = m.X[3 * m.tri[3 * e + a] + i];
    int st = MembraneReferenceBuild(X, md_axis, 0.0, &m.ref[e]);
    PetscCheck(st == KERNEL_OK, PETSC_COMM_SELF, PETSC_ERR_ARG_WRONG,
               "%s: element %" PetscInt_FMT " (nodes %" PetscInt_FMT " %" PetscInt_FMT
               " %" PetscInt_FMT "): %s; fix the mesh (remove or merge the element)",
               gm.source.c_str(), m.element_natural[e],
               m.natural_id[m.tri[3 * e]], m.natural_id[m.tri[3 * e + 1]],
               m.natural_id[m.tri[3 * e + 2]], KernelStatusName(st));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode LocalMeshCreate(MPI_Comm comm, const MeshData &gm, const double md_axis[3], LocalMesh *lm,
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
  PetscCall(BuildReferenceGeometry(gm, md_axis, lm));
  numbering->petsc_id = std::move(petsc_id);
  numbering->local_of = std::move(local_of);
  PetscFunctionReturn(0);
}

} // namespace etfe
