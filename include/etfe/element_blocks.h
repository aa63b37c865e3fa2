// Direct insertion of the membrane elements' 3x3 blocks into a sequential block (BAIJ, bs 3)
// matrix: the position of each element's 9 blocks in the matrix's value array, found once per
// nonzero structure, so the Jacobian loop adds K into the array without MatSetValuesBlocked's
// per-block column search (about 1800 instructions per element on PETSc 3.18, more than the
// element's own tangent). The sums are the same additions in the same order as ADD_VALUES, so
// the matrix is bitwise the same. Other matrix types (parallel, AIJ, MATIS) and a structure
// without some element block keep MatSetValuesBlocked.
#pragma once

#include <petscmat.h>

#include <vector>

namespace etfe {

struct ElementBlockMap {
  Mat mat = nullptr;                     // the matrix the offsets were found in
  PetscObjectState nonzero_state = -1;   // its nonzero structure then
  bool usable = false;                   // every element block was found
  std::vector<PetscInt> offset;          // per element, 9 block offsets (row-major a, b) into the values
};

// The value array of `mat` when the direct path applies (else *values = nullptr): `mat` is an
// assembled MATSEQBAIJ of block size 3 holding every block among each element's nodes
// (element_global: 3 block ids per element, the block rows on one rank). Rebuilds `map` when the
// matrix or its nonzero structure changed. Pair with ElementBlocksRestore before any MatSetValues or assembly.
PetscErrorCode ElementBlocksGet(Mat mat, const std::vector<PetscInt> &element_global, ElementBlockMap *map,
                                PetscScalar **values);
PetscErrorCode ElementBlocksRestore(Mat mat, PetscScalar **values);

// values += K (9x9 row-major, node-major) of element e at its 9 blocks (column-major inside a
// block, PETSc's BAIJ layout).
inline void ElementBlocksAdd(const ElementBlockMap &map, PetscInt e, const double K[81], PetscScalar *values) {
  const PetscInt *off = &map.offset[9 * (size_t)e];
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) {
      PetscScalar *blk = values + 9 * off[3 * a + b];
      const double *k = K + 27 * a + 3 * b;
      for (int j = 0; j < 3; ++j)
        for (int i = 0; i < 3; ++i) blk[3 * j + i] += k[9 * i + j];
    }
}

} // namespace etfe
