// One link (mesh edge) of the least-squares flattening of a cutting strip (docs/theory.md §9,
// thesis §2.3.2, eqs. 2.25, 2.32, 2.33). PETSc-free.
//   c = |q - p| - L                        (phi_i, eq. 2.25: 2D length minus 3D length)
//   A_i = dc/d(px,py,qx,qy) = [-e, e]      (eq. 2.33a, e = (q - p)/|q - p|)
//   K_i = w A_i^T A_i,  R_i = -w c A_i^T   (eq. 2.32, assembled like a truss into K dx = R)
//   optional Newton term w c d2l/dx2 (the bar's geometric stiffness), see FlattenLinkSystem
#pragma once

namespace etfe {

// Residual c and gradient grad[4] = dc/d(px, py, qx, qy) of a link with 2D end points p, q and
// 3D length L. Returns KERNEL_DEGENERATE when the current length is not above min_length (the
// direction e, hence the gradient, is undefined) and KERNEL_NONFINITE for NaN/Inf input; c and
// grad are then left unset. grad may be null (residual only).
int FlattenLink(const double p[2], const double q[2], double L, double min_length, double *c,
                double grad[4]);

// The contribution of one link with weight w to K dx = R, with g = grad from FlattenLink:
//   K[16] (4x4 row-major) = w g g^T                     (Gauss-Newton, eq. 2.32a)
//                         + w c / l [[P, -P], [-P, P]]  (only when l > 0: Newton's second-order
//                           term w c d2l/dx2, P = I - e e^T, the truss "geometric stiffness")
//   R[4] = -w c g                                       (eq. 2.32b)
// Pass l = 0 for the Gauss-Newton matrix (always positive semi-definite) and l = the current
// 2D length (c + L) for the Newton matrix (indefinite for compressed links, c < 0).
void FlattenLinkSystem(double w, double c, const double grad[4], double l, double K[16],
                       double R[4]);

} // namespace etfe
