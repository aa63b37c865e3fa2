// Hencky's problem (clamped circular membrane under uniform pressure, Foppl theory): the
// similarity coefficients C_w, C_s of w0 = C_w a (p a/(E h))^(1/3) and
// sigma0 = C_s (E p^2 a^2/h^2)^(1/3), used as a closed-form check of the membrane element and the
// pressure load (docs/theory.md §4, §13; thesis §5.4 pressurization). Hencky's 1915 numbers contain
// an error (corrected by Chien 1948, Alekseev 1951) and published tables differ in the third digit,
// so the coefficients are computed here rather than copied. This solve gives C_w(0.3) = 0.653443,
// C_s(0.3) = 0.431101 (b0 = 4 C_s = 1.7244 in the normalisation of Hencky's series), confirmed to
// ~1e-13 by an independent power-series solution in tests/unit/test_hencky_closed_form.cpp.
// C_s = 0.423/0.424, quoted in places, matches the approximate energy solution (Timoshenko), not
// the exact Foppl value.
//
// Axisymmetric Foppl equations (a = 1, E h = 1, p = 1, so C_w = w0 and C_s = N0):
//   d(r N_r)/dr = N_theta,  N_r = C(eps_r + nu eps_theta),  N_theta = C(eps_theta + nu eps_r),
//   eps_r = u' + w'^2/2,  eps_theta = u/r,  w' = -p r/(2 N_r),  C = E h/(1-nu^2).
// In t = ln r with v = u/r the system loses its 1/r singularity:
//   dN/dt = E h v - (1-nu) N
//   dv/dt = N/C - (1+nu) v - p^2 r^2/(8 N^2)
//   dW/dt = p r^2/(2 N)          (W = integral_0^r p s/(2 N_r) ds, so w0 = W(1))
// Its linear part has eigenvalues 0 (the N0 family) and -2, so fixed RK4 steps in t are
// non-stiff and the grid is automatically fine near the centre. Start at r0 from the regular
// series N = N0 - r^2/(64 N0^2), v = (1-nu) N0 - (3-nu) r^2/(64 N0^2), shoot on N0 until
// u(1) = v(1) = 0 (bracket + bisection), and remove the O(dt^4) error by Richardson
// extrapolation of two step sizes.
#include "etfe/verification/hencky_closed_form.h"

#include <cmath>

namespace etfe {

namespace {

constexpr double kR0 = 1e-3;  // series truncation error O(r0^4) ~ 1e-12

struct HenckyRhs {
  double nu;
  double inv_c;  // 1/C = 1 - nu^2 (E h = 1)
};

// Returns false when N_r reaches zero or a non-finite value: N0 is then far too small.
inline bool Rhs(const HenckyRhs &q, double t, const double y[3], double dy[3]) {
  const double n = y[0];
  if (!(n > 0.0) || !std::isfinite(y[1])) return false;
  const double r2 = std::exp(2.0 * t);
  dy[0] = y[1] - (1.0 - q.nu) * n;
  dy[1] = q.inv_c * n - (1.0 + q.nu) * y[1] - r2 / (8.0 * n * n);
  dy[2] = r2 / (2.0 * n);
  return true;
}

// Integrates from r0 to 1 for the centre force N0 with `steps` RK4 steps in ln r. On success
// *v1 = u(1)/1 and *w0 = centre deflection.
bool Shoot(const HenckyRhs &q, double n0, int steps, double *v1, double *w0) {
  const double r02 = kR0 * kR0;
  const double s = r02 / (64.0 * n0 * n0);
  double y[3] = {n0 - s, (1.0 - q.nu) * n0 - (3.0 - q.nu) * s, r02 / (4.0 * n0)};
  const double t0 = std::log(kR0);
  const double dt = -t0 / steps;
  double k1[3], k2[3], k3[3], k4[3], z[3];
  for (int k = 0; k < steps; ++k) {
    const double t = t0 + k * dt;
    if (!Rhs(q, t, y, k1)) return false;
    for (int i = 0; i < 3; ++i) z[i] = y[i] + 0.5 * dt * k1[i];
    if (!Rhs(q, t + 0.5 * dt, z, k2)) return false;
    for (int i = 0; i < 3; ++i) z[i] = y[i] + 0.5 * dt * k2[i];
    if (!Rhs(q, t + 0.5 * dt, z, k3)) return false;
    for (int i = 0; i < 3; ++i) z[i] = y[i] + dt * k3[i];
    if (!Rhs(q, t + dt, z, k4)) return false;
    for (int i = 0; i < 3; ++i) y[i] += dt / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
  }
  if (!(y[0] > 0.0) || !std::isfinite(y[1]) || !std::isfinite(y[2])) return false;
  *v1 = y[1];
  *w0 = y[2];
  return true;
}

// u(1) grows with N0 (a stiffer centre pulls less of the rim inward): a failed integration
// means N0 is too small, i.e. a negative residual.
double Residual(const HenckyRhs &q, double n0, int steps, double *w0) {
  double v1 = 0.0;
  if (!Shoot(q, n0, steps, &v1, w0)) return -HUGE_VAL;
  return v1;
}

// Solves for N0 at a fixed step count; returns false when no bracket is found.
bool SolveFixedSteps(const HenckyRhs &q, int steps, double *n0, double *w0) {
  double lo = 0.1, hi = 1.0, w = 0.0;
  int tries = 0;
  while (Residual(q, lo, steps, &w) >= 0.0) {
    lo *= 0.5;
    if (++tries > 60) return false;
  }
  tries = 0;
  while (Residual(q, hi, steps, &w) <= 0.0) {
    hi *= 2.0;
    if (++tries > 60) return false;
  }
  // Bisection down to rounding: ~50 shots, milliseconds; robust where the residual is -inf.
  for (int it = 0; it < 200 && hi - lo > 4e-16 * hi; ++it) {
    const double mid = 0.5 * (lo + hi);
    if (Residual(q, mid, steps, &w) < 0.0)
      lo = mid;
    else
      hi = mid;
  }
  *n0 = 0.5 * (lo + hi);
  double v1 = 0.0;
  return Shoot(q, *n0, steps, &v1, w0);
}

} // namespace

int HenckyCoefficientsCompute(double nu, HenckyCoefficients *c) {
  if (!c || !(nu > -1.0 && nu <= 0.5)) return 1;
  const HenckyRhs q{nu, 1.0 - nu * nu};

  // Two step sizes: RK4's error is O(dt^4), so (16 R_fine - R_coarse)/15 cancels it; the
  // difference of the two bounds what is left (~1e-13 at these sizes against the series check).
  constexpr int kCoarse = 2000;
  double n_c = 0.0, w_c = 0.0, n_f = 0.0, w_f = 0.0;
  if (!SolveFixedSteps(q, kCoarse, &n_c, &w_c)) return 2;
  if (!SolveFixedSteps(q, 2 * kCoarse, &n_f, &w_f)) return 2;
  const double n0 = (16.0 * n_f - n_c) / 15.0;
  const double w0 = (16.0 * w_f - w_c) / 15.0;
  if (std::fabs(n_f - n_c) > 1e-8 * n_f || std::fabs(w_f - w_c) > 1e-8 * w_f) return 3;
  if (!std::isfinite(n0) || !std::isfinite(w0)) return 3;
  c->deflection = w0;
  c->centre_stress = n0;
  return 0;
}

} // namespace etfe
