// The linear solver chosen by the size of the system and the rank count (-etfe_solver): a sparse
// direct factorization for every step where it is fastest (this machine, up to a few ranks),
// the scalable path above -etfe_scalable_min_dof DOF or from -etfe_scalable_min_ranks ranks.
#pragma once
#include <petscsys.h>

#include "etfe/problem.h"

namespace etfe {

// Reads -etfe_solver auto|direct|scalable and, where the scalable path is chosen for a system of
// num_nodes nodes (3 DOF each) on comm's ranks, puts its settings into the options database and
// prints why. Called before the problem reads its options (the path names the matrix type and the
// near-null space). auto keeps whatever the options say below the thresholds, and a Krylov
// method the options name above them. Then checks that the path fits the nodes' memory
// (memory_check.h).
PetscErrorCode ChooseLinearPath(MPI_Comm comm, PetscInt num_nodes);

} // namespace etfe
