// See element_blocks.h. Why a map: MatSetValuesBlocked_SeqBAIJ searches the block row for each
// of the element's 9 blocks on every call; the structure is fixed after the first assembly
// (the matrix is exactly preallocated and MAT_NEW_NONZERO_ALLOCATION_ERR forbids new nonzeros),
// so the search is done once here.
#include "etfe/element_blocks.h"

#include <algorithm>

namespace etfe {

static PetscErrorCode ElementBlocksBuild(Mat mat, const std::vector<PetscInt> &element_global, ElementBlockMap *map) {
  PetscInt n;
  const PetscInt *ia, *ja;
  PetscBool done;
  PetscFunctionBeginUser;
  map->usable = false;
  map->offset.assign(element_global.size() * 3, -1);
  // Block-compressed rows (ia, ja in block units, columns sorted) of the assembled matrix.
  PetscCall(MatGetRowIJ(mat, 0, PETSC_FALSE, PETSC_TRUE, &n, &ia, &ja, &done));
  if (!done) PetscFunctionReturn(0);
  bool all = true;
  const size_t ne = element_global.size() / 3;
  for (size_t e = 0; e < ne && all; ++e)
    for (int a = 0; a < 3 && all; ++a) {
      const PetscInt r = element_global[3 * e + a];
      if (r < 0 || r >= n) {
        all = false;
        break;
      }
      for (int b = 0; b < 3; ++b) {
        const PetscInt c = element_global[3 * e + b];
        const PetscInt *p = std::lower_bound(ja + ia[r], ja + ia[r + 1], c);
        if (p == ja + ia[r + 1] || *p != c) {
          all = false;
          break;
        }
        map->offset[9 * e + 3 * a + b] = (PetscInt)(p - ja);
      }
    }
  PetscCall(MatRestoreRowIJ(mat, 0, PETSC_FALSE, PETSC_TRUE, &n, &ia, &ja, &done));
  map->usable = all;
  if (!all) map->offset.clear();
  PetscFunctionReturn(0);
}

PetscErrorCode ElementBlocksGet(Mat mat, const std::vector<PetscInt> &element_global, ElementBlockMap *map,
                                PetscScalar **values) {
  PetscBool seqbaij, assembled;
  PetscInt bs;
  PetscObjectState state;
  PetscFunctionBeginUser;
  *values = nullptr;
  PetscCall(PetscObjectTypeCompare((PetscObject)mat, MATSEQBAIJ, &seqbaij));
  if (!seqbaij) PetscFunctionReturn(0);
  PetscCall(MatGetBlockSize(mat, &bs));
  PetscCall(MatAssembled(mat, &assembled));
  // Before the first assembly the rows hold no structure yet: that Jacobian inserts as usual.
  if (bs != 3 || !assembled) PetscFunctionReturn(0);
  PetscCall(MatGetNonzeroState(mat, &state));
  if (map->mat != mat || map->nonzero_state != state) {
    PetscCall(ElementBlocksBuild(mat, element_global, map));
    map->mat = mat;
    map->nonzero_state = state;
  }
  if (!map->usable) PetscFunctionReturn(0);
  PetscCall(MatSeqBAIJGetArray(mat, values));
  PetscFunctionReturn(0);
}

PetscErrorCode ElementBlocksRestore(Mat mat, PetscScalar **values) {
  PetscFunctionBeginUser;
  if (*values) PetscCall(MatSeqBAIJRestoreArray(mat, values));
  *values = nullptr;
  PetscFunctionReturn(0);
}

} // namespace etfe
