// Compensation of cutting patterns: rest metric per element and compensated link lengths (see
// etfe/kernels/compensation.h).
#include "etfe/kernels/compensation.h"
#include "etfe/kernels/membrane.h"

#include <cmath>

#include "etfe/kernels/status.h"

namespace etfe {

int CompensationPlaneStressStrain(double young, double nu, const double S[3], double E[3]) {
  if (!(young > 0) || !(nu > -1.0 && nu < 0.5) || !std::isfinite(young) || !std::isfinite(S[0]) ||
      !std::isfinite(S[1]) || !std::isfinite(S[2]))
    return KERNEL_NONFINITE;
  E[0] = (S[0] - nu * S[1]) / young;
  E[1] = (S[1] - nu * S[0]) / young;
  E[2] = (1.0 + nu) * S[2] / young;
  return KERNEL_OK;
}

int CompensationMetricFromStrain(const double E[3], double M[3]) {
  if (!std::isfinite(E[0]) || !std::isfinite(E[1]) || !std::isfinite(E[2])) return KERNEL_NONFINITE;
  const double cxx = 1.0 + 2.0 * E[0], cyy = 1.0 + 2.0 * E[1], cxy = 2.0 * E[2];
  const double det = cxx * cyy - cxy * cxy;
  if (!(cxx > 0) || !(det > 0)) return KERNEL_DEGENERATE;
  M[0] = cyy / det;
  M[1] = cxx / det;
  M[2] = -cxy / det;
  return KERNEL_OK;
}

int CompensationMetricUniform(double c_md, double c_td, double M[3]) {
  if (!std::isfinite(c_md) || !std::isfinite(c_td)) return KERNEL_NONFINITE;
  if (!(c_md > -1.0) || !(c_td > -1.0)) return KERNEL_DEGENERATE;
  M[0] = 1.0 / ((1.0 + c_md) * (1.0 + c_md));
  M[1] = 1.0 / ((1.0 + c_td) * (1.0 + c_td));
  M[2] = 0.0;
  return KERNEL_OK;
}

int CompensationStressInPattern(const double X[9], const double xy[6], const double md_axis[3],
                                const double S_local[3], double S_pattern[3]) {
  double g1[3], g2[3], n[3];
  for (int i = 0; i < 3; ++i) g1[i] = X[3 + i] - X[i], g2[i] = X[6 + i] - X[i];
  n[0] = g1[1] * g2[2] - g1[2] * g2[1];
  n[1] = g1[2] * g2[0] - g1[0] * g2[2];
  n[2] = g1[0] * g2[1] - g1[1] * g2[0];
  const double nn = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  const double mm = std::sqrt(md_axis[0] * md_axis[0] + md_axis[1] * md_axis[1] + md_axis[2] * md_axis[2]);
  if (!(nn > 0) || !std::isfinite(nn) || !(mm > 0)) return KERNEL_DEGENERATE;
  const double mn = (md_axis[0] * n[0] + md_axis[1] * n[1] + md_axis[2] * n[2]) / nn;
  double t[3];
  for (int i = 0; i < 3; ++i) t[i] = md_axis[i] - mn * n[i] / nn;
  if (std::sqrt(t[0] * t[0] + t[1] * t[1] + t[2] * t[2]) < 1e-3 * mm)
    for (int i = 0; i < 3; ++i) t[i] = g1[i];
  // t carried into the pattern by the triangle's own map (the MD axis of the laid-on pattern too).
  const double f1[2] = {xy[2] - xy[0], xy[3] - xy[1]}, f2[2] = {xy[4] - xy[0], xy[5] - xy[1]};
  if (!(f1[0] * f2[1] - f1[1] * f2[0] > 0)) return KERNEL_DEGENERATE;
  const double Y[9] = {xy[0], xy[1], 0.0, xy[2], xy[3], 0.0, xy[4], xy[5], 0.0};
  double tc[3];
  if (MembraneCarryAxis(X, Y, t, tc) != KERNEL_OK) return KERNEL_DEGENERATE;
  const double tx = tc[0], ty = tc[1];
  const double tl = std::hypot(tx, ty);
  if (!(tl > 0)) return KERNEL_DEGENERATE;
  const double c = tx / tl, s = ty / tl;
  const double Smd = S_local[0], Std = S_local[1], Smt = S_local[2];
  S_pattern[0] = c * c * Smd + s * s * Std - 2.0 * c * s * Smt;
  S_pattern[1] = s * s * Smd + c * c * Std + 2.0 * c * s * Smt;
  S_pattern[2] = c * s * (Smd - Std) + (c * c - s * s) * Smt;
  return KERNEL_OK;
}

double CompensatedLength(const double M[3], double L, const double d[2]) {
  const double dd = d[0] * d[0] + d[1] * d[1];
  if (!(dd > 0)) return -1.0;
  const double q = M[0] * d[0] * d[0] + 2.0 * M[2] * d[0] * d[1] + M[1] * d[1] * d[1];
  return L * std::sqrt(q / dd);
}

} // namespace etfe
