// -help without a scene: every component's options, so that -help alone is the manual.
#pragma once
#include <petscsys.h>

namespace etfe {

// Reads the options of every component a case may use (form finding, material with the
// plastic law's, membrane, load stepping, output, checkpoints, contact, LU choice, SNES and the
// etfe line search) without building anything; PETSc prints them as they are read.
PetscErrorCode ListEveryOption(MPI_Comm comm);

} // namespace etfe
