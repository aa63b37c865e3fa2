// Small 3-vector helpers shared by the kernels. PETSc-free.
#pragma once

namespace etfe {

inline void Cross(const double *a, const double *b, double *c) {
  c[0] = a[1] * b[2] - a[2] * b[1];
  c[1] = a[2] * b[0] - a[0] * b[2];
  c[2] = a[0] * b[1] - a[1] * b[0];
}

} // namespace etfe
