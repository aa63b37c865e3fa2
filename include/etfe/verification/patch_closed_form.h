// The patch test's closed form: a homogeneous Green-Lagrange strain in a linear elastic
// (Saint Venant-Kirchhoff) plane-stress film gives the same PK2 stress in every element.
// Written out from Hooke's law here rather than taken from the solver's kernel
// (kernels/elastic.h), so the patch scene checks the kernel against an independent formula.
// PETSc-free.
#pragma once

namespace etfe {

// S[0] = Sxx, S[1] = Syy (MPa) for the strains Exx, Eyy (no shear).
// Biaxial (lateral_free = false): S = E/(1 - nu^2) (Exx + nu Eyy, Eyy + nu Exx).
// Uniaxial (lateral_free = true, the film free to contract across): Sxx = E Exx, Syy = 0, and
// Eyy is not used.
void PatchClosedFormStress(double young, double nu, double Exx, double Eyy, bool lateral_free,
                           double S[2]);

} // namespace etfe
