// Three-node total-Lagrangian membrane element (docs/theory.md §2, thesis §4.2.1). PETSc-free.
//
// Conventions shared by every kernel:
//  * nodal arrays are node-major: X[3*a + i] is component i of node a (a = 0,1,2);
//  * 9x9 matrices are row-major: K[9*(3*a+i) + 3*b+j];
//  * membrane Voigt vectors are (xx, yy, xy). Strain E = (Exx, Eyy, 2Exy) uses the engineering
//    shear; stress S = (Sxx, Syy, Sxy); the material tangent D = dS/dE (3x3 row-major) is
//    consistent with that pairing, so S·dE is the work density.
#pragma once

namespace etfe {

struct MembraneReference {
  double dNdx[3];   // dN_a/dxi  on the reference local frame
  double dNdy[3];   // dN_a/deta
  double area;      // reference area A0 [mm^2]
  double frame[9];  // rows e1, e2, e3 (unit vectors, global components)
};

// Reference data of a triangle from its stress-free nodal coordinates X. The local frame's
// first axis e1 is the projection of md_axis on the element plane (the MD axis: stresses come
// out in MD/TD); when md_axis is within ~1e-3 of the normal it falls back to the edge 1->2.
// e3 = (X2-X1)x(X3-X1)/|..|, e2 = e3 x e1. Returns KERNEL_DEGENERATE when the area is below
// min_area (absolute, mm^2) or the coordinates are not finite.
int MembraneReferenceBuild(const double X[9], const double md_axis[3], double min_area,
                           MembraneReference *ref);

// The direction axis carried from triangle X to triangle Y (9 each, same node order) by the
// affine map that takes X's nodes to Y's: the part of axis in X's plane, written as a combination
// of X's edges, is returned as the same combination of Y's edges (not normalized). Used to give
// a triangle whose stress-free shape Y differs from its placed shape X (a cutting pattern laid
// onto the surface) the MD axis it has on the surface. KERNEL_DEGENERATE for a sliver X or Y.
int MembraneCarryAxis(const double X[9], const double Y[9], const double axis[3], double out[3]);

// Deformation gradient F (3x2 row-major, F[2*i+j] = dx_i/dxi_j) and Green-Lagrange strain
// E = (Exx, Eyy, 2Exy) at the current coordinates x.
void MembraneKinematics(const MembraneReference &ref, const double x[9], double F[6], double E[3]);

// Internal force f (9) and, when K != nullptr, tangent K (81) of the element for the PK2 stress S
// and the material tangent D (may be nullptr when K is nullptr); f may be nullptr when only K is
// wanted (the Jacobian loop):
//   f_a  = h0 A0 F S gradN_a
//   K_ab = h0 A0 [ (gradN_a . S gradN_b) I3 + B_a^T D B_b ]
void MembraneForce(const MembraneReference &ref, double thickness, const double F[6],
                   const double S[3], const double D[9], double f[9], double K[81]);

// Current area ratio a/A0 and unit normal n (may be nullptr) of the triangle x.
double MembraneAreaRatio(const MembraneReference &ref, const double x[9], double n[3]);

// Output measures of a membrane stress/strain state (docs/theory.md §2).
double MisesPlaneStress(const double S[3]);          // sqrt(Sxx^2+Syy^2-SxxSyy+3Sxy^2)
double MinPrincipalStress(const double S[3]);        // (Sxx+Syy)/2 - sqrt(((Sxx-Syy)/2)^2+Sxy^2)
double MinPrincipalStrain(const double E[3]);        // E uses engineering shear: tensor shear E[2]/2

} // namespace etfe
