// Tension-field membrane: relaxed plane-stress St. Venant-Kirchhoff law. The
// formulation, the state criterion and the tangent are in include/etfe/kernels/wrinkling.h.
// Called once per element per Newton iteration: plain arithmetic, no allocation.
#include "etfe/kernels/wrinkling.h"

#include <cmath>

#include "etfe/kernels/elastic.h"

namespace etfe {

namespace {

struct Principal {
  double e1, e2;  // principal strains, e1 >= e2
  double c, s;    // n = (c, s): direction of e1
};

// Principal strains; the direction (trigonometry, the costly part) only when asked, i.e. for a
// wrinkled element: every element is classified at every residual evaluation.
Principal PrincipalStrains(const double E[3], bool direction) {
  const double m = 0.5 * (E[0] + E[1]);
  const double d = 0.5 * (E[0] - E[1]);
  const double g = 0.5 * E[2];  // tensor shear
  const double r = std::sqrt(d * d + g * g);
  Principal p;
  p.e1 = m + r;
  p.e2 = m - r;
  p.c = 1.0, p.s = 0.0;
  if (direction) {
    // atan2(0, 0) = 0: equal principal strains (never wrinkled, see the header) give n = e1 axis.
    const double th = 0.5 * std::atan2(g, d);
    p.c = std::cos(th);
    p.s = std::sin(th);
  }
  return p;
}

} // namespace

void TensionFieldClassify(double young, double nu, const double E[3], WrinkleInfo *info) {
  (void)young;  // the criterion is a sign test; the modulus only scales the stress
  Principal p = PrincipalStrains(E, false);
  info->dir[0] = info->dir[1] = 0.0;
  info->strain = 0.0;
  if (p.e2 + nu * p.e1 >= -kTautStrainTolerance) {
    info->state = WRINKLE_TAUT;
  } else if (p.e1 <= 0.0) {
    info->state = WRINKLE_SLACK;
    info->strain = -p.e2;
  } else {
    info->state = WRINKLE_WRINKLED;
    p = PrincipalStrains(E, true);
    info->dir[0] = p.c;
    info->dir[1] = p.s;
    info->strain = -(p.e2 + nu * p.e1);
  }
}

int TensionFieldStress(double young, double nu, const double E[3], double S[3], double D[9],
                       WrinkleInfo *info) {
  WrinkleInfo local;
  if (!info) info = &local;
  TensionFieldClassify(young, nu, E, info);
  if (info->state == WRINKLE_TAUT) {
    ElasticPlaneStress(young, nu, E, S, D);
    return info->state;
  }
  if (info->state == WRINKLE_SLACK) {
    S[0] = S[1] = S[2] = 0.0;
    if (D) {
      ElasticPlaneStressTangent(young, nu, D);
      for (int k = 0; k < 9; ++k) D[k] *= kSlackTangentFraction;
    }
    return info->state;
  }
  const Principal p = PrincipalStrains(E, true);
  const double c = p.c, s = p.s;
  const double N[3] = {c * c, s * s, c * s};
  const double sig = young * p.e1;
  for (int i = 0; i < 3; ++i) S[i] = sig * N[i];
  if (D) {
    const double W[3] = {-c * s, c * s, 0.5 * (c * c - s * s)};
    const double k = 2.0 * p.e1 / (p.e1 - p.e2);
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) D[3 * i + j] = young * (N[i] * N[j] + k * W[i] * W[j]);
  }
  return info->state;
}

} // namespace etfe
