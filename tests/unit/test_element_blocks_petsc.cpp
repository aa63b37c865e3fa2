// The Jacobian's direct block insertion (src/assembly/element_blocks.cpp) gives bitwise the same
// one-rank BAIJ matrix as MatSetValuesBlocked with ADD_VALUES, takes no part before the first
// assembly (the rows have no structure yet) nor for other matrix types, and falls back when an
// element block is missing from the structure.
#include "etfe/assembly/element_blocks.h"

#include "check.h"

#include <cstring>
#include <vector>

namespace {

// Five nodes, four triangles sharing edges (every node pair of a triangle is a block; nodes 0
// and 4 share none).
const int kNumElements = 4;
const std::vector<PetscInt> kElements = {0, 1, 2, 1, 3, 2, 2, 3, 0, 2, 4, 3};

Mat Create(MatType type) {
  Mat A;
  const PetscInt nnz[5] = {5, 5, 5, 5, 5};
  MatCreate(PETSC_COMM_SELF, &A);
  MatSetSizes(A, 15, 15, 15, 15);
  MatSetBlockSize(A, 3);
  MatSetType(A, type);
  MatXAIJSetPreallocation(A, 3, nnz, nullptr, nullptr, nullptr);
  MatSetOption(A, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_TRUE);
  return A;
}

void ElementMatrix(int e, int pass, double K[81]) {
  // Values with full mantissas, different per element and pass, so sums round.
  for (int k = 0; k < 81; ++k) K[k] = 1.0 / (3.0 + k + 7.0 * e + 13.0 * pass) - 0.1 * (k % 5);
}

void AssembleReference(Mat A, int pass) {
  for (int e = 0; e < kNumElements; ++e) {
    double K[81];
    ElementMatrix(e, pass, K);
    MatSetValuesBlocked(A, 3, &kElements[3 * e], 3, &kElements[3 * e], K, ADD_VALUES);
  }
  MatAssemblyBegin(A, MAT_FINAL_ASSEMBLY);
  MatAssemblyEnd(A, MAT_FINAL_ASSEMBLY);
}

bool SameValues(Mat A, Mat B) {
  for (PetscInt r = 0; r < 15; ++r) {
    PetscInt na, nb;
    const PetscInt *ca, *cb;
    const PetscScalar *va, *vb;
    MatGetRow(A, r, &na, &ca, &va);
    MatGetRow(B, r, &nb, &cb, &vb);
    const bool same = na == nb && !std::memcmp(ca, cb, na * sizeof *ca) && !std::memcmp(va, vb, na * sizeof *va);
    MatRestoreRow(B, r, &nb, &cb, &vb);
    MatRestoreRow(A, r, &na, &ca, &va);
    if (!same) return false;
  }
  return true;
}

} // namespace

int main(int argc, char **argv) {
  if (PetscInitialize(&argc, &argv, nullptr, nullptr)) return 2;
  {
    Mat ref = Create(MATSEQBAIJ), A = Create(MATSEQBAIJ);
    etfe::ElementBlockMap map;
    etfe::ElementBlockValues values;
    etfe::ElementBlocksGet(A, kElements, &map, &values);
    CHECK(values.diag == nullptr, "an unassembled matrix has no structure to write into");
    AssembleReference(ref, 0);
    AssembleReference(A, 0);
    for (int pass = 1; pass <= 2; ++pass) {
      MatZeroEntries(ref);
      AssembleReference(ref, pass);
      MatZeroEntries(A);
      etfe::ElementBlocksGet(A, kElements, &map, &values);
      CHECK(values.diag != nullptr, "pass %d: the assembled BAIJ matrix takes the direct path", pass);
      if (!values.diag) break;
      for (int e = 0; e < kNumElements; ++e) {
        double K[81];
        ElementMatrix(e, pass, K);
        CHECK(etfe::ElementBlocksAdd(map, e, K, values), "pass %d: element %d has its blocks", pass, e);
      }
      etfe::ElementBlocksRestore(&values);
      MatAssemblyBegin(A, MAT_FINAL_ASSEMBLY);
      MatAssemblyEnd(A, MAT_FINAL_ASSEMBLY);
      CHECK(SameValues(A, ref), "pass %d: direct insertion differs from MatSetValuesBlocked", pass);
    }
    // An element whose block (0, 4) the structure lacks: the map is not usable, the caller
    // falls back to MatSetValuesBlocked (which reports the new nonzero).
    const std::vector<PetscInt> outside = {0, 1, 4};
    etfe::ElementBlockMap other;
    etfe::ElementBlocksGet(A, outside, &other, &values);
    CHECK(values.diag == nullptr && !other.usable, "a block outside the structure disables the direct path");
    MatDestroy(&A);
    MatDestroy(&ref);
  }
  {
    Mat A = Create(MATSEQAIJ);
    AssembleReference(A, 0);
    etfe::ElementBlockMap map;
    etfe::ElementBlockValues values;
    etfe::ElementBlocksGet(A, kElements, &map, &values);
    CHECK(values.diag == nullptr, "an AIJ matrix keeps MatSetValuesBlocked");
    MatDestroy(&A);
  }
  PetscFinalize();
  TEST_MAIN_END();
}
