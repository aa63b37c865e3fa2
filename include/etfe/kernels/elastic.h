// Plane-stress St. Venant-Kirchhoff law in the membrane's local frame: S = D E, with
// D = E/(1-nu^2) [[1,nu,0],[nu,1,0],[0,0,(1-nu)/2]] for E = (Exx, Eyy, 2Exy). PETSc-free.
#pragma once

namespace etfe {

void ElasticPlaneStressTangent(double young, double nu, double D[9]);
void ElasticPlaneStress(double young, double nu, const double E[3], double S[3], double D[9]);

} // namespace etfe
