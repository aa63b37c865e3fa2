// See element_blocks.h. Why a map: MatSetValuesBlocked_SeqBAIJ searches the block row for each
// of the element's 9 blocks on every call; the structure is fixed after the first assembly
// (the matrix is exactly preallocated and MAT_NEW_NONZERO_ALLOCATION_ERR forbids new nonzeros),
// so the search is done once here.
#include "etfe/assembly/element_blocks.h"

#include <algorithm>
#include <utility>

namespace etfe {

namespace {

// Position of block column c in block row r of an assembled SeqBAIJ's compressed rows, or -1.
PetscInt FindBlock(const PetscInt *ia, const PetscInt *ja, PetscInt r, PetscInt c) {
  const PetscInt *p = std::lower_bound(ja + ia[r], ja + ia[r + 1], c);
  return p != ja + ia[r + 1] && *p == c ? (PetscInt)(p - ja) : -1;
}

// diag/offdiag: the sequential parts (offdiag nullptr on one rank, whose matrix is diag);
// garray: the global block column of each of offdiag's block columns; rstart: first owned block.
PetscErrorCode Build(Mat diag, Mat offdiag, const PetscInt *garray, PetscInt rstart, PetscInt rend,
                     const std::vector<PetscInt> &element_global, ElementBlockMap *map) {
  PetscInt nd, no = 0;
  const PetscInt *ia, *ja, *ib = nullptr, *jb = nullptr;
  PetscBool done, done_o = PETSC_TRUE;
  PetscFunctionBeginUser;
  map->usable = false;
  map->offset.assign(element_global.size() * 3, -1);
  // Block-compressed rows (ia, ja in block units, columns sorted) of the assembled parts.
  PetscCall(MatGetRowIJ(diag, 0, PETSC_FALSE, PETSC_TRUE, &nd, &ia, &ja, &done));
  if (offdiag) PetscCall(MatGetRowIJ(offdiag, 0, PETSC_FALSE, PETSC_TRUE, &no, &ib, &jb, &done_o));
  std::vector<std::pair<PetscInt, PetscInt>> cols;  // (global block column, offdiag block column)
  if (offdiag) {
    PetscInt ncols;
    PetscCall(MatGetLocalSize(offdiag, nullptr, &ncols));
    for (PetscInt k = 0; k < ncols / 3; ++k) cols.emplace_back(garray[k], k);
    std::sort(cols.begin(), cols.end());
  }
  bool all = done && done_o;
  map->ndiag = all ? ia[nd] : 0;
  const size_t ne = element_global.size() / 3;
  for (size_t e = 0; e < ne && all; ++e) {
    const PetscInt *g = &element_global[3 * e];
    bool owned = true;
    for (int a = 0; a < 3; ++a) owned = owned && g[a] >= rstart && g[a] < rend;
    if (!owned) continue;  // rows of another rank: MatSetValuesBlocked and the stash
    for (int a = 0; a < 3 && all; ++a)
      for (int b = 0; b < 3 && all; ++b) {
        const PetscInt r = g[a] - rstart, c = g[b];
        PetscInt o = -1;
        if (c >= rstart && c < rend) {
          o = FindBlock(ia, ja, r, c - rstart);
        } else if (offdiag) {
          const auto it = std::lower_bound(cols.begin(), cols.end(), std::make_pair(c, (PetscInt)-1));
          if (it != cols.end() && it->first == c) {
            o = FindBlock(ib, jb, r, it->second);
            if (o >= 0) o += map->ndiag;
          }
        }
        if (o < 0) all = false;
        map->offset[9 * e + 3 * a + b] = o;
      }
  }
  PetscCall(MatRestoreRowIJ(diag, 0, PETSC_FALSE, PETSC_TRUE, &nd, &ia, &ja, &done));
  if (offdiag) PetscCall(MatRestoreRowIJ(offdiag, 0, PETSC_FALSE, PETSC_TRUE, &no, &ib, &jb, &done_o));
  map->usable = all;
  if (!all) map->offset.clear();
  PetscFunctionReturn(0);
}

} // namespace

PetscErrorCode ElementBlocksGet(Mat mat, const std::vector<PetscInt> &element_global, ElementBlockMap *map,
                                ElementBlockValues *values) {
  PetscBool seq, mpi, assembled;
  PetscInt bs, rstart, rend;
  PetscObjectState state;
  PetscObjectId id;
  Mat diag = mat, offdiag = nullptr;
  const PetscInt *garray = nullptr;
  PetscFunctionBeginUser;
  *values = ElementBlockValues();
  PetscCall(PetscObjectTypeCompare((PetscObject)mat, MATSEQBAIJ, &seq));
  PetscCall(PetscObjectTypeCompare((PetscObject)mat, MATMPIBAIJ, &mpi));
  if (!seq && !mpi) PetscFunctionReturn(0);
  PetscCall(MatGetBlockSize(mat, &bs));
  PetscCall(MatAssembled(mat, &assembled));
  // Before the first assembly the rows hold no structure yet: that Jacobian inserts as usual.
  if (bs != 3 || !assembled) PetscFunctionReturn(0);
  if (mpi) PetscCall(MatMPIBAIJGetSeqBAIJ(mat, &diag, &offdiag, &garray));
  PetscCall(MatGetOwnershipRange(mat, &rstart, &rend));
  PetscCall(MatGetNonzeroState(mat, &state));
  PetscCall(PetscObjectGetId((PetscObject)mat, &id));
  if (map->mat_id != id || map->nonzero_state != state) {
    PetscCall(Build(diag, offdiag, garray, rstart / 3, rend / 3, element_global, map));
    map->mat_id = id;
    map->nonzero_state = state;
  }
  if (!map->usable) PetscFunctionReturn(0);
  values->diag_mat = diag;
  values->offdiag_mat = offdiag;
  values->ndiag = map->ndiag;
  PetscCall(MatSeqBAIJGetArray(diag, &values->diag));
  if (offdiag) PetscCall(MatSeqBAIJGetArray(offdiag, &values->offdiag));
  PetscFunctionReturn(0);
}

PetscErrorCode ElementBlocksRestore(ElementBlockValues *values) {
  PetscFunctionBeginUser;
  if (values->diag) PetscCall(MatSeqBAIJRestoreArray(values->diag_mat, &values->diag));
  if (values->offdiag) PetscCall(MatSeqBAIJRestoreArray(values->offdiag_mat, &values->offdiag));
  *values = ElementBlockValues();
  PetscFunctionReturn(0);
}

} // namespace etfe
