// ETFE viscoelastic-plastic law: a generalized Maxwell (Prony series) relaxation spectrum on the
// elastic strain of the two-yield plane-stress plasticity (plasticity.h). PETSc-free.
//
// Voigt vectors as in plasticity.h: E = (Exx, Eyy, 2Exy), S = (Sxx, Syy, Sxy), D = dS/dE.
// The relaxation modulus is E(t) = E0 (g_inf + sum_i g_i exp(-t / tau_i)), g_inf = 1 - sum g_i,
// with E0 = plastic.young the instantaneous modulus and one Poisson's ratio for every branch.
// Times are in seconds of reduced time (the caller divides physical time by the shift factor).
#pragma once

#include "etfe/kernels/plasticity.h"

namespace etfe {

constexpr int kMaxPronyTerms = 32;

// The strain and stress the law's numbers are in (ViscoelasticPlasticMaterial::measure).
//  * kMeasureGreenLagrange: the law maps Green-Lagrange strain E to 2nd Piola-Kirchhoff stress S
//    directly, as the plastic law (the thesis's). Fitted to a uniaxial test in engineering strain e
//    and nominal stress P, it gives P = (1 + e)(1 + e/2) E0 e at small e: 1.5 e above (1.2 % at
//    0.8 % strain).
//  * kMeasureBiot: the law maps the Biot strain U - I (U the in-plane right stretch, C = U^2 =
//    I + 2E) to the Biot stress T = (U S + S U) / 2, its work conjugate (T : dU = S : dE); for a
//    uniaxial test these are the engineering strain and the nominal stress, the measures of the
//    lab curve, exactly. The history (plastic strain, S0, the branches) is in these measures.
constexpr int kMeasureGreenLagrange = 0;
constexpr int kMeasureBiot = 1;

struct ViscoelasticPlasticMaterial {
  PlasticMaterial plastic;      // E0 (instantaneous modulus), nu and the hardening curve
  int nterms;                   // Maxwell branches (0: the plastic law itself)
  double tau[kMaxPronyTerms];   // relaxation times [s], increasing
  double g[kMaxPronyTerms];     // modulus fractions of E0, > 0, sum < 1
  int measure = kMeasureGreenLagrange;  // kMeasureGreenLagrange or kMeasureBiot (above)
};

// History of one element (integration point): ViscoelasticPlasticHistorySize(nterms) doubles,
//   [0..3]          PlasticState (ep[3], ep_bar)
//   [4..6]          S0 = D0 (E - Ep): the instantaneous elastic stress of the committed state
//   [7+3i .. 9+3i]  h_i: the internal stress of Maxwell branch i
inline int ViscoelasticPlasticHistorySize(int nterms) { return 7 + 3 * nterms; }

// 0 or a positive code with a message (the plastic part's check, then the spectrum's: tau > 0
// and increasing, g > 0, sum g < 1, at most kMaxPronyTerms terms).
int ViscoelasticPlasticMaterialCheck(const ViscoelasticPlasticMaterial &m, char *msg, int msglen);

// Relaxation modulus fraction E(t)/E0 of the spectrum (closed form, for checks and reports).
double ViscoelasticPlasticRelaxationFraction(const ViscoelasticPlasticMaterial &m, double t);

// One step of reduced length dt >= 0 from the committed history to the total strain E. Every
// branch sees the elastic strain Ee = E - Ep and integrates exactly over the step for a strain
// linear in time:
//   h_i,n+1 = exp(-dt/tau_i) h_i,n + g_i gamma_i (S0_n+1 - S0_n),  gamma_i = tau_i/dt (1 - exp(-dt/tau_i)),
//   S = g_inf S0 + sum_i h_i,
// the yield function sees S, the flow is associated with S. Then S = Deff (E - Ep) + Shist with
// Deff = geff D0 (geff = g_inf + sum g_i gamma_i) and a stress Shist fixed by the history, so
// the return map is the plastic one of modulus geff E0 at the strain E + Deff^-1 Shist and D its
// consistent tangent. dt = 0 is the instantaneous response (geff = 1). hist_new may alias
// hist_old. Returns the plastic return map's status (hist_new = hist_old, S = 0 on failure).
// With measure kMeasureBiot all of this is in the Biot measures; E, S and D are still the Green-
// Lagrange strain, the PK2 stress and dS/dE (KERNEL_NONFINITE for det C <= 0).
int ViscoelasticPlasticUpdate(const ViscoelasticPlasticMaterial &m, double dt, const double E[3], const double *hist_old,
                       double *hist_new, double S[3], double D[9]);

} // namespace etfe
