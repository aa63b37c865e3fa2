// ETFE elasto-plasticity (docs/theory.md §3.2, thesis §4.2.1 eqs. 4.13-4.21). PETSc-free.
//
// Plane stress, von Mises yield, associated flow, isotropic hardening, additive split of the
// Green-Lagrange strain E = Ee + Ep (large displacement, small strain). Voigt vectors as in
// membrane.h: E = (Exx, Eyy, 2Exy), S = (Sxx, Syy, Sxy), D = dS/dE.
//
// Hardening is piecewise linear in the equivalent plastic strain ep_bar: segment k starts at
// yield stress yield[k] (increasing) with plastic modulus H[k] (dSy/dep_bar, >= 0). Under
// uniaxial stress the S-E curve has slope E, then E H[0]/(E+H[0]) from yield[0] to yield[1], ...
// ep_bar is the uniaxial-equivalent plastic strain (rate sqrt(2/3 dEp:dEp) on the tensor
// strain, which equals the axial plastic strain in uniaxial stress).
#pragma once

namespace etfe {

constexpr int kMaxHardeningSegments = 8;

struct PlasticMaterial {
  double young;   // E [MPa]
  double nu;      // Poisson's ratio
  int nseg;       // number of hardening segments (>= 1)
  double yield[kMaxHardeningSegments];  // yield stress where segment k starts [MPa]
  double H[kMaxHardeningSegments];      // plastic modulus on segment k [MPa]
};

// History of one element (integration point). 4 doubles, in this order.
struct PlasticState {
  double ep[3];   // plastic strain (Voigt, engineering shear)
  double ep_bar;  // equivalent plastic strain
};

// Checks the parameters; returns 0 or a positive code and writes a message (may be nullptr).
// Besides the obvious ranges it requires yield[0] > 0 and H[k] > 0 on every segment but the last
// (a flat inner segment would never reach the next yield stress).
int PlasticMaterialCheck(const PlasticMaterial &m, char *msg, int msglen);

// Current yield stress and hardening slope at ep_bar (slope may be nullptr). At a breakpoint
// the slope is that of the segment starting there; ep_bar < 0 reads as 0.
double PlasticYieldStress(const PlasticMaterial &m, double ep_bar, double *slope);

// Return map (Simo & Taylor 1986 plane-stress algorithm; the scalar Newton in the plastic
// multiplier handles the kinks between segments) from the committed state at the total strain E.
// Writes the trial state (the updated, not yet committed history at E; it may alias committed),
// S and the consistent tangent D (3x3 row-major, Simo & Taylor 1985, eq. 4.21; the elastic D on
// an elastic step). Returns KERNEL_OK, KERNEL_NONFINITE or KERNEL_NO_CONVERGENCE; on failure
// trial = committed, S = 0 and D is the elastic tangent. The material must pass
// PlasticMaterialCheck (an unchecked one is only guarded against out-of-bounds reads).
int PlasticReturnMap(const PlasticMaterial &m, const double E[3], const PlasticState &committed,
                     PlasticState *trial, double S[3], double D[9]);

} // namespace etfe
