// Results file: HDF5 (written in parallel with MPI-IO) plus an XDMF index beside it that ParaView
// opens as a time series. Its datasets are the rows of the field table (etfe/io/output_fields.h),
// each described by attributes; groups, root attributes and how to open it: docs/results.md.
// A step's group is complete once it is listed in the XDMF file (rewritten atomically after the
// step is flushed) and counted in steps_written.
#pragma once
#include <petscsys.h>

#include <string>
#include <vector>

#include "etfe/assembly/problem.h"

namespace etfe {

struct OutputFile;

struct OutputOptions {
  char path[PETSC_MAX_PATH_LEN] = "";
  PetscInt every = 1;
  PetscBool enabled = PETSC_TRUE;
  // -output_allow_lost_steps: a restart whose results file is missing or unreadable (or lost some
  // of its steps) continues into a file without those steps (its status then says so) instead of
  // being refused.
  PetscBool allow_lost_steps = PETSC_FALSE;
  // Set by a restart: the results file of the run that wrote the checkpoint ("" if unknown). A
  // restart into another file starts it (it lacks the steps up to the checkpoint, and its status
  // says so); a restart into that one refuses it missing or unreadable, as above.
  std::string checkpoint_results;
};

PetscErrorCode OutputOptionsFromCommandLine(MPI_Comm comm, const char *scene, OutputOptions *o);
// restart_step >= 0: continue the results file of the load history run_id (the checkpoint's),
// dropping the steps after restart_step (a run killed after its last checkpoint wrote them). A
// missing or unreadable file (or one whose earlier steps cannot be read) is refused untouched,
// unless o.allow_lost_steps: then it is started anew (an unreadable one moved aside) and its
// status never says "complete" (root attribute steps_lost, kept through later restarts); one of
// another scene or history is refused untouched. A fresh run (restart_step < 0) gets a new run_id unless one is given.
PetscErrorCode OutputOpen(Problem *problem, const OutputOptions &o, OutputFile **out, PetscInt restart_step = -1,
                          const std::string &run_id = "");
// The load history's identity, stored in the results file and in its checkpoints.
const std::string &OutputRunId(const OutputFile *out);
PetscErrorCode NewRunId(MPI_Comm comm, std::string *id);
// Error exits: marks the open results file (if any) "failed: why" (with "the disk is full" when
// it is) and closes it (collective).
PetscErrorCode OutputAbandon(const std::string &why);
// Whether a results file is open (an error exit then has one to mark).
bool OutputIsOpen();
// On an error exit of one rank, before MPI ends: closes whatever HDF5 still holds open (a file an
// error left half made). False when it cannot: a file's close failed (a full disk; h5io.h), and
// closing the library, here or in MPI_Finalize's callback, would crash on it; the process must
// then end without MPI_Finalize.
bool OutputLibraryClose();
// An error exit of a rank whose partners are elsewhere (no collective write possible): "failed:
// why" in the status note beside the open results file (etfe/io/writer_identity.h), unless a note
// is there already. No MPI. Returns the note's path, or "" when none was written.
std::string OutputNoteFailure(const std::string &why);
// U is the displacement from the scene's mesh; fields (stress, strain, ...) are evaluated at
// U_fields on the problem's current reference (nullptr: U itself — they differ only in form
// finding, where the reference moves).
PetscErrorCode OutputWriteStep(OutputFile *out, Problem *problem, Vec U, PetscInt step,
                               double time, Vec U_fields = nullptr);
// Gathers the current shape (reference + U) to rank 0 as a copy of the scene's mesh.
PetscErrorCode OutputGatherShape(Problem *problem, Vec U, MeshData *shape);
// status: "complete", "stopped ..." or "failed: ..." (a fixed 1 kB attribute rewritten in place,
// so it can be written on a full disk); closes the file, also when the status write fails.
PetscErrorCode OutputClose(OutputFile **out, const std::string &status);
PetscInt OutputLastStep(const OutputFile *out);
PetscInt OutputEvery(const OutputFile *out);
// Directory of the results file (for CSV histories beside it).
std::string OutputDirectory(const OutputFile *out);
// The results file's path without its extension: CSV histories are named <stem>_<what>.csv.
std::string OutputStem(const OutputFile *out);

} // namespace etfe
