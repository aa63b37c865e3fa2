// The solver a case gets unless its options say otherwise: Newton with the etfe line search, a
// direct solve (KSP preonly + LU) and the LU package chosen by the size of the system.
#pragma once
#include <petscsnes.h>

#include "etfe/assembly/problem.h"

namespace etfe {

// The LU package of pc when the options name none, as the linear path decided (P->linear_path:
// PETSc's own LU with AMD for small systems on one rank, MUMPS otherwise).
PetscErrorCode ChooseLUPackage(Problem *P, PC pc);
// The SNES of P (residual, Jacobian, tolerances, KSP/PC, line search) with the defaults above,
// then SNESSetFromOptions: options files and the command line override every default.
PetscErrorCode CreateSolver(Problem *P, SNES *snes);

} // namespace etfe
