// The branch restart's part of a checkpoint (private to src/io; -restart_branch,
// docs/design-run.md): the load-path fingerprints, one per stage end (LoadPathStates gone on with
// the contact set and material), written and verified with the checkpoint's checksum, and the
// comparison a branch makes with them.
#pragma once
#include <hdf5.h>

#include <cstdint>
#include <string>

#include "etfe/assembly/problem.h"

namespace etfe {

// Writes dataset load_path_fingerprints (collective; rank 0's rows) and adds it to *sum.
PetscErrorCode LoadPathWrite(Problem *problem, const std::string &file, hid_t f, std::uint64_t *sum);
// Rank 0 alone, on a file opened for reading: adds the dataset to *sum when there (checkpoints
// written before it have none); false when it is there but cannot be read.
bool LoadPathVerify(hid_t f, std::uint64_t *sum);
// Once the mesh and the options agree: why this run is no branch of the checkpoint (appended to
// *table), or nothing. The checkpoint must be at a stage end k before this run's last stage, and
// its fingerprint k must be this run's.
PetscErrorCode BranchDifferences(Problem *problem, const std::string &path, hid_t f, std::string *table);

} // namespace etfe
