// Annular membrane under torsion with a tension field (Stein & Hedgepeth 1961, Mikulas 1964),
// small-strain plane stress, isotropic (E, nu), for the boundary conditions of the annulus scene:
// the outer edge r = b held at u_r = eps0 b, u_theta = 0; a rigid hub r = a at u_r = eps0 a,
// rotated by phi. eps0 alone gives the uniform pretension sigma0 = E eps0/(1-nu).
//
// Equilibrium carries the torque as tau = C/r^2 everywhere (M = 2 pi t C).
//  * Taut zone R <= r <= b (Lame + torsion): s_r = A + B/r^2, s_t = A - B/r^2,
//    u = ((1-nu) A r - (1+nu) B/r)/E, v/r = C/(2G) (1/b^2 - 1/r^2).
//  * Wrinkled zone a <= r < R: uniaxial tension (s_r s_t = tau^2); radial equilibrium
//    (r s_r)' = s_t integrates to (r s_r)^2 = K - C^2/r^2. Kinematics: the strain along the
//    tension direction n (angle psi, tan psi = tau/s_r) is the uniaxial elastic one,
//    e_nn = s_1/E with s_1 = s_r + s_t, and the shear e_nm vanishes (wrinkles take only the
//    strain across n). That gives two linear ODEs in u and v/r, integrated (RK4) from R to a.
//  * At r = R: s_r, tau continuous and the taut side has s_2 = 0: A^2 R^4 = B^2 + C^2,
//    K = 2 A (A R^2 + B); u, v continuous.
// Given R, the outer condition and u(a) = eps0 a fix A, B, C (a scalar root in B); phi(R) is
// then the hub rotation. phi grows with R, so R(phi) is a bisection. Below the onset
// (tau(a) = sigma0) the annulus is taut: R = a, C = 2 G phi a^2 b^2/(b^2 - a^2). PETSc-free.
#pragma once

namespace etfe {

struct AnnulusTorsion {
  double a, b;      // hub and outer radius [mm], 0 < a < b
  double young, nu; // MPa, -
  double eps0;      // pretension strain (> 0)
};

struct AnnulusTorsionResult {
  double wrinkle_radius;  // R [mm] (= a when taut)
  double C;               // tau r^2 [MPa mm^2]: torque M = 2 pi t C
  double phi;             // hub rotation [rad]
};

// Hub rotation at the onset of wrinkling.
double AnnulusOnsetRotation(const AnnulusTorsion &p);

// The state with wrinkled zone radius R (a <= R < b). Returns 0, or 1 when no state exists.
int AnnulusStateAtRadius(const AnnulusTorsion &p, double R, AnnulusTorsionResult *res);

// The state at hub rotation phi >= 0. Returns 0, 1 for bad parameters (a, b, E, nu, eps0 <= 0),
// 2 when phi wrinkles the annulus to the outer edge (no partly wrinkled state).
int AnnulusStateAtRotation(const AnnulusTorsion &p, double phi, AnnulusTorsionResult *res);

// The state carrying the torque constant C = M/(2 pi t) (same return codes as above).
int AnnulusStateAtTorque(const AnnulusTorsion &p, double C, AnnulusTorsionResult *res);

} // namespace etfe
