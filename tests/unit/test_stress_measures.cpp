// Cauchy stress, its Mises value and the principal stresses of the membrane against closed forms:
// a uniaxial stretch (sigma = lambda^2 S with the incompressible thickness), rigid rotations (the
// tensor rotates, its invariants do not), and random states (eigen-equations, orthonormal tangent
// directions, Mises equals the plane-stress formula of the principal values).
#include <cmath>
#include <random>

#include "check.h"
#include "etfe/kernels/stress_measures.h"

using namespace etfe;

namespace {

void Apply(const double s[6], const double v[3], double out[3]) {
  out[0] = s[0] * v[0] + s[3] * v[1] + s[5] * v[2];
  out[1] = s[3] * v[0] + s[1] * v[1] + s[4] * v[2];
  out[2] = s[5] * v[0] + s[4] * v[1] + s[2] * v[2];
}

double Dot(const double a[3], const double b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

} // namespace

int main() {
  // Uniaxial: F = diag(lambda, mu) in the plane z = 0, S = (s, 0, 0).
  {
    const double lambda = 1.2, mu = 0.95, s = 13.28;
    const double F[6] = {lambda, 0, 0, mu, 0, 0}, S[3] = {s, 0, 0};
    double sig[6], p[2], d1[3], d2[3];
    CauchyStress(F, S, sig);
    CHECK_CLOSE(sig[0], lambda * lambda * s, 1e-14, 0);
    CHECK_CLOSE(sig[1], 0.0, 0, 1e-14);
    CHECK_CLOSE(MisesStress3(sig), lambda * lambda * s, 1e-14, 0);
    PrincipalStresses(F, sig, p, d1, d2);
    CHECK_CLOSE(p[0], lambda * lambda * s, 1e-14, 0);
    CHECK_CLOSE(std::fabs(d1[0]), 1.0, 1e-14, 0);
  }
  // Rigid rotation of the current configuration: sigma rotates (R sigma R^T), invariants stay.
  {
    const double F0[6] = {1.1, 0.05, 0.02, 0.97, 0.0, 0.0}, S[3] = {10.0, 4.0, 2.5};
    const double a = 0.7, b = -0.4;
    const double R[9] = {std::cos(a), -std::sin(a) * std::cos(b), std::sin(a) * std::sin(b),
                         std::sin(a), std::cos(a) * std::cos(b), -std::cos(a) * std::sin(b),
                         0.0, std::sin(b), std::cos(b)};
    double F1[6];
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 2; ++j) F1[2 * i + j] = R[3 * i] * F0[j] + R[3 * i + 1] * F0[2 + j] + R[3 * i + 2] * F0[4 + j];
    double s0[6], s1[6], p0[2], p1[2], d[3], e[3];
    CauchyStress(F0, S, s0);
    CauchyStress(F1, S, s1);
    CHECK_CLOSE(MisesStress3(s1), MisesStress3(s0), 1e-13, 0);
    PrincipalStresses(F0, s0, p0, d, e);
    PrincipalStresses(F1, s1, p1, d, e);
    CHECK_CLOSE(p1[0], p0[0], 1e-13, 1e-13);
    CHECK_CLOSE(p1[1], p0[1], 1e-13, 1e-13);
  }
  // Random states: eigen-equations in the tangent plane, orthonormal directions, Mises.
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  for (int k = 0; k < 500; ++k) {
    double F[6], S[3] = {20 * U(rng), 20 * U(rng), 10 * U(rng)};
    for (double &x : F) x = U(rng);
    F[0] += 1.5, F[3] += 1.5;  // non-degenerate
    double sig[6], p[2], d1[3], d2[3], r[3];
    CauchyStress(F, S, sig);
    PrincipalStresses(F, sig, p, d1, d2);
    const double scale = std::fabs(p[0]) + std::fabs(p[1]) + 1e-300;
    Apply(sig, d1, r);
    for (int i = 0; i < 3; ++i) CHECK_CLOSE(r[i], p[0] * d1[i], 0, 1e-12 * scale);
    Apply(sig, d2, r);
    for (int i = 0; i < 3; ++i) CHECK_CLOSE(r[i], p[1] * d2[i], 0, 1e-12 * scale);
    CHECK(p[0] >= p[1], "p = %g %g", p[0], p[1]);
    CHECK_CLOSE(Dot(d1, d1), 1.0, 1e-13, 0);
    CHECK_CLOSE(Dot(d1, d2), 0.0, 0, 1e-13);
    CHECK_CLOSE(MisesStress3(sig), std::sqrt(p[0] * p[0] + p[1] * p[1] - p[0] * p[1]), 1e-12, 1e-12 * scale);
    // Symmetry: sigma = F S F^T is symmetric by construction; its trace equals p0 + p1.
    CHECK_CLOSE(sig[0] + sig[1] + sig[2], p[0] + p[1], 1e-12, 1e-12 * scale);
  }
  TEST_MAIN_END();
}
