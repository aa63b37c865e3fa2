// Compensation of cutting patterns: rest metric per element and compensated link lengths (see
// etfe/kernels/compensation.h).
#include "etfe/kernels/compensation.h"

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

double CompensatedLength(const double M[3], double L, const double d[2]) {
  const double dd = d[0] * d[0] + d[1] * d[1];
  if (!(dd > 0)) return -1.0;
  const double q = M[0] * d[0] * d[0] + 2.0 * M[2] * d[0] * d[1] + M[1] * d[1] * d[1];
  return L * std::sqrt(q / dd);
}

} // namespace etfe
