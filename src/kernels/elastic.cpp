// Plane-stress St. Venant-Kirchhoff law of the membrane (docs/theory.md §3.1, thesis §4.2.1 elastic
// part of eqs. 4.14-4.21): S = D E in the element's local frame,
//   D = E/(1-nu^2) [[1, nu, 0], [nu, 1, 0], [0, 0, (1-nu)/2]].
// The shear entry is (1-nu)/2 = G (1-nu^2)/E because the strain vector carries the engineering
// shear 2Exy, so Sxy = G * 2Exy and S.E is the work density.
#include "etfe/kernels/elastic.h"

namespace etfe {

void ElasticPlaneStressTangent(double young, double nu, double D[9]) {
  const double c = young / (1.0 - nu * nu);
  D[0] = c;
  D[1] = c * nu;
  D[2] = 0.0;
  D[3] = c * nu;
  D[4] = c;
  D[5] = 0.0;
  D[6] = 0.0;
  D[7] = 0.0;
  D[8] = 0.5 * c * (1.0 - nu);
}

void ElasticPlaneStress(double young, double nu, const double E[3], double S[3], double D[9]) {
  const double c = young / (1.0 - nu * nu);
  S[0] = c * (E[0] + nu * E[1]);
  S[1] = c * (nu * E[0] + E[1]);
  S[2] = 0.5 * c * (1.0 - nu) * E[2];
  // Callers that only need the stress (output, line search) pass no D.
  if (D) ElasticPlaneStressTangent(young, nu, D);
}

} // namespace etfe
