// Whether the chosen linear solver fits the nodes' memory, checked before anything large is made.
// A run past a node's memory is not an error the code sees: the system's out-of-memory killer
// ends it minutes later without a message. The estimate is the path's memory per DOF as measured
// with this code (docs/solvers.md), per node: the ranks that share it, each with its share of
// the DOFs.
#pragma once
#include <petscsys.h>

#include "etfe/assembly/linear_path.h"

namespace etfe {

// Reads -etfe_memory_check and -etfe_memory_node_gb. Refuses (an error naming the estimate, the
// node's memory and the ways out) when the estimate exceeds a node's memory (its physical memory,
// or the batch job's memory limit where the control group sets one); prints a warning when it
// exceeds what the node has available now. The estimate is the decided path's memory per DOF
// (linear_path.h) times its DOF. Collective.
PetscErrorCode CheckMemoryFits(MPI_Comm comm, const LinearPath &path);

} // namespace etfe
