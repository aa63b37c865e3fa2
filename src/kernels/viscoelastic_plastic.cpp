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

int ViscoelasticPlasticUpdate(const ViscoelasticPlasticMaterial &m, double dt, const double E[3], const double *hist_old,
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

} // namespace etfe
