// Frictionless contact of a film node with a triangle of another film layer (a cushion's top foil
// resting on the foil below it). PETSc-free.
//
// The node xs keeps to one side of the triangle's plane: its signed distance
//   g = side (xs - x1).n,  n = (x2-x1)x(x3-x1)/|(x2-x1)x(x3-x1)|,
// side = +1 or -1 the side it started on. A penalty energy W = k/2 min(0, g)^2 (k [N/mm]: the
// pressure per unit penetration times the node's tributary area) acts only while g < 0; its
// gradient is the contact force on the 12 DOFs (xs, x1, x2, x3), so the force on the triangle's
// nodes follows from the same energy (it turns the triangle as well as pushing it), and the
// tangent is its Hessian: k (dg dg^T + min(0, g) d2g), d2g from central differences of the exact
// gradient dg. Newton uses k dg dg^T alone (`curvature` false): positive semi-definite whatever
// the iterate (a predictor that throws the film 0.6 m through the layer below made the full
// Hessian singular), and the part left out is O(g / triangle size), ~1e-3 at equilibrium.
#pragma once

namespace etfe {

// g and, when dg is given, its gradient (12: xs, x1, x2, x3). x: 12 values in that order.
// Returns false for a degenerate triangle.
bool LayerGap(const double x[12], double side, double *g, double dg[12]);

// The penalty's force f (12, the gradient of W) and, when K is given, its Hessian K (144, row
// major; without the gap's curvature term unless `curvature`). Returns the gap; f and K are zero
// while it is positive.
double LayerContactForce(const double x[12], double side, double k, double f[12], double K[144],
                         bool curvature = false);

} // namespace etfe
