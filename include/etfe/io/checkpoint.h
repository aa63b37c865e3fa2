// Checkpoint/restart of a load history (options -checkpoint_*, -restart). A checkpoint holds
// the committed state in the scene's order, so any number of ranks can read it:
//   attrs: format "etfe-checkpoint-3", scene, run_id, options (one "-name value" per line),
//          nodes, elements, pairs, history_size, stages, mesh_fingerprint (coordinates,
//          triangles, node and element sets), physics_fingerprint (what the options resolve
//          to), the stepper state (t, dt, dt_last, step, converged_states, easy, cutbacks,
//          newton) and data_checksum (a rank-count-independent 64-bit checksum of every value
//          above and below)
//   u_committed (N,3), u_previous (N,3), history (E,h) if the material has one,
//   contact_state (C,7: g x0 y0 z0, f x0 y0 z0, status) if the scene has contact,
//   scene_state (the scene monitor's values) if the scene has one.
// It is written in HDF5's newest format (its metadata carry HDF5's own checksums) to
// <file>.tmp, synced and renamed, so a killed run leaves the previous checkpoint intact; a
// failed write removes the .tmp. Restarting on the same number of ranks continues bit for bit.
#pragma once
#include <petscvec.h>

#include <cstdint>
#include <string>

#include "etfe/assembly/problem.h"

namespace etfe {

struct StepperState {
  double t = 0.0, dt = 0.0, dt_last = 0.0;
  PetscInt step = 0, converged_states = 0, easy = 0, cutbacks = 0, newton = 0;
};

struct CheckpointOptions {
  PetscInt every = 0;  // increments between checkpoints (0: none, except at -load_stop_after)
  PetscReal every_s = 0.0;           // wall-clock seconds between checkpoints (0: none)
  PetscBool stage_end = PETSC_TRUE;  // a checkpoint at each stage end (with a results file)
  char file[PETSC_MAX_PATH_LEN] = "";
  char restart[PETSC_MAX_PATH_LEN] = "";
  // -restart_branch: `restart` is a base state (a stage end) from which this run starts its own
  // loads (the stages after it), writing a results file of its own (checkpoint_compare.cpp).
  PetscBool branch = PETSC_FALSE;
  // -checkpoint_final: a checkpoint of the last state too, once the history completed (the base
  // state that -restart_branch runs start from).
  PetscBool final = PETSC_FALSE;
};

// results_stem: the results file without its extension; the default checkpoint goes beside it.
PetscErrorCode CheckpointOptionsFromCommandLine(MPI_Comm comm, const std::string &results_stem, CheckpointOptions *o);
// At set-up, before any work: rank 0 makes the checkpoint's directory and writes a test file in
// it, so that an unwritable directory is refused now (naming -checkpoint_file) rather than at the
// first checkpoint, after a stage's work. Collective.
PetscErrorCode CheckpointCheckWritable(MPI_Comm comm, const CheckpointOptions &o);
// run_id: the load history's identity (OutputRunId), checked against the results file on restart.
PetscErrorCode CheckpointWrite(Problem *problem, const std::string &path, const StepperState &state,
                               Vec U_committed, Vec U_previous, const std::string &run_id);
// Everything CheckpointRead checks, without changing the problem: call it before anything on disk
// is touched, so a refused restart changes nothing. Rank 0 first reads the whole file against its
// checksum; then scene, mesh, shape, resolved physics and every option other than those that may
// change on a restart (solver, output, monitors: checkpoint_compare.cpp) must agree, and a
// refusal lists each differing option with both values. Returns the increment and run id and,
// when results_file is given, the results file of the run that wrote it (its -output_file, or the
// default results/<scene>/<scene>.h5; as that run gave it, relative to its working directory).
PetscErrorCode CheckpointValidate(Problem *problem, const std::string &path, PetscInt *step, std::string *run_id,
                                  std::string *results_file = nullptr, bool branch = false);
// Takes the fingerprints a checkpoint compares the scene by from rank 0's global description
// (the mesh: coordinates, triangles, node and element sets; the physics: schedules, constraints,
// loads, supports, element data, with the problem's thickness and area ratio) and stores them
// in the problem on every rank (collective). Call it before ProblemCreate, which may drop the
// description once distributed.
PetscErrorCode CheckpointFingerprintScene(MPI_Comm comm, const SceneSpec &scene, Problem *problem);
// Refuses (with the reason) a checkpoint of another scene, mesh, material, contact set or
// physics options, or one whose data do not match its checksum.
// branch: the comparison of -restart_branch (the loads after the checkpoint's stage end may differ).
PetscErrorCode CheckpointRead(Problem *problem, const std::string &path, StepperState *state,
                              Vec U_committed, Vec U_previous, bool branch = false);

} // namespace etfe
