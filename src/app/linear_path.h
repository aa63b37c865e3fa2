// The linear solver chosen by the size of the system and the rank count (-etfe_solver): a sparse
// direct factorization for every step where it is fastest (this machine, up to a few ranks),
// the scalable path above -etfe_scalable_min_dof DOF or from -etfe_scalable_min_ranks ranks.
#pragma once
#include <petscsys.h>

#include "etfe/problem.h"

namespace etfe {

// Reads -etfe_solver auto|direct|scalable and, where the scalable path is chosen, puts its
// settings into the options database (before the solver reads it) and prints why. auto keeps
// whatever the options say below the thresholds, and a Krylov method the options name above them.
PetscErrorCode ChooseLinearPath(Problem *P);

} // namespace etfe
