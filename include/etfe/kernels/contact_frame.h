// The local frame of a node-to-support contact pair (docs/theory.md §5.1, thesis §4.2.2).
// PETSc-free.
//
// A support is a circular cylinder (an arch is the same surface: only its extent differs, which
// the scene's candidate selection handles): centre c, axis a (any length), radius r. For a point
// p, with d = p - c and n the unit component of d normal to a, the master point is
// M = c + (d.a) a + r n and the frame R has rows x0 = a x n (circumferential), y0 = n x x0 (= a,
// along the axis), z0 = n (outward radial normal): orthonormal and right-handed. R maps global
// vectors to local ones (v_local = R v), R^T maps back. Sign: the distance r_p - r is negative
// inside the support (penetration).
#pragma once

namespace etfe {

// Master point M (3), frame R (3x3 row-major, rows x0, y0, z0); returns the signed distance of p
// to the surface. p on the axis has no radial direction: n = 0 and R is degenerate (a pair is
// never created there; the caller's search tolerance is far smaller than the radius).
double ContactSupportFrame(const double centre[3], const double axis[3], double radius,
                           const double p[3], double M[3], double R[9]);

// A plane support through `point` with outward normal `normal` (any length): M is the foot of p
// on the plane, z0 the unit normal, x0 a fixed unit tangent (normal x the global axis least
// aligned with it), y0 = z0 x x0; returns the signed distance (p - point) . z0.
double ContactPlaneFrame(const double point[3], const double normal[3], const double p[3], double M[3], double R[9]);

// out = R v (global -> local).
void ContactToLocal(const double R[9], const double v[3], double out[3]);
// out = R^T v (local -> global).
void ContactToGlobal(const double R[9], const double v[3], double out[3]);
// Kg = R^T K R: a local tangent df/dg (3x3 row-major) as the global tangent of the node.
void ContactRotateTangent(const double R[9], const double K[9], double Kg[9]);

} // namespace etfe
