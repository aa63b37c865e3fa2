// The true (Cauchy) stress of the membrane from its PK2 stress, for output beside PK2: gauges,
// ANSYS, CalculiX and test curves speak Cauchy. PETSc-free.
#pragma once

namespace etfe {

// sigma = F S F^T / J (docs/theory.md §2), with the film's thickness stretch taken from
// incompressibility (lambda3 = A0/a, so J = 1): exact for the isochoric plastic flow that dominates
// ETFE at the saddle's strains, and 0.1 % off for the elastic part at 1 % strain with nu = 0.43
// (volume change (1 - 2 nu) eps). F: the 3x2 deformation gradient of MembraneKinematics (global x
// local), S: PK2 (Sxx, Syy, Sxy) in the element frame. sigma: global symmetric tensor (xx, yy, zz,
// xy, yz, xz), the order of XDMF's Tensor6.
void CauchyStress(const double F[6], const double S[3], double sigma[6]);

// von Mises stress of a symmetric 3x3 tensor given as (xx, yy, zz, xy, yz, xz).
double MisesStress3(const double s[6]);

// Principal values and unit directions of the in-plane (rank <= 2) symmetric tensor s: p[0] >= p[1]
// are the two eigenvalues whose directions lie in the span of F's columns (the current tangent
// plane), d1 and d2 those directions (global, unit, orthogonal). The third (normal) eigenvalue is
// 0.
void PrincipalStresses(const double F[6], const double s[6], double p[2], double d1[3], double d2[3]);

} // namespace etfe
