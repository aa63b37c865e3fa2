// Cables (docs/theory.md §14): a two-node total-Lagrangian cable segment, tension-only; the constant-force
// and force-density segments form finding uses; a sliding cable over a node chain (one axial force along it). PETSc-free.
//
// Layouts: x holds the current positions, 3 per node, node after node (a segment: x1 then x2;
// a chain: n0 ... nk). f holds the internal nodal forces in the same layout (the residual adds
// them); K, where asked for, is df/dx, row-major (6x6 for a segment, 3(k+1) squared for a chain).
//
// Tension only: a cable whose strain is not positive carries nothing and has no stiffness, so
// residual and tangent stay consistent in both states (the finite-difference checks). Newton
// stays regular because every cable node is a node of the film, whose own stiffness holds it
// while the cable is slack (the term refuses cable nodes the film does not have).
#pragma once

namespace etfe {

// What a segment or a chain is doing at x.
struct CableState {
  double length = 0.0;  // current length l [mm]
  double force = 0.0;   // axial force N [N] (0 when slack)
  bool slack = false;   // l <= L0
};

// Elastic segment: Green-Lagrange strain E = (l^2 - L0^2) / (2 L0^2), energy 1/2 EA L0 E^2 for
// E > 0 (else 0). f2 = (EA E / L0)(x2 - x1) = -f1, N = EA E l / L0;
// K22 = (EA/L0^3) d d^T + (EA E / L0) I with d = x2 - x1, K11 = K22, K12 = K21 = -K22.
// K may be null (residual only).
CableState CableSegment(const double x[6], double L0, double EA, double f[6], double K[36]);

// Constant-force segment (form finding: the cable's prescribed force T whatever its length):
// f2 = T e = -f1 with e = d / l, K22 = (T / l)(I - e e^T). K may be null.
CableState CableSegmentConstantForce(const double x[6], double T, double f[6], double K[36]);

// Force-density segment (form finding: the cable's prescribed force density q [N/mm], its force
// q l proportional to its current length): f2 = q d = -f1 with d = x2 - x1, N = q l, K22 = q I,
// K11 = K22, K12 = K21 = -K22 (linear in x: the tangent is exact and symmetric). K may be null.
CableState CableSegmentForceDensity(const double x[6], double q, double f[6], double K[36]);

// Sliding cable over nodes 0..k (frictionless pocket): l = sum of |x_{i+1} - x_i|, one force
// N = EA (l - L0) / L0 for l > L0 (else 0) along the whole cable; f = N g with g = dl/dx;
// K = (EA/L0) g g^T (taut) + N sum_i (I - e_i e_i^T) / l_i on segment i's two nodes.
// nodes = k + 1 >= 2; K ((3 nodes)^2) may be null.
CableState CableSliding(int nodes, const double *x, double L0, double EA, double *f, double *K);

// The part of a sliding cable's force and tangent one segment carries, given the chain's force N
// and axial stiffness ka = EA/L0 (0 when slack): f2 = N e = -f1; K22 = ka e e^T + (N / l)(I - e e^T),
// K11 = K22, K12 = -K22. The chain's rank-one coupling between segments (ka g g^T beyond a
// segment's own e e^T) is left to the caller. K may be null. Returns l.
double CableSlidingSegment(const double x[6], double N, double ka, double f[6], double K[36]);

// Stress-free length of a segment of reference length L prestressed by a force T at the
// reference geometry (engineering strain, docs/theory.md §14): L0 = L / (1 + T / EA). The cut length.
double CableLengthForForce(double L, double T, double EA);

} // namespace etfe
