// The registry of physics terms (assembly layer, private to ProblemCreate): physics_terms.cpp.
#pragma once
#include <vector>

#include "etfe/assembly/problem.h"

namespace etfe {

// Creates the terms the scene uses, in the order the residual and the Jacobian sum their parts:
// at the end of ProblemCreate (vectors, matrix and U at load time 0 exist). pressure_elements:
// per pressure load its local elements (moved from); forces: the nodal forces on owned nodes.
PetscErrorCode MakePhysicsTerms(Problem *P, std::vector<std::vector<PetscInt>> *pressure_elements,
                                const std::vector<NodalForce> &forces);

} // namespace etfe
