// One link of the least-squares flattening, docs/theory.md §9 / thesis eqs. 2.25, 2.32, 2.33: the
// residual phi = l - L of a mesh edge (2D length l = |q - p|, 3D length L) and its gradient, the
// row A_i of the Gauss-Newton matrix A. The link behaves like a truss bar whose "stiffness" w A^T A
// has only the axial part: Gauss-Newton drops the geometric term w phi d2l/dx2, which vanishes at
// an exact development (phi = 0), so convergence is quadratic there and linear otherwise. With a
// large weight w the product w phi stays finite (it is the force that keeps a boundary link at
// its length), so the dropped term matters; FlattenLinkSystem can add it for a Newton step.
#include "etfe/kernels/flatten_link.h"

#include <cmath>

#include "etfe/kernels/status.h"

namespace etfe {

int FlattenLink(const double p[2], const double q[2], double L, double min_length, double *c,
                double grad[4]) {
  const double dx = q[0] - p[0], dy = q[1] - p[1];
  if (!std::isfinite(dx) || !std::isfinite(dy) || !std::isfinite(L)) return KERNEL_NONFINITE;
  // hypot avoids overflow/underflow of dx^2 + dy^2 for extreme coordinates.
  const double l = std::hypot(dx, dy);
  if (!(l > min_length) || !(l > 0.0)) return KERNEL_DEGENERATE;
  *c = l - L;
  if (grad) {
    const double ex = dx / l, ey = dy / l;
    grad[0] = -ex;
    grad[1] = -ey;
    grad[2] = ex;
    grad[3] = ey;
  }
  return KERNEL_OK;
}

void FlattenLinkSystem(double w, double c, const double grad[4], double l, double K[16],
                       double R[4]) {
  for (int a = 0; a < 4; ++a) {
    R[a] = -w * c * grad[a];
    for (int b = 0; b < 4; ++b) K[4 * a + b] = w * grad[a] * grad[b];
  }
  if (!(l > 0.0)) return;
  // d2l/dp2 = d2l/dq2 = P / l, d2l/dpdq = -P / l, with P the projector across the link.
  const double e[2] = {grad[2], grad[3]}, f = w * c / l;
  for (int i = 0; i < 2; ++i)
    for (int j = 0; j < 2; ++j) {
      const double h = f * ((i == j ? 1.0 : 0.0) - e[i] * e[j]);
      K[4 * i + j] += h;
      K[4 * (i + 2) + j + 2] += h;
      K[4 * i + j + 2] -= h;
      K[4 * (i + 2) + j] -= h;
    }
}

} // namespace etfe
