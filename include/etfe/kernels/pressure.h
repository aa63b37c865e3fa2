// Follower pressure on a three-node membrane (docs/theory.md §4, thesis §5.4). PETSc-free.
// The load acts along the current normal n = (x2-x1)x(x3-x1)/|..| (positive p pushes along n):
//   f_a = p/6 (x2-x1)x(x3-x1)   for each node a
// Its derivative L = df/dx (9x9 row-major, not symmetric) is the load stiffness; the assembler
// adds -L to the tangent because the residual is f_int - f_ext.
#pragma once

namespace etfe {

void PressureLoad(double p, const double x[9], double f[9], double L[81]);

// The same load f, with K -= L applied in place (the Jacobian loop's use): only L's 54 nonzero
// entries are subtracted, with the values PressureLoad gives them, so K comes out bitwise as
// after PressureLoad and K[k] -= L[k] (subtracting +0.0 changes no double). f == nullptr: K
// only (the Jacobian loop has no use for the load; forming it was 57 of the call's 264
// instructions per element).
void PressureLoadSubtractTangent(double p, const double x[9], double f[9], double K[81]);

} // namespace etfe
