// Compensation kernels (etfe/kernels/compensation.h):
//  * the plane-stress strain of a stress, put through the solver's elastic law, gives the stress
//    back (so a pattern compensated with it reaches the prestress);
//  * the rest metric M = (I + 2E)^-1 inverts C: a link cut with M's length and stretched by the
//    stretch U = C^1/2 is the design length again, in any direction (closed form for a rotated
//    principal frame);
//  * uniform factors: cut MD/TD lengths are 1/(1 + c) of the design;
//  * bad input (NaN, Poisson's ratio 0.5, a strain that no stretch reaches) is refused.
#include <cmath>

#include "check.h"
#include "etfe/kernels/compensation.h"
#include "etfe/kernels/elastic.h"
#include "etfe/kernels/status.h"

using namespace etfe;

int main() {
  const double young = 800.0, nu = 0.43;
  // Round trip stress -> strain -> the solver's elastic law.
  const double cases[3][3] = {{10.0, 0.0, 0.0}, {6.0, 4.0, 0.0}, {5.0, -2.0, 3.0}};
  for (const auto &S : cases) {
    double E[3], Sb[3];
    CHECK(CompensationPlaneStressStrain(young, nu, S, E) == KERNEL_OK, "status");
    const double Ev[3] = {E[0], E[1], 2.0 * E[2]};  // the law takes the engineering shear
    ElasticPlaneStress(young, nu, Ev, Sb, nullptr);
    for (int k = 0; k < 3; ++k) CHECK_CLOSE(Sb[k], S[k], 1e-13, 1e-13);
  }
  // Uniaxial: Exx = S/Y, Eyy = -nu S/Y.
  {
    const double S[3] = {12.0, 0.0, 0.0};
    double E[3];
    CompensationPlaneStressStrain(young, nu, S, E);
    CHECK_CLOSE(E[0], 12.0 / young, 1e-15, 0);
    CHECK_CLOSE(E[1], -nu * 12.0 / young, 1e-15, 0);
  }
  // M = C^-1 with C = I + 2E in a frame rotated by th: principal stretches l1, l2 along
  // (cos th, sin th) and (-sin th, cos th). A link along a principal axis is cut l_k times
  // shorter; any link, stretched by U, comes back to its design length.
  {
    const double l1 = 1.07, l2 = 0.96, th = 0.6, c = std::cos(th), s = std::sin(th);
    const double C[3] = {l1 * l1 * c * c + l2 * l2 * s * s, l1 * l1 * s * s + l2 * l2 * c * c,
                         (l1 * l1 - l2 * l2) * c * s};
    const double E[3] = {0.5 * (C[0] - 1.0), 0.5 * (C[1] - 1.0), 0.5 * C[2]};
    double M[3];
    CHECK(CompensationMetricFromStrain(E, M) == KERNEL_OK, "status");
    const double a1[2] = {c, s}, a2[2] = {-s, c};
    CHECK_CLOSE(CompensatedLength(M, 100.0, a1), 100.0 / l1, 1e-14, 0);
    CHECK_CLOSE(CompensatedLength(M, 100.0, a2), 100.0 / l2, 1e-14, 0);
    // U = l1 a1 a1^T + l2 a2 a2^T maps the cut vector back onto the design vector's length.
    for (double phi = 0.0; phi < 3.2; phi += 0.4) {
      const double d[2] = {std::cos(phi), std::sin(phi)};
      const double L0 = CompensatedLength(M, 1.0, d);
      // The cut vector is U^-1 d (same principal frame), of length L0.
      const double p1 = (d[0] * a1[0] + d[1] * a1[1]) / l1, p2 = (d[0] * a2[0] + d[1] * a2[1]) / l2;
      CHECK_CLOSE(std::hypot(p1, p2), L0, 1e-14, 0);
    }
  }
  // Uniform factors.
  {
    double M[3];
    CHECK(CompensationMetricUniform(0.02, 0.01, M) == KERNEL_OK, "status");
    const double x[2] = {3.0, 0.0}, y[2] = {0.0, -2.0};
    CHECK_CLOSE(CompensatedLength(M, 500.0, x), 500.0 / 1.02, 1e-15, 0);
    CHECK_CLOSE(CompensatedLength(M, 500.0, y), 500.0 / 1.01, 1e-15, 0);
    CHECK(CompensationMetricUniform(-1.0, 0.0, M) == KERNEL_DEGENERATE, "c = -1 refused");
  }
  // Bad input.
  {
    double E[3], M[3];
    const double S[3] = {NAN, 0.0, 0.0}, S1[3] = {1.0, 0.0, 0.0};
    CHECK(CompensationPlaneStressStrain(young, nu, S, E) == KERNEL_NONFINITE, "NaN stress");
    CHECK(CompensationPlaneStressStrain(young, 0.5, S1, E) == KERNEL_NONFINITE, "nu = 0.5");
    const double Ebad[3] = {-0.5, 0.0, 0.0};
    CHECK(CompensationMetricFromStrain(Ebad, M) == KERNEL_DEGENERATE, "C singular");
    const double zero[2] = {0.0, 0.0}, M1[3] = {1.0, 1.0, 0.0};
    CHECK(CompensatedLength(M1, 1.0, zero) < 0, "zero direction");
  }
  TEST_MAIN_END();
}
