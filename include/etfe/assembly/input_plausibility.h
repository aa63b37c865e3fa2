// The plausibility checks of etfe/kernels/plausibility.h on a run's inputs: a warning is printed once
// (rank 0, "etfe: warning: ..."), an error stops the run with the message. Collective where the
// value is the same on every rank (options); the mesh's check runs where the mesh is (rank 0).
#pragma once
#include <petscsys.h>

#include "etfe/kernels/plausibility.h"

namespace etfe {

class Material;

// Prints c's warning, or raises its error (PETSC_ERR_ARG_OUTOFRANGE); nothing when it is fine.
PetscErrorCode ReportPlausibility(MPI_Comm comm, const PlausibilityCheck &c);
// Young's modulus (ElasticConstants) and, for a law with one, the yield stresses of a material
// made from the -material_* options; call it right after the material is created.
PetscErrorCode MaterialCheckPlausible(MPI_Comm comm, const Material &material, const char *prefix = nullptr);

} // namespace etfe
