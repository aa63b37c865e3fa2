// The cables of a scene (SceneSpec::cables) as a physics term (physics_term.h; the formulation is
// docs/theory.md §14 and etfe/kernels/cable.h, the modelling guide docs/cables.md). Assembly layer.
#pragma once
#include "etfe/assembly/physics_term.h"
#include "etfe/assembly/problem.h"

namespace etfe {

// Adds the cable term to P->terms and sets it up when the scene has cables (collective; after
// ProblemCreate). Nothing when it has none.
PetscErrorCode CableTermAdd(Problem *P);

// The largest displacement in U (owned part) of a cable node: form finding's convergence measure
// for the edges the cables hold (collective).
PetscErrorCode CableLargestMove(Problem *P, Vec U, PetscReal *move);

// The clamps' committed state in the checkpoint (written only by runs with clamps): per clamp
// the stress-free length passed on, the last increment's slip and status (TermCheckpointDatasets).
extern const TermDatasetInfo kCableCheckpoint;

} // namespace etfe
