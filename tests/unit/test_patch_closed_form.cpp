// The patch test's closed form (src/verification/patch_closed_form.cpp) against the solver's
// elastic kernel (src/kernels/elastic.cpp): two codes for the same plane-stress Hooke law, so
// agreement to round-off checks both; the uniaxial case is checked by its own property, a free
// lateral direction (Syy = 0 under the strain the kernel says makes it zero).
#include "etfe/kernels/elastic.h"
#include "etfe/verification/patch_closed_form.h"

#include "check.h"

#include <cmath>

int main() {
  const double young = 1100.0;  // MPa, ETFE-like; any positive value works
  const double nus[] = {0.0, 0.3, 0.45};
  const double strains[][2] = {{0.0202, 0.0}, {0.0202, 0.0101}, {0.0202, -0.0099}, {-0.01, 0.03}};
  for (double nu : nus)
    for (const auto &e : strains) {
      double S[2], E[3] = {e[0], e[1], 0.0}, Sk[3], D[9];
      etfe::PatchClosedFormStress(young, nu, e[0], e[1], false, S);
      etfe::ElasticPlaneStress(young, nu, E, Sk, D);
      const double scale = young * (std::fabs(e[0]) + std::fabs(e[1]));
      CHECK_CLOSE(S[0], Sk[0], 0.0, 1e-13 * scale);
      CHECK_CLOSE(S[1], Sk[1], 0.0, 1e-13 * scale);
      CHECK(std::fabs(Sk[2]) <= 1e-13 * scale, "no shear from normal strains: Sxy = %g", Sk[2]);

      // Uniaxial: with Eyy = -nu Exx the biaxial law gives Syy = 0 and Sxx = E Exx, which is
      // what the lateral-free form returns whatever Eyy it is handed.
      double Su[2], Sb[2];
      etfe::PatchClosedFormStress(young, nu, e[0], 12.3, true, Su);
      etfe::PatchClosedFormStress(young, nu, e[0], -nu * e[0], false, Sb);
      CHECK_CLOSE(Su[0], Sb[0], 1e-14, 0.0);
      CHECK(Su[1] == 0.0 && std::fabs(Sb[1]) <= 1e-13 * young * std::fabs(e[0]), "Syy %g %g", Su[1],
            Sb[1]);
    }
  TEST_MAIN_END();
}
