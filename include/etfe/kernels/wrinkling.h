// Tension-field (relaxed) membrane for an isotropic plane-stress St. Venant-Kirchhoff law: a
// film that carries no compression. PETSc-free. Voigt vectors as in membrane.h:
// E = (Exx, Eyy, 2Exy), S = (Sxx, Syy, Sxy), D = dS/dE (3x3 row-major).
//
// Mixed stress/strain criterion (Roddeman et al. 1987; Kang & Im 1997), E1 >= E2 the principal
// strains, n the principal direction of E1:
//   taut      if the plane-stress law's minor principal stress c (E2 + nu E1) >= 0  -> S = D_e E;
//   slack     else if E1 <= 0                                                        -> S = 0;
//   wrinkled  otherwise: uniaxial tension along n, S = Y E1 n (x) n.
// Why n is the principal direction of E: in the wrinkled state E = Ee + beta m (x) m (m _|_ n,
// beta the wrinkle strain) and Ee is the strain of the uniaxial stress s n (x) n, so
// E_nn = s/Y, E_nm = 0 (n is a principal direction of E, the one with E1) and
// E_mm = -nu s/Y + beta: s = Y E1 and beta = E2 + nu E1 < 0. The "lost" length is -beta.
// Tangent in the wrinkled state (spectral derivative; dE1 = n.dE.n,
// dn = (m.dE.n)/(E1-E2) m):
//   D = Y [ N N^T + 2 E1/(E1-E2) W W^T ],  N = (c^2, s^2, cs),  W = (-cs, cs, (c^2-s^2)/2),
// exact and finite there (E1 - E2 > (1+nu) E1 > 0). The taut test comes first and allows
// E2 + nu E1 down to -kTautStrainTolerance: an unloaded film's round-off strains (~1e-16, of
// either sign) are taut with the elastic tangent, not wrinkled or slack with a near-singular one
// (a stress-free saddle otherwise starts Newton on a singular in-plane tangent). The stress is
// continuous across the taut|wrinkled boundary, so the shift changes it by at most
// E kTautStrainTolerance / (1 - nu^2) (a compressive minor stress of that size may remain). In the slack state the exact
// tangent is 0 (a singular stiffness); the tangent only is regularized to
// kSlackTangentFraction * D_e (the stress stays exactly 0), which changes the Newton path in
// slack regions, never the converged answer.
#pragma once

namespace etfe {

enum WrinkleState : int { WRINKLE_TAUT = 0, WRINKLE_WRINKLED = 1, WRINKLE_SLACK = 2 };

constexpr double kSlackTangentFraction = 1e-6;
constexpr double kTautStrainTolerance = 1e-10;

struct WrinkleInfo {
  int state;         // WrinkleState
  double dir[2];     // wrinkled: unit tension (= wrinkle) direction n in the local frame; else 0
  double strain;     // wrinkled: -(E2 + nu E1); slack: -E2; taut: 0 (the length lost to wrinkles)
};

// State, direction and wrinkle strain of the strain E (no stress computed).
void TensionFieldClassify(double young, double nu, const double E[3], WrinkleInfo *info);

// Relaxed stress S and its tangent D (may be nullptr) at E; info may be nullptr. Returns the state.
int TensionFieldStress(double young, double nu, const double E[3], double S[3], double D[9],
                       WrinkleInfo *info);

} // namespace etfe
