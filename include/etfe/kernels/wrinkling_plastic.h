// Tension-field membrane with the ETFE elasto-plastic law. PETSc-free. Voigt vectors
// as in membrane.h; the plastic law and its history as in plasticity.h.
//
// The state is decided on the plastic law's own answer, so that the stress is continuous:
//  * slack: the elastic trial strain Ee = E - Ep_n has E1 <= 0: S = 0, no plastic flow, the
//    regularized tangent of wrinkling.h;
//  * taut: the plane-stress return map (PlasticReturnMap) gives a minor principal stress
//    >= -young kTautStrainTolerance: its S, D and history, unchanged;
//  * wrinkled otherwise: uniaxial tension s along n, the major principal direction of Ee (the
//    isotropic return map keeps principal directions, so n does not move during flow), with a
//    uniaxial return map: associated flow of a uniaxial stress, dEp = dl (n n - 1/2 m m) (tensor),
//    dep_bar = dl, and s = E (E1 - dl) = Sy(ep_bar_n + dl) when the trial E E1 exceeds the yield
//    stress (the wrinkles take the strain across n). At the boundary (return-mapped minor stress
//    = 0) both branches give the same stress, plastic strain and ep_bar.
//    Tangent: D = Et N N^T + 2 s/(E1 - E2) W W^T with Et = E H/(E + H) on a plastic step (E on
//    an elastic one), N, W as in wrinkling.h, E1 > E2 the principal values of Ee.
#pragma once

#include "etfe/kernels/plasticity.h"
#include "etfe/kernels/wrinkling.h"

namespace etfe {

// Returns a KernelStatus (the return maps' failures pass through); info may be nullptr.
int TensionFieldPlastic(const PlasticMaterial &m, const double E[3], const PlasticState &committed,
                        PlasticState *trial, double S[3], double D[9], WrinkleInfo *info);

} // namespace etfe
