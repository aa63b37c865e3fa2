// Fabrication criteria of a drawn film (see the header).
#include "etfe/kernels/plan_criteria.h"

#include <algorithm>
#include <cmath>

#include "etfe/kernels/status.h"

namespace etfe {

int PlanElementViolations(const PlanCriteria &c, double mises, double minor, double eq_strain, double v[3]) {
  v[0] = v[1] = v[2] = 0.0;
  if (!std::isfinite(mises) || !std::isfinite(minor) || !std::isfinite(eq_strain)) return KERNEL_NONFINITE;
  if (!(c.mises_target > 0) || !(c.mises_band > 0) || !(c.strain_unit > 0) || !(c.minor_unit > 0) || !std::isfinite(c.minor_limit) ||
      !std::isfinite(c.max_eq_strain))
    return KERNEL_NONFINITE;
  const double half = c.mises_band * c.mises_target;
  v[0] = std::max(0.0, std::fabs(mises - c.mises_target) - half) / half;
  v[1] = std::max(0.0, c.minor_limit - minor) / c.minor_unit;
  v[2] = std::max(0.0, eq_strain - c.max_eq_strain) / c.strain_unit;
  return KERNEL_OK;
}

} // namespace etfe
