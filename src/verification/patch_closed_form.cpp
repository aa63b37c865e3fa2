// Plane-stress Hooke closed form of the patch test (see the header); independent of
// src/kernels/elastic.cpp on purpose.
#include "etfe/verification/patch_closed_form.h"

namespace etfe {

void PatchClosedFormStress(double young, double nu, double Exx, double Eyy, bool lateral_free,
                           double S[2]) {
  if (lateral_free) {
    S[0] = young * Exx;
    S[1] = 0.0;
    return;
  }
  const double c = young / (1.0 - nu * nu);
  S[0] = c * (Exx + nu * Eyy);
  S[1] = c * (Eyy + nu * Exx);
}

} // namespace etfe
