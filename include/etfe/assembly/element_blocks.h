// Direct insertion of the membrane elements' 3x3 blocks into a block (BAIJ, bs 3) matrix: the
// position of each element's 9 blocks in the matrix's value arrays, found once per nonzero
// structure, so the Jacobian loop adds K into the arrays without MatSetValuesBlocked's per-block
// column search (about 1800 instructions per element on PETSc 3.18, more than the element's own
// tangent). The sums are the same additions in the same order as ADD_VALUES, so the matrix is
// bitwise the same. On several ranks an element with a node another rank owns (its rows travel
// in PETSc's stash) keeps MatSetValuesBlocked, as do other matrix types (AIJ, MATIS) and a
// structure without some element block.
#pragma once

#include <petscmat.h>

#include <vector>

namespace etfe {

struct ElementBlockMap {
  PetscObjectId mat_id = 0;             // the matrix the offsets were found in (ids are never reused)
  PetscObjectState nonzero_state = -1;  // its nonzero structure then
  bool usable = false;                  // every owned element block was found
  // Per element, 9 block offsets (row-major a, b): below ndiag into the diagonal part's values,
  // from ndiag on into the off-diagonal part's (offset - ndiag); -1: the element goes through
  // MatSetValuesBlocked.
  std::vector<PetscInt> offset;
  PetscInt ndiag = 0;
};

// The value arrays while the direct path is open (diag == nullptr: closed).
struct ElementBlockValues {
  Mat diag_mat = nullptr, offdiag_mat = nullptr;
  PetscScalar *diag = nullptr, *offdiag = nullptr;
  PetscInt ndiag = 0;
};

// Opens the direct path when it applies: `mat` is an assembled MATSEQBAIJ or MATMPIBAIJ of block
// size 3 holding every block among each owned element's nodes (element_global: 3 global block ids
// per element). Rebuilds `map` when the matrix or its nonzero structure changed. Pair with
// ElementBlocksRestore before any assembly.
PetscErrorCode ElementBlocksGet(Mat mat, const std::vector<PetscInt> &element_global, ElementBlockMap *map,
                                ElementBlockValues *values);
PetscErrorCode ElementBlocksRestore(ElementBlockValues *values);

// Adds K (9x9 row-major, node-major) of element e at its 9 blocks (column-major inside a block,
// PETSc's BAIJ layout); false when e must go through MatSetValuesBlocked.
inline bool ElementBlocksAdd(const ElementBlockMap &map, PetscInt e, const double K[81], const ElementBlockValues &v) {
  const PetscInt *off = &map.offset[9 * (size_t)e];
  if (off[0] < 0) return false;
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) {
      const PetscInt o = off[3 * a + b];
      PetscScalar *blk = o < v.ndiag ? v.diag + 9 * o : v.offdiag + 9 * (o - v.ndiag);
      const double *k = K + 27 * a + 3 * b;
      for (int j = 0; j < 3; ++j)
        for (int i = 0; i < 3; ++i) blk[3 * j + i] += k[9 * i + j];
    }
  return true;
}

} // namespace etfe
