// Results file: HDF5 (written in parallel with MPI-IO) plus an XDMF index that ParaView opens
// as a time series. Layout (stable, documented in the README):
//   /                      attributes: format "etfe-results-1", scene, run_id, options (the option
//                          table of the run that created the file), version, status
//                          ("running" | "complete" | "failed: <why>"), steps_written
//   /mesh/coordinates      (N, 3) float64  reference coordinates, scene node order
//   /mesh/triangles        (E, 3) int32    0-based node ids, scene element order
//   /steps/<k:06d>/        attributes: step, time (load time), stage, load_factor (time - stage)
//     displacement (N,3); reaction (N,3); nodal_mises (N)
//     stress (E,3) Sxx Syy Sxy [MPa, element MD/TD frame, PK2]; strain (E,3) Exx Eyy Exy (GL,
//     tensor shear); mises (E); min_principal_stress (E); min_principal_strain (E);
//     area_ratio (E); plastic_strain (E,3) and plastic_strain_eq (E) with a plastic material.
//   /steps/<k>/contact/    (only with contact; C pairs in scene node order)
//     force (C,3) local (x0 tangent, y0, z0 normal; f_z < 0 in compression) [N];
//     slide_local (C,2) and slide_global (C,2: X, Y) since t0 [mm]; status (C) int
//     0 open, 1 stick, 2 slip; node (C) int film node id.
// A step's group is complete once it is listed in the XDMF file (rewritten atomically after the
// step is flushed) and counted in steps_written.
#pragma once
#include <petscsys.h>

#include <string>
#include <vector>

#include "etfe/problem.h"

namespace etfe {

struct OutputFile;

struct OutputOptions {
  char path[PETSC_MAX_PATH_LEN] = "";
  PetscInt every = 1;
  PetscBool enabled = PETSC_TRUE;
};

PetscErrorCode OutputOptionsFromCommandLine(MPI_Comm comm, const char *scene, OutputOptions *o);
// restart_step >= 0: continue the results file of the load history run_id (the checkpoint's),
// dropping the steps after restart_step (a run killed after its last checkpoint wrote them); a
// missing file is started anew, an unreadable one moved aside, one of another scene or history
// refused untouched. A fresh run (restart_step < 0) gets a new run_id unless one is given.
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
