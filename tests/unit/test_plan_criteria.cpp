// The drawing planner's per-element criteria (kernels/plan_criteria.h).
#include <cmath>
#include <limits>

#include "check.h"
#include "etfe/kernels/plan_criteria.h"
#include "etfe/kernels/status.h"

using namespace etfe;

int main() {
  PlanCriteria c;  // 13.28 MPa +- 10 %, emin >= 0, eq < 0.10, unit 1e-3
  double v[3];
  // Inside the band, no wrinkle, little plastic strain: nothing violated, up to the band's edges.
  CHECK(PlanElementViolations(c, 13.28, 0.01, 0.02, v) == KERNEL_OK, "status");
  CHECK(v[0] == 0 && v[1] == 0 && v[2] == 0, "inside: %g %g %g", v[0], v[1], v[2]);
  PlanElementViolations(c, 13.28 * 1.1 - 1e-12, 0.0, 0.1, v);
  CHECK(v[0] == 0 && v[1] == 0 && v[2] == 0, "edges: %g %g %g", v[0], v[1], v[2]);
  // Above and below the band by one half-width (1.328 MPa): one unit either way.
  PlanElementViolations(c, 13.28 * 1.2, 0.0, 0.0, v);
  CHECK_CLOSE(v[0], 1.0, 1e-12, 0);
  PlanElementViolations(c, 13.28 * 0.8, 0.0, 0.0, v);
  CHECK_CLOSE(v[0], 1.0, 1e-12, 0);
  // A stress-free element is (13.28 - 1.328)/1.328 = 9 units below.
  PlanElementViolations(c, 0.0, 0.0, 0.0, v);
  CHECK_CLOSE(v[0], 9.0, 1e-12, 0);
  // A wrinkle of -2e-3 and an equivalent strain of 0.103: 2 and 3 strain units.
  PlanElementViolations(c, 13.28, -2e-3, 0.103, v);
  CHECK_CLOSE(v[1], 2.0, 1e-9, 0);
  CHECK_CLOSE(v[2], 3.0, 1e-9, 0);
  // Linear growth away from each criterion (so the squared sum is C1 with a linear gradient).
  double a[3], b[3];
  PlanElementViolations(c, 16.0, -1e-3, 0.11, a);
  PlanElementViolations(c, 17.0, -3e-3, 0.12, b);
  CHECK_CLOSE(b[0] - a[0], 1.0 / 1.328, 1e-12, 0);
  CHECK_CLOSE(b[1] - a[1], 2.0, 1e-9, 0);
  CHECK_CLOSE(b[2] - a[2], 10.0, 1e-9, 0);
  // Other criteria: a wider band and a tolerated small wrinkle.
  PlanCriteria d;
  d.mises_band = 0.2, d.minor_limit = -1e-3;
  PlanElementViolations(d, 13.28 * 1.15, -5e-4, 0.0, v);
  CHECK(v[0] == 0 && v[1] == 0, "relaxed: %g %g", v[0], v[1]);
  // Bad input and nonsense criteria.
  const double nan = std::numeric_limits<double>::quiet_NaN();
  CHECK(PlanElementViolations(c, nan, 0, 0, v) == KERNEL_NONFINITE, "NaN mises");
  CHECK(PlanElementViolations(c, 1, 0, INFINITY, v) == KERNEL_NONFINITE, "Inf eq");
  PlanCriteria bad;
  bad.mises_band = 0;
  CHECK(PlanElementViolations(bad, 13, 0, 0, v) == KERNEL_NONFINITE, "zero band");
  TEST_MAIN_END();
}
