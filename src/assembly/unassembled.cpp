// The unassembled tangent (MATIS) for domain decomposition (PCBDDC): each rank keeps the matrix
// of its own elements (its METIS part) over their nodes, owned and ghost, in the local numbering
// of the mesh (owned first, then ghosts); the global operator is the sum over the ranks and is
// never formed. The element loop adds each element block with local ids into this rank's
// matrix; no entry travels between ranks. A node shared by k subdomains is in k local matrices.
//
// Constrained DOFs: the element blocks come with their rows and columns zeroed (as for the
// assembled matrix) and the unit diagonal of the constrained row is split over the subdomains
// that share the node (MatDiagonalSet on MATIS divides by the multiplicity), so every local
// matrix is regular at its constrained DOFs and the sum is the assembled matrix's identity row.
#include <algorithm>

#include "etfe/assembly/assembly.h"

namespace etfe {

namespace {

// The number of neighbouring nodes (itself included) of every local node over the local
// elements: the exact block preallocation of the local matrix (contact adds diagonal blocks only).
std::vector<PetscInt> LocalBlockNonzeros(const LocalMesh &m) {
  const PetscInt nl = m.NumLocal();
  std::vector<std::vector<int>> adj(nl);
  for (PetscInt e = 0; e < m.num_elements; ++e)
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) adj[m.tri[3 * e + a]].push_back(m.tri[3 * e + b]);
  std::vector<PetscInt> nnz(nl, 1);
  for (PetscInt l = 0; l < nl; ++l) {
    std::vector<int> &v = adj[l];
    std::sort(v.begin(), v.end());
    nnz[l] = std::max<PetscInt>(1, (PetscInt)(std::unique(v.begin(), v.end()) - v.begin()));
  }
  return nnz;
}

} // namespace

PetscErrorCode UnassembledDefaultType(const Problem *P) {
  PetscFunctionBeginUser;
  if (P->linear_path.kind == LinearPath::Kind::unassembled && !P->linear_path.mat_type_named)
    PetscCall(MatSetType(P->J, MATIS));
  PetscFunctionReturn(0);
}

PetscErrorCode UnassembledCheckType(Problem *P) {
  PetscFunctionBeginUser;
  PetscCall(PetscObjectTypeCompare((PetscObject)P->J, MATIS, &P->unassembled));
  PetscCheck(P->unassembled || P->linear_path.kind != LinearPath::Kind::unassembled, P->comm, PETSC_ERR_ARG_INCOMP,
             "-pc_type bddc needs the unassembled tangent: drop -mat_type (bddc then takes -mat_type is) or give "
             "-mat_type is");
  PetscFunctionReturn(0);
}

PetscErrorCode UnassembledMatrixSetUp(Problem *P) {
  Mat local;
  PetscFunctionBeginUser;
  PetscCall(MatSetLocalToGlobalMapping(P->J, P->l2g, P->l2g));  // creates the local matrix
  const std::vector<PetscInt> nnz = LocalBlockNonzeros(P->mesh);
  PetscCall(MatISGetLocalMat(P->J, &local));
  PetscCall(MatXAIJSetPreallocation(local, 3, nnz.data(), nullptr, nullptr, nullptr));
  PetscCall(MatISRestoreLocalMat(P->J, &local));
  PetscCall(VecDuplicate(P->U, &P->constraint_unit));
  PetscCall(VecZeroEntries(P->constraint_unit));
  PetscScalar *a;
  PetscCall(VecGetArray(P->constraint_unit, &a));
  for (PetscInt d : P->con_owned_dof) a[d] = 1.0;
  PetscCall(VecRestoreArray(P->constraint_unit, &a));
  PetscFunctionReturn(0);
}

PetscErrorCode UnassembledAddElement(Mat J, const int tri[3], const PetscScalar K[81]) {
  const PetscInt l[3] = {tri[0], tri[1], tri[2]};
  PetscFunctionBeginUser;
  PetscCall(MatSetValuesBlockedLocal(J, 3, l, 3, l, K, ADD_VALUES));
  PetscFunctionReturn(0);
}

PetscErrorCode UnassembledAddConstraintDiagonal(Problem *P, Mat J) {
  PetscFunctionBeginUser;
  PetscCall(MatDiagonalSet(J, P->constraint_unit, ADD_VALUES));
  PetscFunctionReturn(0);
}

PetscErrorCode UnassembledDestroy(Problem *P) {
  PetscFunctionBeginUser;
  PetscCall(VecDestroy(&P->constraint_unit));
  PetscFunctionReturn(0);
}

} // namespace etfe
