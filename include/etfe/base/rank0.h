// Work done on rank 0 only (file reading, flattening) reports its outcome to every rank.
#pragma once
#include <petscsys.h>

#include <string>

namespace etfe {

// Collective: when rank 0's ok is 0, every rank raises `code` with rank 0's message.
PetscErrorCode Rank0Outcome(MPI_Comm comm, int ok, const std::string &err, PetscErrorCode code);

} // namespace etfe
