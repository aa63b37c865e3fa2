// ETFE viscoelastic-plastic law (see viscoelastic_plastic.h). Pure C++17, no allocation.
//
// Formulation
//  * Small strain on top of large displacement as the plastic law: E = Ee + Ep additively, the
//    plastic strain Ep flows by the plane-stress von Mises return map of plasticity.cpp.
//  * The elastic strain Ee drives a generalized Maxwell solid (Simo & Hughes 1998, §10.3): an
//    equilibrium spring g_inf E0 and Maxwell branches (g_i E0, tau_i), all with the one Poisson's
//    ratio, so every branch's stress is a multiple of the instantaneous elastic stress
//    S0 = D0 Ee (D0 the plane-stress matrix of E0, nu). The internal stresses h_i integrate
//    exactly for Ee linear in time over the step (the recursion in the header), which is
//    unconditionally stable and exact in relaxation (Ee held) for any step.
//  * The yield function sees the total stress S = g_inf S0 + sum h_i; the flow is associated
//    with it. Relaxation therefore moves a state inside the yield surface, and a fast load yields
//    at the instantaneous stress. Within a step S = geff D0 (E - Ep) + Shist with
//        geff  = g_inf + sum_i g_i gamma_i,   Shist = sum_i (exp(-dt/tau_i) h_i,n - g_i gamma_i S0_n),
//    so S is the plastic law's stress for the modulus geff E0 at the shifted strain
//    E~ = E + (geff D0)^-1 Shist: the plastic return map (Simo & Taylor) solves the step and its
//    consistent tangent dS/dE~ = dS/dE is the algorithmic tangent of this law.
//  * Units: MPa, seconds (reduced time), strains dimensionless.
#include "etfe/kernels/viscoelastic_plastic.h"

#include <cmath>
#include <cstdio>
#include <cstring>

#include "etfe/kernels/status.h"

namespace etfe {
namespace {

// gamma = (1 - exp(-x)) / x for x = dt/tau >= 0, 1 at x = 0 (the instantaneous response).
double StepFactor(double x) { return x > 0.0 ? -std::expm1(-x) / x : 1.0; }

int Terms(const ViscoelasticPlasticMaterial &m) {
  if (m.nterms < 0) return 0;
  return m.nterms > kMaxPronyTerms ? kMaxPronyTerms : m.nterms;
}

// S = D0(young, nu) e in Voigt notation (engineering shear strain).
void PlaneStress(double young, double nu, const double e[3], double S[3]) {
  const double f = young / (1.0 - nu * nu);
  S[0] = f * (e[0] + nu * e[1]);
  S[1] = f * (nu * e[0] + e[1]);
  S[2] = 0.5 * f * (1.0 - nu) * e[2];
}

} // namespace

int ViscoelasticPlasticMaterialCheck(const ViscoelasticPlasticMaterial &m, char *msg, int msglen) {
  char local[1];
  if (msg == nullptr || msglen <= 0) {
    msg = local;
    msglen = 1;
  }
  if (int code = PlasticMaterialCheck(m.plastic, msg, msglen)) return code;
  if (m.nterms < 0 || m.nterms > kMaxPronyTerms) {
    std::snprintf(msg, (size_t)msglen, "number of Prony terms must be in [0, %d] (got %d)", kMaxPronyTerms,
                  m.nterms);
    return 1;
  }
  double sum = 0.0;
  for (int i = 0; i < m.nterms; ++i) {
    if (!(std::isfinite(m.tau[i]) && m.tau[i] > 0.0)) {
      std::snprintf(msg, (size_t)msglen, "relaxation time %d must be finite and > 0 s (got %g)", i, m.tau[i]);
      return 1;
    }
    if (i > 0 && !(m.tau[i] > m.tau[i - 1])) {
      std::snprintf(msg, (size_t)msglen,
                    "relaxation times must increase: tau[%d] = %g <= tau[%d] = %g (sort the spectrum, its moduli "
                    "with it)",
                    i, m.tau[i], i - 1, m.tau[i - 1]);
      return 1;
    }
    if (!(std::isfinite(m.g[i]) && m.g[i] > 0.0)) {
      std::snprintf(msg, (size_t)msglen, "modulus fraction g[%d] must be finite and > 0 (got %g)", i, m.g[i]);
      return 1;
    }
    sum += m.g[i];
  }
  if (!(sum < 1.0)) {
    std::snprintf(msg, (size_t)msglen,
                  "the modulus fractions sum to %g: they must sum to < 1 (the rest is the relaxed modulus)", sum);
    return 1;
  }
  return 0;
}

double ViscoelasticPlasticRelaxationFraction(const ViscoelasticPlasticMaterial &m, double t) {
  double f = 1.0;
  for (int i = 0; i < Terms(m); ++i) f -= m.g[i] * (1.0 - std::exp(-t / m.tau[i]));
  return f;
}

namespace {

// The law in its own measures (Green-Lagrange/PK2, or Biot for kMeasureBiot): strain e, stress s.
int UpdateInMeasure(const ViscoelasticPlasticMaterial &m, double dt, const double E[3], const double *hist_old,
                    double *hist_new, double S[3], double D[9]) {
  const int n = Terms(m);
  const int nh = ViscoelasticPlasticHistorySize(n);
  double old[ViscoelasticPlasticHistorySize(kMaxPronyTerms)];
  std::memcpy(old, hist_old, sizeof(double) * (size_t)nh);  // hist_new may alias hist_old
  PlasticState committed, trial;
  std::memcpy(&committed, old, sizeof committed);
  const double *S0n = old + 4;

  // The step's effective modulus and history stress.
  double geff = 1.0, Shist[3] = {0.0, 0.0, 0.0}, decay[kMaxPronyTerms], weight[kMaxPronyTerms];
  for (int i = 0; i < n; ++i) {
    const double x = dt / m.tau[i];
    decay[i] = std::exp(-x);
    weight[i] = m.g[i] * StepFactor(x);
    geff -= m.g[i] - weight[i];
    const double *h = old + 7 + 3 * i;
    for (int k = 0; k < 3; ++k) Shist[k] += decay[i] * h[k] - weight[i] * S0n[k];
  }

  int status;
  if (n == 0) {
    status = PlasticReturnMap(m.plastic, E, committed, &trial, S, D);
  } else {
    PlasticMaterial pm = m.plastic;
    pm.young = geff * m.plastic.young;
    const double nu = pm.nu;
    const double Et[3] = {E[0] + (Shist[0] - nu * Shist[1]) / pm.young, E[1] + (Shist[1] - nu * Shist[0]) / pm.young,
                          E[2] + 2.0 * (1.0 + nu) * Shist[2] / pm.young};
    status = PlasticReturnMap(pm, Et, committed, &trial, S, D);
  }
  if (status != KERNEL_OK) {
    if (hist_new) std::memcpy(hist_new, old, sizeof(double) * (size_t)nh);
    return status;
  }
  if (!hist_new) return status;

  const double ee[3] = {E[0] - trial.ep[0], E[1] - trial.ep[1], E[2] - trial.ep[2]};
  double S0[3];
  PlaneStress(m.plastic.young, m.plastic.nu, ee, S0);
  std::memcpy(hist_new, &trial, sizeof trial);
  for (int k = 0; k < 3; ++k) hist_new[4 + k] = S0[k];
  for (int i = 0; i < n; ++i) {
    const double *h = old + 7 + 3 * i;
    for (int k = 0; k < 3; ++k) hist_new[7 + 3 * i + k] = decay[i] * h[k] + weight[i] * (S0[k] - S0n[k]);
  }
  return status;
}

// The in-plane right stretch U of C = I + 2E, closed form for 2x2: U = (C + d I) / t with
// d = sqrt(det C), t = sqrt(tr C + 2 d); u = (U11, U22, U12) and du[3 j + k] = du_k / dE_j (E in
// Voigt form, engineering shear). False for det C <= 0 or non-finite input.
bool RightStretch(const double E[3], double u[3], double du[9]) {
  const double c11 = 1.0 + 2.0 * E[0], c22 = 1.0 + 2.0 * E[1], c12 = E[2];
  const double det = c11 * c22 - c12 * c12;
  if (!(det > 0.0) || !std::isfinite(det)) return false;
  const double d = std::sqrt(det), t = std::sqrt(c11 + c22 + 2.0 * d);
  u[0] = (c11 + d) / t, u[1] = (c22 + d) / t, u[2] = c12 / t;
  const double dC[3][3] = {{2.0, 0.0, 0.0}, {0.0, 2.0, 0.0}, {0.0, 0.0, 1.0}};  // d(c11, c22, c12) / dE_j
  for (int j = 0; j < 3; ++j) {
    const double dd = (c22 * dC[j][0] + c11 * dC[j][1] - 2.0 * c12 * dC[j][2]) / (2.0 * d);
    const double dt = (dC[j][0] + dC[j][1] + 2.0 * dd) / (2.0 * t);
    du[3 * j + 0] = (dC[j][0] + dd - u[0] * dt) / t;
    du[3 * j + 1] = (dC[j][1] + dd - u[1] * dt) / t;
    du[3 * j + 2] = (dC[j][2] - u[2] * dt) / t;
  }
  return true;
}

// x = A^-1 b for a 3x3 A (Cramer's rule; A is the Sylvester operator below, well conditioned
// for stretches near 1).
void Solve3(const double A[9], const double b[3], double x[3]) {
  const double adj[9] = {A[4] * A[8] - A[5] * A[7], A[2] * A[7] - A[1] * A[8], A[1] * A[5] - A[2] * A[4],
                         A[5] * A[6] - A[3] * A[8], A[0] * A[8] - A[2] * A[6], A[2] * A[3] - A[0] * A[5],
                         A[3] * A[7] - A[4] * A[6], A[1] * A[6] - A[0] * A[7], A[0] * A[4] - A[1] * A[3]};
  const double det = A[0] * adj[0] + A[1] * adj[3] + A[2] * adj[6];
  for (int i = 0; i < 3; ++i) x[i] = (adj[3 * i] * b[0] + adj[3 * i + 1] * b[1] + adj[3 * i + 2] * b[2]) / det;
}

// The Sylvester operator of U S + S U = 2 T on Voigt (S11, S22, S12): M s = 2 t.
void SylvesterMatrix(const double u[3], double M[9]) {
  const double v[9] = {2.0 * u[0], 0.0, 2.0 * u[2], 0.0, 2.0 * u[1], 2.0 * u[2], u[2], u[2], u[0] + u[1]};
  std::memcpy(M, v, sizeof v);
}

} // namespace

int ViscoelasticPlasticUpdate(const ViscoelasticPlasticMaterial &m, double dt, const double E[3], const double *hist_old,
                              double *hist_new, double S[3], double D[9]) {
  if (m.measure != kMeasureBiot) return UpdateInMeasure(m, dt, E, hist_old, hist_new, S, D);
  // Biot measures: the law on e = U - I gives the Biot stress T and dT/de; S solves U S + S U = 2 T
  // (T = sym(U S) is S's work conjugate on U), and dS/dE = M^-1 (2 dT/dE - dM/dE s).
  double u[3], du[9];
  if (!RightStretch(E, u, du)) {
    S[0] = S[1] = S[2] = 0.0;
    if (hist_new && hist_new != hist_old)
      std::memcpy(hist_new, hist_old, sizeof(double) * (size_t)ViscoelasticPlasticHistorySize(Terms(m)));
    return KERNEL_NONFINITE;
  }
  const double e[3] = {u[0] - 1.0, u[1] - 1.0, 2.0 * u[2]};
  double T[3], DT[9];
  const int status = UpdateInMeasure(m, dt, e, hist_old, hist_new, T, DT);
  if (status != KERNEL_OK) {
    S[0] = S[1] = S[2] = 0.0;
    return status;
  }
  double M[9];
  SylvesterMatrix(u, M);
  const double twoT[3] = {2.0 * T[0], 2.0 * T[1], 2.0 * T[2]};
  Solve3(M, twoT, S);
  for (int j = 0; j < 3; ++j) {  // column j: d/dE_j
    const double *duj = &du[3 * j];
    const double dej[3] = {duj[0], duj[1], 2.0 * duj[2]};
    double rhs[3], col[3];
    for (int k = 0; k < 3; ++k) rhs[k] = 2.0 * (DT[3 * k] * dej[0] + DT[3 * k + 1] * dej[1] + DT[3 * k + 2] * dej[2]);
    rhs[0] -= 2.0 * duj[0] * S[0] + 2.0 * duj[2] * S[2];
    rhs[1] -= 2.0 * duj[1] * S[1] + 2.0 * duj[2] * S[2];
    rhs[2] -= duj[2] * (S[0] + S[1]) + (duj[0] + duj[1]) * S[2];
    Solve3(M, rhs, col);
    for (int k = 0; k < 3; ++k) D[3 * k + j] = col[k];
  }
  return status;
}

} // namespace etfe
