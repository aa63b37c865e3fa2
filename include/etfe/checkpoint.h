// Checkpoint/restart of a load history (options -checkpoint_*, -restart). A checkpoint holds
// the committed state in the scene's order, so any number of ranks can read it:
//   attrs: format "etfe-checkpoint-2", scene, nodes, elements, pairs, history_size, stages,
//          mesh_checksum, options (the command line, for the record) and the stepper state
//          (t, dt, dt_last, step, converged_states, easy, cutbacks, newton), data_checksum (a
//          rank-count-independent 64-bit checksum of every value above and below)
//   u_committed (N,3), u_previous (N,3), history (E,h) if the material has one,
//   contact_state (C,7: g x0 y0 z0, f x0 y0 z0, status) if the scene has contact.
// It is written to <file>.tmp and renamed, so a killed run leaves the previous checkpoint
// intact. Restarting on the same number of ranks continues bit for bit.
#pragma once
#include <petscvec.h>

#include <string>

#include "etfe/problem.h"

namespace etfe {

struct StepperState {
  double t = 0.0, dt = 0.0, dt_last = 0.0;
  PetscInt step = 0, converged_states = 0, easy = 0, cutbacks = 0, newton = 0;
};

struct CheckpointOptions {
  PetscInt every = 0;  // increments between checkpoints (0: none, except at -load_stop_after)
  char file[PETSC_MAX_PATH_LEN] = "";
  char restart[PETSC_MAX_PATH_LEN] = "";
};

PetscErrorCode CheckpointOptionsFromCommandLine(MPI_Comm comm, const char *scene, CheckpointOptions *o);
// run_id: the load history's identity (OutputRunId), checked against the results file on restart.
PetscErrorCode CheckpointWrite(Problem *problem, const std::string &path, const StepperState &state,
                               Vec U_committed, Vec U_previous, const std::string &run_id);
// The increment a checkpoint was written at (collective; refuses unreadable files).
PetscErrorCode CheckpointPeekStep(MPI_Comm comm, const std::string &path, PetscInt *step);
// Everything CheckpointRead checks, without changing the problem: call it before anything on disk
// is touched, so a refused restart changes nothing. Returns the checkpoint's increment.
PetscErrorCode CheckpointValidate(Problem *problem, const std::string &path, PetscInt *step, std::string *run_id);
// Refuses (with the reason) a checkpoint of another scene, mesh, material, contact set or
// physics options, or one whose data do not match its checksum.
PetscErrorCode CheckpointRead(Problem *problem, const std::string &path, StepperState *state,
                              Vec U_committed, Vec U_previous);

} // namespace etfe
