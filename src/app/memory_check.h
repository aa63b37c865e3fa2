// Whether the chosen linear solver fits the nodes' memory, checked before anything large is made.
// A run past a node's memory is not an error the code sees: the system's out-of-memory killer
// ends it minutes later without a message. The estimate is the path's memory per DOF as measured
// with this code (docs/solvers.md), per node: the ranks that share it, each with its share of
// the DOFs.
#pragma once
#include <petscsys.h>

namespace etfe {

// Reads -etfe_memory_check and -etfe_memory_node_gb. Refuses (an error naming the estimate, the
// node's memory and the ways out) when the estimate exceeds a node's memory (its physical memory,
// or the batch job's memory limit where the control group sets one); prints a warning when it
// exceeds what the node has available now. Collective; call it once the linear path's options are
// in the options database.
PetscErrorCode CheckMemoryFits(MPI_Comm comm, PetscInt dof);

} // namespace etfe
