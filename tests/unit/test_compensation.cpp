// Compensation kernels (etfe/kernels/compensation.h):
//  * the plane-stress strain of a stress, put through the solver's elastic law, gives the stress
//    back (so a pattern compensated with it reaches the prestress);
//  * the rest metric M = (I + 2E)^-1 inverts C: a link cut with M's length and stretched by the
//    stretch U = C^1/2 is the design length again, in any direction (closed form for a rotated
//    principal frame);
//  * uniform factors: cut MD/TD lengths are 1/(1 + c) of the design;
//  * an element's MD/TD stress turned into the pattern's axes by the triangle's own map;
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
  // The element frame carried into the pattern: a triangle tilted out of the XY plane, its
  // pattern turned by an angle; MD = global X projected on the triangle. The stress in pattern
  // axes has the same invariants and its MD direction is where the triangle's map sends X.
  {
    const double tilt = 0.4, turn = 0.7;
    const double P[3][2] = {{0.0, 0.0}, {100.0, 20.0}, {30.0, 80.0}};  // in-plane coordinates
    double X[9], xy[6];
    for (int k = 0; k < 3; ++k) {
      // the plane spanned by the orthonormal u = (1, 0, 0), v = (0, cos tilt, sin tilt)
      X[3 * k] = P[k][0];
      X[3 * k + 1] = P[k][1] * std::cos(tilt);
      X[3 * k + 2] = P[k][1] * std::sin(tilt);
      xy[2 * k] = std::cos(turn) * P[k][0] - std::sin(turn) * P[k][1];
      xy[2 * k + 1] = std::sin(turn) * P[k][0] + std::cos(turn) * P[k][1];
    }
    const double md[3] = {1.0, 0.0, 0.0}, S[3] = {6.0, 2.0, 1.0};
    double Sp[3];
    CHECK(CompensationStressInPattern(X, xy, md, S, Sp) == KERNEL_OK, "status");
    // MD (global X = in-plane u) goes to the direction 'turn' in the pattern.
    const double c = std::cos(turn), s = std::sin(turn);
    CHECK_CLOSE(Sp[0], c * c * 6.0 + s * s * 2.0 - 2 * c * s * 1.0, 1e-13, 1e-13);
    CHECK_CLOSE(Sp[1], s * s * 6.0 + c * c * 2.0 + 2 * c * s * 1.0, 1e-13, 1e-13);
    CHECK_CLOSE(Sp[2], c * s * (6.0 - 2.0) + (c * c - s * s) * 1.0, 1e-13, 1e-13);
    CHECK_CLOSE(Sp[0] + Sp[1], 8.0, 1e-14, 0);  // trace kept
    // MD along the normal: the edge 0 -> 1 is MD instead.
    const double normal[3] = {0.0, -std::sin(tilt), std::cos(tilt)};
    CHECK(CompensationStressInPattern(X, xy, normal, S, Sp) == KERNEL_OK, "status");
    const double th = std::atan2(xy[3] - xy[1], xy[2] - xy[0]), c2 = std::cos(th), s2 = std::sin(th);
    CHECK_CLOSE(Sp[0], c2 * c2 * 6.0 + s2 * s2 * 2.0 - 2 * c2 * s2 * 1.0, 1e-12, 1e-12);
    const double flat[6] = {0, 0, 1, 0, 2, 0};
    CHECK(CompensationStressInPattern(X, flat, md, S, Sp) == KERNEL_DEGENERATE, "degenerate pattern triangle");
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
