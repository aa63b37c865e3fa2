// Hencky's problem: a flat circular membrane (radius a, thickness h, Young E, Poisson nu),
// clamped at its rim, under uniform lateral pressure p, in Foppl's small-rotation theory.
// Closed form by similarity: w0 = C_w(nu) a (p a/(E h))^(1/3) and the centre membrane stress
// sigma0 = C_s(nu) (E p^2 a^2 / h^2)^(1/3). The coefficients come from a shooting solve of the
// axisymmetric Foppl equations (no table lookup), accurate to ~1e-8. PETSc-free.
#pragma once

namespace etfe {

struct HenckyCoefficients {
  double deflection;     // C_w(nu): 0.65344 for nu = 0.3
  double centre_stress;  // C_s(nu): 0.43110 for nu = 0.3
};

// Returns 0 on success, non-zero when nu is outside (-1, 0.5].
int HenckyCoefficientsCompute(double nu, HenckyCoefficients *c);

} // namespace etfe
