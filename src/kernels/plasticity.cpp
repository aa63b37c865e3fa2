// ETFE elasto-plasticity: plane-stress von Mises return map with piecewise-linear isotropic
// hardening (docs/theory.md §3.2; thesis §4.2.1, eqs. 4.9-4.21, Table 4.2). Pure C++17, no
// allocation.
//
// Formulation
//  * Strain-driven, small strain on top of large displacement: the Green-Lagrange strain
//    E = (Exx, Eyy, 2Exy) splits additively, E = Ee + Ep, and the 2nd Piola-Kirchhoff stress is
//    S = (Sxx, Syy, Sxy) = D (E - Ep) with the plane-stress D of eq. 4.10. Units: stresses and
//    moduli in MPa, strains dimensionless, the plastic multiplier dl in 1/MPa.
//  * Yield function f = 1/2 S^T P S - 1/3 Sy(ep_bar)^2 with P of eq. 4.16, so that
//    S^T P S = 2/3 Smises^2 (eq. 4.9). Associated flow Ep_{n+1} = Ep_n + dl P S_{n+1} (eq. 4.12,
//    dl = 3/2 dep_bar / Smises), hence dep_bar = 2/3 dl Smises = dl sqrt(2/3 S^T P S). In uniaxial
//    stress ep_bar is then the axial plastic strain, the quantity Table 4.2 is fitted to, and the
//    uniaxial S-E slope on segment k is E H[k] / (E + H[k]).
//  * Backward Euler (Simo & Taylor 1986): S_{n+1} = Xi(dl) (E - Ep_n), Xi = (D^-1 + dl P)^-1.
//    D and P share the eigenvectors (1,1,0)/sqrt2, (1,-1,0)/sqrt2, (0,0,1) (the matrix Q of
//    eq. 4.17), so Xi and S(dl) are closed-form (eq. 4.18) and consistency is one scalar equation
//    in dl (eq. 4.19, with the single-slope law of eq. 4.20 replaced by the piecewise-linear one).
//    We write it as Smises(dl) = Sy(ep_n + 2/3 dl Smises(dl)) instead of the squared form:
//    Smises(dl) decreases and dl Smises(dl) increases, so Smises - Sy is strictly decreasing for
//    any H >= 0, a root bracket is known before the first iteration, and a Newton step that
//    jumps over a kink of Sy can always fall back to bisection. Newton runs on
//    r(dl) = 1/Sy - 1/Smises, which is linear in dl for a single stress mode without hardening
//    (1/Smises = (1 + c dl)/Smises_trial) and so converges in a few steps even for trial stresses
//    far outside the yield surface; convergence is judged on |Smises - Sy| <= 1e-13 Sy.
//  * Linearisation (Simo & Taylor 1985, eq. 4.21): with N = Xi P S, H the slope of the segment
//    the converged ep_bar lies on and a = 1 - 2/3 H dl = 1/gamma,
//        D_ep = Xi - a N N^T / (a S^T P Xi P S + 4/9 H Smises^2).
//    This is eq. 4.21 multiplied through by a: the same matrix, but it stays finite when a -> 0,
//    which a later segment that is much stiffer than the earlier ones can cause. It is the exact
//    derivative dS/dE of the discrete map, which keeps the global Newton quadratic.
#include "etfe/kernels/plasticity.h"

#include <cfloat>
#include <cmath>
#include <cstdio>

#include "etfe/kernels/status.h"

namespace etfe {
namespace {

// Bisection alone halves the bracket each time, so 200 iterations pin the root to rounding
// long before the cap; reaching it means non-finite arithmetic, reported as no convergence.
constexpr int kMaxLocalIterations = 200;
constexpr double kLocalRelTol = 1e-13;

// Keeps the fixed-size arrays safe for a material nobody checked; PlasticMaterialCheck reports it.
int SegmentCount(const PlasticMaterial &m) {
  if (m.nseg < 1) return 1;
  return m.nseg > kMaxHardeningSegments ? kMaxHardeningSegments : m.nseg;
}

void ElasticTangent(const PlasticMaterial &m, double D[9]) {
  const double f = m.young / (1.0 - m.nu * m.nu);
  D[0] = f;         D[1] = f * m.nu;  D[2] = 0.0;
  D[3] = f * m.nu;  D[4] = f;         D[5] = 0.0;
  D[6] = 0.0;       D[7] = 0.0;       D[8] = 0.5 * f * (1.0 - m.nu);
}

// The trial state in the common eigenbasis of D and P: Smises(dl)^2 = A/a^2 + B/b^2 with
// a = 1 + c1 dl (equibiaxial mode) and b = 1 + c2 dl (the two deviatoric modes).
struct TrialModes {
  double sum, dif, s12;  // the trial stress's mode amplitudes: Sxx + Syy, Sxx - Syy, Sxy
  double A, B;
  double c1, c2;
  double ep_n;
};

TrialModes TrialInEigenbasis(const PlasticMaterial &m, const double St[3], double ep_n) {
  TrialModes t;
  t.sum = St[0] + St[1];
  t.dif = St[0] - St[1];
  t.s12 = St[2];
  t.A = 0.25 * t.sum * t.sum;
  t.B = 0.75 * t.dif * t.dif + 3.0 * t.s12 * t.s12;
  t.c1 = m.young / (3.0 * (1.0 - m.nu));
  t.c2 = m.young / (1.0 + m.nu);
  t.ep_n = ep_n;
  return t;
}

struct LocalEval {
  double g;      // consistency residual Smises - Sy (the convergence measure)
  double r, dr;  // 1/Sy - 1/Smises, the function Newton iterates on, and its derivative in dl
  double q;      // Mises stress at dl
  double ep;     // equivalent plastic strain at dl
  double H;      // hardening slope there
};

void EvaluateConsistency(const PlasticMaterial &m, const TrialModes &t, double dl, LocalEval *ev) {
  const double ia = 1.0 / (1.0 + t.c1 * dl);
  const double ib = 1.0 / (1.0 + t.c2 * dl);
  const double q = std::sqrt(t.A * ia * ia + t.B * ib * ib);
  const double dq = -(t.A * t.c1 * ia * ia * ia + t.B * t.c2 * ib * ib * ib) / q;
  ev->q = q;
  ev->ep = t.ep_n + (2.0 / 3.0) * dl * q;
  const double sy = PlasticYieldStress(m, ev->ep, &ev->H);
  const double dsy = ev->H * (2.0 / 3.0) * (q + dl * dq);
  ev->g = q - sy;
  ev->r = 1.0 / sy - 1.0 / q;
  ev->dr = -dsy / (sy * sy) + dq / (q * q);
}

// The plastic multiplier dl at which Smises(dl) = Sy(ep_n + 2/3 dl Smises(dl)), with ev the state
// there. False when no bracket exists or the iteration does not converge.
bool SolveConsistency(const PlasticMaterial &m, const TrialModes &t, double q_trial, double sy_n, double *dl_out,
                      LocalEval *ev_out) {
  // Every mode shrinks at least as fast as 1/(1 + min(c1,c2) dl), so at this dl the Mises stress
  // is at most sy_n <= Sy(ep): g <= 0 there and the root lies in [0, hi].
  double hi = (q_trial / sy_n - 1.0) / std::fmin(t.c1, t.c2);
  if (!(std::isfinite(hi) && hi > 0.0)) return false;
  double lo = 0.0;
  double dl = 0.0;
  LocalEval ev;
  EvaluateConsistency(m, t, dl, &ev);
  const double tol = kLocalRelTol * sy_n;
  double r_prev = HUGE_VAL;
  double H_prev = ev.H;
  bool kink_pass = true;
  bool converged = false;
  for (int it = 0; it < kMaxLocalIterations; ++it) {
    if (!(std::isfinite(ev.g) && std::isfinite(ev.r) && std::isfinite(ev.dr))) break;
    if (std::fabs(ev.g) <= tol) {
      converged = true;
      break;
    }
    if (ev.r > 0.0) {
      lo = dl;
    } else {
      hi = dl;
    }
    // The bracket is at the rounding level of dl: g cannot get any smaller than it is.
    if (hi - lo <= 4.0 * DBL_EPSILON * hi) {
      converged = true;
      break;
    }
    // Newton unless it leaves the bracket or the last Newton step did not halve the residual;
    // then bisect, and let the next step try Newton again, so the bracket at least halves every
    // second iteration. The first step that lands on a new hardening segment is exempt once:
    // it was taken with the old segment's slope, and the new slope is usually accurate.
    const double newton = ev.dr < 0.0 ? dl - ev.r / ev.dr : hi;
    bool stalled = std::fabs(ev.r) > 0.5 * r_prev;
    if (stalled && kink_pass && ev.H != H_prev) {
      stalled = false;
      kink_pass = false;
    }
    H_prev = ev.H;
    if (newton > lo && newton < hi && !stalled) {
      dl = newton;
      r_prev = std::fabs(ev.r);
    } else {
      dl = 0.5 * (lo + hi);
      r_prev = HUGE_VAL;
    }
    EvaluateConsistency(m, t, dl, &ev);
  }
  *dl_out = dl;
  *ev_out = ev;
  return converged;
}

// At the converged dl: the returned stress Sn, the flow direction PS = P Sn and the consistent
// tangent Dep = Xi - coef N N^T (eq. 4.21 multiplied through by a).
void ReturnedStressAndTangent(const PlasticMaterial &m, const TrialModes &t, double dl, const LocalEval &ev,
                              double Sn[3], double PS[3], double Dep[9], double *coef) {
  const double ia = 1.0 / (1.0 + t.c1 * dl);
  const double ib = 1.0 / (1.0 + t.c2 * dl);
  Sn[0] = 0.5 * (t.sum * ia + t.dif * ib);
  Sn[1] = 0.5 * (t.sum * ia - t.dif * ib);
  Sn[2] = t.s12 * ib;
  PS[0] = (2.0 * Sn[0] - Sn[1]) / 3.0, PS[1] = (2.0 * Sn[1] - Sn[0]) / 3.0, PS[2] = 2.0 * Sn[2];

  // Xi in the shared eigenbasis: eigenvalues d_i / (1 + dl d_i p_i) with D-eigenvalues
  // E/(1-nu), 2G, G and P-eigenvalues 1/3, 1, 2.
  const double G = 0.5 * m.young / (1.0 + m.nu);
  const double x1 = m.young / (1.0 - m.nu) * ia;
  const double x2 = 2.0 * G * ib;
  const double x3 = G * ib;
  const double Xi[9] = {0.5 * (x1 + x2), 0.5 * (x1 - x2), 0.0,
                        0.5 * (x1 - x2), 0.5 * (x1 + x2), 0.0,
                        0.0,             0.0,             x3};
  const double N[3] = {Xi[0] * PS[0] + Xi[1] * PS[1], Xi[3] * PS[0] + Xi[4] * PS[1], x3 * PS[2]};
  const double pxp = PS[0] * N[0] + PS[1] * N[1] + PS[2] * N[2];
  const double a = 1.0 - (2.0 / 3.0) * ev.H * dl;
  const double den = a * pxp + (4.0 / 9.0) * ev.H * ev.q * ev.q;
  *coef = a / den;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) Dep[3 * i + j] = Xi[3 * i + j] - *coef * N[i] * N[j];
  }
}

// Leaves the history untouched and a usable (elastic) tangent so that a caller that ignores the
// status still sees no garbage; the assembler is expected to reject the step anyway.
int Fail(int status, const PlasticMaterial &m, const PlasticState &c, PlasticState *trial,
         double S[3], double D[9]) {
  *trial = c;
  S[0] = S[1] = S[2] = 0.0;
  ElasticTangent(m, D);
  return status;
}

} // namespace

int PlasticMaterialCheck(const PlasticMaterial &m, char *msg, int msglen) {
  char local[1];
  if (msg == nullptr || msglen <= 0) {
    msg = local;
    msglen = 1;
  }
  msg[0] = '\0';
  if (!(std::isfinite(m.young) && m.young > 0.0)) {
    std::snprintf(msg, (size_t)msglen, "Young's modulus must be finite and > 0 (got %g)", m.young);
    return 1;
  }
  if (!(std::isfinite(m.nu) && m.nu > -1.0 && m.nu < 0.5)) {
    std::snprintf(msg, (size_t)msglen, "Poisson's ratio must lie in (-1, 0.5) (got %g)", m.nu);
    return 1;
  }
  if (m.nseg < 1 || m.nseg > kMaxHardeningSegments) {
    std::snprintf(msg, (size_t)msglen, "number of hardening segments must be in [1, %d] (got %d)",
                  kMaxHardeningSegments, m.nseg);
    return 1;
  }
  for (int k = 0; k < m.nseg; ++k) {
    if (!(std::isfinite(m.yield[k]) && m.yield[k] > 0.0)) {
      std::snprintf(msg, (size_t)msglen, "yield stress %d must be finite and > 0 (got %g)", k,
                    m.yield[k]);
      return 1;
    }
    if (k > 0 && !(m.yield[k] > m.yield[k - 1])) {
      std::snprintf(msg, (size_t)msglen,
                    "yield stresses must increase: yield[%d] = %g <= yield[%d] = %g", k,
                    m.yield[k], k - 1, m.yield[k - 1]);
      return 1;
    }
    if (!(std::isfinite(m.H[k]) && m.H[k] >= 0.0)) {
      std::snprintf(msg, (size_t)msglen, "hardening modulus H[%d] must be finite and >= 0 (got %g)",
                    k, m.H[k]);
      return 1;
    }
    // A flat segment never reaches the next yield stress, which would silently drop the rest of
    // the curve; only the last segment may be perfectly plastic.
    if (k + 1 < m.nseg && !(m.H[k] > 0.0)) {
      std::snprintf(msg, (size_t)msglen,
                    "H[%d] = 0 makes yield[%d] unreachable; only the last segment may have H = 0",
                    k, k + 1);
      return 1;
    }
  }
  return 0;
}

double PlasticYieldStress(const PlasticMaterial &m, double ep_bar, double *slope) {
  const int n = SegmentCount(m);
  // A negative history value can only come from round-off or bad input; the virgin yield stress
  // is the safe reading. NaN passes through (the comparisons below are false for it).
  const double ep = ep_bar < 0.0 ? 0.0 : ep_bar;
  int k = 0;
  double ep_k = 0.0;
  while (k + 1 < n) {
    // Breakpoints follow from the yields and slopes, so the curve is continuous by construction.
    const double next = ep_k + (m.yield[k + 1] - m.yield[k]) / m.H[k];
    if (!(ep >= next)) break;  // at a kink the segment starting there is the current one
    ep_k = next;
    ++k;
  }
  if (slope) *slope = m.H[k];
  return m.yield[k] + m.H[k] * (ep - ep_k);
}

int PlasticReturnMap(const PlasticMaterial &m, const double E[3], const PlasticState &committed,
                     PlasticState *trial, double S[3], double D[9]) {
  const PlasticState c = committed;  // trial may alias committed
  const double Ein[3] = {E[0], E[1], E[2]};
  if (!(std::isfinite(Ein[0]) && std::isfinite(Ein[1]) && std::isfinite(Ein[2]) &&
        std::isfinite(c.ep[0]) && std::isfinite(c.ep[1]) && std::isfinite(c.ep[2]) &&
        std::isfinite(c.ep_bar))) {
    return Fail(KERNEL_NONFINITE, m, c, trial, S, D);
  }

  double De[9];
  ElasticTangent(m, De);
  const double ee[3] = {Ein[0] - c.ep[0], Ein[1] - c.ep[1], Ein[2] - c.ep[2]};
  const double St[3] = {De[0] * ee[0] + De[1] * ee[1], De[3] * ee[0] + De[4] * ee[1],
                        De[8] * ee[2]};
  const TrialModes t = TrialInEigenbasis(m, St, c.ep_bar);
  const double q_trial = std::sqrt(t.A + t.B);
  const double sy_n = PlasticYieldStress(m, c.ep_bar, nullptr);
  if (!(std::isfinite(q_trial) && std::isfinite(sy_n))) {
    return Fail(KERNEL_NONFINITE, m, c, trial, S, D);
  }

  // A trial on the yield surface to round-off (the committed state itself, at the first Newton
  // iterate of an increment) is elastic: its tangent must be the elastic one, or an increment
  // that unloads starts with the soft plastic tangent and a Newton direction of no descent.
  if (q_trial <= sy_n * (1.0 + 1e-10)) {
    *trial = c;
    for (int i = 0; i < 3; ++i) S[i] = St[i];
    for (int i = 0; i < 9; ++i) D[i] = De[i];
    return KERNEL_OK;
  }

  double dl;
  LocalEval ev;
  if (!SolveConsistency(m, t, q_trial, sy_n, &dl, &ev)) return Fail(KERNEL_NO_CONVERGENCE, m, c, trial, S, D);
  double Sn[3], PS[3], Dep[9], coef;
  ReturnedStressAndTangent(m, t, dl, ev, Sn, PS, Dep, &coef);

  PlasticState out;
  for (int i = 0; i < 3; ++i) out.ep[i] = c.ep[i] + dl * PS[i];
  out.ep_bar = ev.ep;
  bool finite = std::isfinite(out.ep_bar) && std::isfinite(coef);
  for (int i = 0; i < 3; ++i) finite = finite && std::isfinite(Sn[i]) && std::isfinite(out.ep[i]);
  for (int i = 0; i < 9; ++i) finite = finite && std::isfinite(Dep[i]);
  if (!finite) return Fail(KERNEL_NONFINITE, m, c, trial, S, D);

  *trial = out;
  for (int i = 0; i < 3; ++i) S[i] = Sn[i];
  for (int i = 0; i < 9; ++i) D[i] = Dep[i];
  return KERNEL_OK;
}

} // namespace etfe
