// Closed form of the annulus under torsion with a tension field
// (src/verification/annulus_closed_form.cpp): continuity with the taut torsion solution at the
// wrinkling onset, the three parametrizations (radius, rotation, torque) agreeing with each other,
// monotone growth of the wrinkled zone, and the refusal past the range where the film around the
// hub goes slack. (The FE annulus scene, tests/regression/test_wrinkle_annulus.py, converges to it.)
#include "etfe/verification/annulus_closed_form.h"

#include "check.h"

#include <cmath>
#include <initializer_list>

int main() {
  const etfe::AnnulusTorsion p{100.0, 500.0, 800.0, 0.43, 1e-4};
  const double sigma0 = p.young * p.eps0 / (1 - p.nu), G = 0.5 * p.young / (1 + p.nu);
  const double phi0 = etfe::AnnulusOnsetRotation(p);
  CHECK_CLOSE(phi0, sigma0 / (2 * G) * (1 - p.a * p.a / (p.b * p.b)), 1e-14, 0.0);

  // Below the onset: taut torsion, tau(a) = C/a^2 < sigma0.
  etfe::AnnulusTorsionResult r;
  CHECK(etfe::AnnulusStateAtRotation(p, 0.5 * phi0, &r) == 0, "taut state");
  CHECK(r.wrinkle_radius == p.a, "taut: R = a (got %g)", r.wrinkle_radius);
  CHECK_CLOSE(r.C, 0.5 * sigma0 * p.a * p.a, 1e-12, 0.0);

  // The wrinkled branch starts where the taut one ends.
  CHECK(etfe::AnnulusStateAtRadius(p, p.a * (1 + 1e-9), &r) == 0, "R -> a");
  CHECK_CLOSE(r.C, sigma0 * p.a * p.a, 1e-6, 0.0);
  CHECK_CLOSE(r.phi, phi0, 1e-6, 0.0);

  // Radius -> (rotation, torque) -> radius, and both grow with R.
  double prev_phi = phi0, prev_C = sigma0 * p.a * p.a;
  for (double R : {105.0, 115.0, 125.0, 135.0}) {
    etfe::AnnulusTorsionResult s, t, u;
    CHECK(etfe::AnnulusStateAtRadius(p, R, &s) == 0, "R = %g", R);
    CHECK(s.phi > prev_phi && s.C > prev_C, "R = %g: phi %g, C %g not increasing", R, s.phi, s.C);
    prev_phi = s.phi, prev_C = s.C;
    CHECK(etfe::AnnulusStateAtRotation(p, s.phi, &t) == 0, "rotation %g", s.phi);
    CHECK_CLOSE(t.wrinkle_radius, R, 1e-9, 0.0);
    CHECK_CLOSE(t.C, s.C, 1e-8, 0.0);
    CHECK(etfe::AnnulusStateAtTorque(p, s.C, &u) == 0, "torque %g", s.C);
    CHECK_CLOSE(u.wrinkle_radius, R, 1e-9, 0.0);
    CHECK_CLOSE(u.phi, s.phi, 1e-8, 0.0);
    // Near the onset the zone follows the stress-driven estimate R ~ sqrt(C/sigma0) within a few %.
    CHECK(std::fabs(R / std::sqrt(s.C / sigma0) - 1) < 0.05, "R = %g vs sqrt(C/sigma0) = %g", R,
          std::sqrt(s.C / sigma0));
  }
  // Only the ratio phi/eps0 matters (linear theory): scaling both keeps R.
  etfe::AnnulusTorsion q = p;
  q.eps0 = 3 * p.eps0;
  etfe::AnnulusTorsionResult a1, a3;
  etfe::AnnulusStateAtRotation(p, 2.0 * phi0, &a1);
  etfe::AnnulusStateAtRotation(q, 6.0 * phi0, &a3);
  CHECK_CLOSE(a3.wrinkle_radius, a1.wrinkle_radius, 1e-9, 0.0);
  CHECK_CLOSE(a3.C, 3 * a1.C, 1e-8, 0.0);

  // Bad input and rotations past the partly wrinkled range are refused, not extrapolated.
  etfe::AnnulusTorsion bad = p;
  bad.eps0 = -1e-4;
  CHECK(etfe::AnnulusStateAtRotation(bad, phi0, &r) == 1, "negative pretension accepted");
  CHECK(etfe::AnnulusStateAtRotation(p, 1e3 * phi0, &r) == 2, "huge rotation accepted (R = %g)",
        r.wrinkle_radius);
  TEST_MAIN_END();
}
