// Hencky coefficients (src/verification/hencky_closed_form.cpp) against an independent solution of the
// same Foppl problem: the stress-function power series of Hencky/Chien. With F = r N_r
// (E h = p = a = 1) compatibility reads r F'' + F' - F/r = -r^4/(8 F^2); F = sum c_k r^(2k+1)
// gives a recurrence for c_k from c_0 = N0, and the clamped rim u(1) = 0 is F'(1) - nu F(1) = 0.
// The centre deflection is w0 = integral_0^1 r^2/(2F) dr = 1/4 integral_0^1 ds/G(s), with
// G(s) = sum c_k s^k, integrated term by term through the series of 1/G. Shooting + RK4 and this
// series share no code, so agreement to ~1e-10 checks both.
#include "etfe/verification/hencky_closed_form.h"

#include "check.h"

#include <cmath>

namespace {

constexpr int kTerms = 300;  // c_k decays like 1e-120 at k = 300 for nu in [0.3, 0.5]

// Residual of the rim condition for a centre force n0; *w0 gets the centre deflection.
double SeriesRim(double nu, double n0, double *w0) {
  double c[kTerms], q[kTerms], h[kTerms], d[kTerms];
  c[0] = n0;
  q[0] = n0 * n0;
  // G^2 H = -1/8 with H(s) = sum_j 4 (j+1)(j+2) c_{j+1} s^j, q = coefficients of G^2.
  for (int n = 0; n + 1 < kTerms; ++n) {
    double s = n == 0 ? -0.125 : 0.0;
    for (int m = 1; m <= n; ++m) s -= q[m] * h[n - m];
    h[n] = s / q[0];
    c[n + 1] = h[n] / (4.0 * (n + 1) * (n + 2));
    double qq = 0.0;
    for (int i = 0; i <= n + 1; ++i) qq += c[i] * c[n + 1 - i];
    q[n + 1] = qq;
  }
  double f = 0.0, df = 0.0;
  for (int k = 0; k < kTerms; ++k) {
    f += c[k];
    df += (2 * k + 1) * c[k];
  }
  d[0] = 1.0 / c[0];
  for (int n = 1; n < kTerms; ++n) {
    double s = 0.0;
    for (int i = 1; i <= n; ++i) s += c[i] * d[n - i];
    d[n] = -s / c[0];
  }
  double w = 0.0;
  for (int k = 0; k < kTerms; ++k) w += d[k] / (k + 1);
  *w0 = 0.25 * w;
  return df - nu * f;
}

void SeriesSolve(double nu, double *cw, double *cs) {
  double lo = 0.3, hi = 0.6, w = 0.0;
  const double flo = SeriesRim(nu, lo, &w);
  for (int it = 0; it < 100; ++it) {
    const double mid = 0.5 * (lo + hi);
    if ((SeriesRim(nu, mid, &w) < 0.0) == (flo < 0.0))
      lo = mid;
    else
      hi = mid;
  }
  *cs = 0.5 * (lo + hi);
  SeriesRim(nu, *cs, &w);
  *cw = w;
}

} // namespace

int main() {
  using etfe::HenckyCoefficients;
  using etfe::HenckyCoefficientsCompute;

  const double nus[3] = {0.3, 0.43, 0.5};
  HenckyCoefficients c[3];
  for (int k = 0; k < 3; ++k) {
    const int rc = HenckyCoefficientsCompute(nus[k], &c[k]);
    CHECK(rc == 0, "nu = %g: rc = %d", nus[k], rc);
    CHECK(std::isfinite(c[k].deflection) && std::isfinite(c[k].centre_stress), "nu = %g", nus[k]);
    double cw = 0.0, cs = 0.0;
    SeriesSolve(nus[k], &cw, &cs);
    std::printf("nu = %.2f  C_w = %.12f (series %.12f)  C_s = %.12f (series %.12f)\n", nus[k],
                c[k].deflection, cw, c[k].centre_stress, cs);
    CHECK_CLOSE(c[k].deflection, cw, 1e-10, 0.0);
    CHECK_CLOSE(c[k].centre_stress, cs, 1e-10, 0.0);
  }

  // nu = 0.3 against the literature. C_w = 0.6527 (header) is met within the requested 0.002;
  // the exact C_s is 0.4311 (= b0/4, b0 = 1.7244): the header's 0.4240 lies 0.007 away and is
  // the approximate energy solution's 0.423, so the check uses the exact value.
  CHECK(std::fabs(c[0].deflection - 0.6527) < 0.002, "C_w(0.3) = %.6f", c[0].deflection);
  CHECK(std::fabs(c[0].centre_stress - 0.4311) < 0.0005, "C_s(0.3) = %.6f", c[0].centre_stress);

  // A larger Poisson ratio raises the biaxial stiffness E/(1-nu) of the near-equibiaxial centre:
  // the deflection coefficient falls and the centre stress rises (monotone over 0.3..0.5).
  CHECK(c[0].deflection > c[1].deflection && c[1].deflection > c[2].deflection, "C_w order");
  CHECK(c[0].centre_stress < c[1].centre_stress && c[1].centre_stress < c[2].centre_stress,
        "C_s order");
  // Smooth in nu: second differences small against first differences.
  const double d1 = (c[1].deflection - c[0].deflection) / 0.13;
  const double d2 = (c[2].deflection - c[1].deflection) / 0.07;
  CHECK(std::fabs(d2 - d1) < 0.2 * std::fabs(d1), "C_w slopes %g %g", d1, d2);

  // Out-of-range Poisson ratios and a null output are refused.
  HenckyCoefficients bad{0.0, 0.0};
  CHECK(HenckyCoefficientsCompute(0.51, &bad) != 0, "nu = 0.51 accepted");
  CHECK(HenckyCoefficientsCompute(-1.0, &bad) != 0, "nu = -1 accepted");
  CHECK(HenckyCoefficientsCompute(std::nan(""), &bad) != 0, "nu = NaN accepted");
  CHECK(HenckyCoefficientsCompute(0.3, nullptr) != 0, "null output accepted");
  // The open end of the range still solves (auxetic limit).
  HenckyCoefficients aux{0.0, 0.0};
  CHECK(HenckyCoefficientsCompute(-0.9, &aux) == 0 && aux.deflection > c[0].deflection,
        "nu = -0.9: C_w = %g", aux.deflection);

  TEST_MAIN_END();
}
