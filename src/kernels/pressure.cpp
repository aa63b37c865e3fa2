// Follower pressure on a three-node membrane, docs/theory.md §4 / thesis §5.4: the consistent nodal
// load of a uniform pressure on a flat triangle, f_a = p/3 * (area vector) = p/6 (x2-x1)x(x3-x1)
// for every node. With c = x1 x x2 + x2 x x3 + x3 x x1 (the same vector) the derivative is cyclic:
// dc/dx_k = [x_{k+2} - x_{k+1}]_x (indices mod 3), so L_ab = p/6 [x_{b+2} - x_{b+1}]_x for
// every row block a. L is not symmetric (a follower load is not conservative on an open
// surface); the assembler adds -L to the tangent.
#include "etfe/kernels/pressure.h"

namespace etfe {

void PressureLoad(double p, const double x[9], double f[9], double L[81]) {
  double a[3], b[3];
  for (int i = 0; i < 3; ++i) {
    a[i] = x[3 + i] - x[i];
    b[i] = x[6 + i] - x[i];
  }
  const double s = p / 6.0;
  const double c[3] = {s * (a[1] * b[2] - a[2] * b[1]), s * (a[2] * b[0] - a[0] * b[2]),
                       s * (a[0] * b[1] - a[1] * b[0])};
  for (int n = 0; n < 3; ++n)
    for (int i = 0; i < 3; ++i) f[3 * n + i] = c[i];
  if (!L) return;  // load only (e.g. external work or a residual evaluation)

  for (int k = 0; k < 3; ++k) {
    const double *xp = x + 3 * ((k + 2) % 3);
    const double *xn = x + 3 * ((k + 1) % 3);
    const double v[3] = {s * (xp[0] - xn[0]), s * (xp[1] - xn[1]), s * (xp[2] - xn[2])};
    // Skew matrix [v]_x, i.e. [v]_x w = v x w.
    const double m[9] = {0.0, -v[2], v[1], v[2], 0.0, -v[0], -v[1], v[0], 0.0};
    for (int row = 0; row < 3; ++row)
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) L[9 * (3 * row + i) + 3 * k + j] = m[3 * i + j];
  }
}

void PressureLoadSubtractTangent(double p, const double x[9], double f[9], double K[81]) {
  if (f) PressureLoad(p, x, f, nullptr);
  const double s = p / 6.0;
  for (int k = 0; k < 3; ++k) {
    const double *xp = x + 3 * ((k + 2) % 3);
    const double *xn = x + 3 * ((k + 1) % 3);
    const double v[3] = {s * (xp[0] - xn[0]), s * (xp[1] - xn[1]), s * (xp[2] - xn[2])};
    // K_(row,k) -= [v]_x for every row block; [v]_x's diagonal is zero.
    for (int row = 0; row < 3; ++row) {
      double *b = K + 9 * (3 * row) + 3 * k;
      b[1] -= -v[2], b[2] -= v[1];
      b[9] -= v[2], b[11] -= -v[0];
      b[18] -= -v[1], b[19] -= v[0];
    }
  }
}

} // namespace etfe
