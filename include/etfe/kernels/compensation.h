// Compensation of cutting patterns: the pattern is cut smaller than the design surface
// so that the drawn-in film reaches its design prestress. PETSc-free.
//
// A pattern is described per element by its rest metric M (2x2 symmetric, in the pattern's
// axes: x = MD along the strip, y = TD): a design link with unit direction d and length L is cut
// with length L sqrt(d^T M d). With the film's deformation from the cut (rest) state to the
// design state a pure stretch U (no rotation), M = U^-2 = C^-1, C = I + 2E the right
// Cauchy-Green tensor of the Green-Lagrange strain E.
//   uniform: M = diag(1/(1+c_md)^2, 1/(1+c_td)^2): MD lengths cut 1/(1+c_md) of the design,
//            i.e. the film is drawn by the engineering strain c_md (and c_td) back to it;
//   stress:  E = the plane-stress elastic strain of the prestress S (PK2, MPa) under Hooke's law
//            on Green-Lagrange strain (the solver's elastic law, ElasticPlaneStress):
//            Exx = (Sxx - nu Syy)/Y, Eyy = (Syy - nu Sxx)/Y, Exy = (1 + nu) Sxy / Y.
// Stretching such a pattern back to the design shape gives exactly the strain E, hence the
// stress S, in an elastic film.
#pragma once

namespace etfe {

// Green-Lagrange strain (Exx, Eyy, Exy tensor shear) of the plane stress S (Sxx, Syy, Sxy).
// Returns KERNEL_NONFINITE for NaN/Inf input or young <= 0 or nu outside (-1, 0.5).
int CompensationPlaneStressStrain(double young, double nu, const double S[3], double E[3]);

// M = (I + 2E)^-1 as (Mxx, Myy, Mxy). Returns KERNEL_DEGENERATE when I + 2E is not positive
// definite (a compressive strain of 50 % or more: no stretch reaches it), KERNEL_NONFINITE for
// NaN/Inf input.
int CompensationMetricFromStrain(const double E[3], double M[3]);

// M of the uniform compensation (engineering strains c_md, c_td > -1).
int CompensationMetricUniform(double c_md, double c_td, double M[3]);

// An element's stress S_local (S_MD, S_TD, S_MD-TD in its frame: first axis md_axis projected on
// the triangle's plane, falling back to the edge from node 0 to node 1 when md_axis is within
// ~1e-3 of the normal, as MembraneReferenceBuild) turned into the pattern's axes: X the 3D
// triangle (9), xy its flattened image (6, same node order, counter-clockwise seen from the
// normal (X1-X0)x(X2-X0)). The MD axis is carried to the pattern by the triangle's own affine
// map. Returns KERNEL_DEGENERATE for a degenerate triangle in 3D or in the pattern.
int CompensationStressInPattern(const double X[9], const double xy[6], const double md_axis[3],
                                const double S_local[3], double S_pattern[3]);

// The cut length of a design link of length L along the (not necessarily unit, nonzero)
// direction d: L sqrt(d^T M d) / |d|. Returns a negative value for a zero direction.
double CompensatedLength(const double M[3], double L, const double d[2]);

} // namespace etfe
