// The gas in a chamber of membrane surfaces (docs/theory.md §6). PETSc-free.
//
// A chamber is bounded by triangles whose normals n = (x2-x1)x(x3-x1) point out of it (a group
// whose triangles point in enters with sign -1), closed by nodes that do not move (a clamped rim)
// or by planes through the origin o (symmetry planes of a part model, a rigid base). Its volume is
// the sum of the tetrahedra (o, x1, x2, x3): V = sum sign (x1-o).((x2-o)x(x3-o)) / 6, exact for
// the discrete surface. Its gradient on the moving nodes is the follower-pressure load per unit
// pressure, sum sign (area vector)/3 per node (kernels/pressure.h): the gas pushes with p dV/dx.
//
// Gas laws (absolute pressures inside): supplied, p = p(t) from a schedule; sealed,
// p_abs V^kappa = C, the amount C fixed when the chamber is sealed (kappa = 1 isothermal, 1.4
// adiabatic air). The sealed chamber's stiffness dp/dV = -kappa p_abs / V makes the tangent's
// rank-one term (kappa p_abs / V) g g^T, g = dV/dx.
#pragma once

namespace etfe {

// The tetrahedron (o, x1, x2, x3)'s signed volume: (x1-o).((x2-o)x(x3-o)) / 6 (x: 9 values).
double ChamberTetVolume(const double x[9], const double o[3]);

// Sealed gas: the amount C = p_abs V^kappa at sealing, the gauge pressure p_abs - p_atm at volume
// V, and -dp/dV = kappa p_abs / V (positive: a smaller volume raises the pressure).
double SealedAmount(double gauge, double atmosphere, double volume, double kappa);
double SealedGauge(double amount, double atmosphere, double volume, double kappa);
double SealedStiffness(double amount, double volume, double kappa);

} // namespace etfe
