// The outer load-stepping loop (TS-like, options -load_*): increments over the stages of the
// scene's schedules, a Newton solve per increment, the increment cut back on divergence and
// grown again on easy steps, history committed after convergence only, output as it goes.
#pragma once
#include <petscsnes.h>

#include "etfe/io/checkpoint.h"
#include "etfe/io/output.h"
#include "etfe/assembly/problem.h"

namespace etfe {

struct LoadStepperOptions {
  PetscInt increments = 10;      // over the whole schedule, split evenly over the stages
  PetscInt max_cutbacks = 6;     // halvings of one increment before the run stops
  PetscInt grow_after = 2;       // easy increments in a row before the increment doubles
  PetscInt easy_iterations = 5;  // Newton iterations that count as easy
  PetscBool extrapolate = PETSC_TRUE;
  // Tangent predictor: a linear solve with the tangent at the committed state for the increment
  // of prescribed values and loads, so the interior follows a jump of the boundary instead of
  // leaving it to Newton's first iterations (+1 factorisation per increment).
  PetscBool tangent_predictor = PETSC_FALSE;
  // Extra diagonal shift (relative to E h) of the predictor's tangent only: at a stress-free start
  // the film's out-of-plane stiffness is nearly zero and the predictor's solve throws the nodes far.
  PetscReal tangent_predictor_shift = 0.0;
  // Newton iteration limit of every increment but the history's first (0: -snes_max_it for all).
  // The slack start needs many capped iterations to let the film sag; a later increment that has
  // not converged in this many is cut back at once instead of running on to -snes_max_it.
  PetscInt max_it = 0;
  PetscInt monitor = 1;
  PetscInt stop_after = -1;      // end cleanly after this many increments (-1: never)
  PetscReal force_rtol = 1e-10;  // converged when |R| <= force_rtol * (reactions + loads)
  // Also converged when |R| <= force_roundoff * eps |x|max E h0 sqrt(elements): the round-off of
  // the membrane forces (coordinates of size |x| differenced over elements of size ~|x|/sqrt(n)),
  // which grows with the mesh density and passes the force test's tolerance near 10^6 elements
  // (and at 10^5 on 2 ranks: the clamped membrane stagnated at 5e-11 N per node in increment 2).
  PetscReal force_roundoff = 10.0;  // 0: off
  // Viscous stabilization (stabilization.cpp) relative to E h0 per node, and when it acts: never,
  // on failure (an increment whose Newton solve failed is solved again stabilized before it is
  // cut back) or always. Proximal passes move its anchor to the converged state and solve again
  // until its force is at most stabilize_rtol of the reactions and loads (0: no passes).
  // Warn once when the committed equivalent plastic strain passes this (0: never): beyond it the
  // small-strain yield law no longer describes the film.
  PetscReal plastic_strain_limit = 0.2;
  PetscReal stabilize = 1e-3;
  PetscInt stabilize_when = 1;  // index into kStabilizeWhen
  PetscReal stabilize_rtol = 0.0;
  PetscInt stabilize_passes = 20;
  // A stabilized increment is an equilibrium (accepted) while its stabilizing force carries at
  // most stabilize_force_max of the forces in play (resultant and moment against the loads, contact
  // forces and reactions); a run while that force did at most stabilize_work_max of the work done
  // on the film (0: no limit). docs/stabilization.md: what was measured, why these values.
  PetscReal stabilize_force_max = 0.1;
  PetscReal stabilize_work_max = 0.25;
  // Refuse a history whose DOF constraints leave a rigid motion of the film free (without rigid
  // contact supports; free_rigid_motions.h); false: only say which motions are free.
  PetscBool check_supports = PETSC_TRUE;
  // After a caught signal (etfe/solver/interrupt.h), how long Newton may go on to finish the increment
  // under way before it is given up and the run stops at the last converged one (s).
  PetscReal signal_grace = 10.0;
  // Fault injection for the fault campaign: rank fail_alone[0] raises an error alone after
  // increment fail_alone[1], while the others go on (-1: never).
  PetscInt fail_alone[2] = {-1, -1};
};
extern const char *const kStabilizeWhen[3];  // never, failure, always

struct LoadStepperResult {
  PetscInt steps = 0, cutbacks = 0, newton_iterations = 0;
  PetscInt stabilized = 0;  // converged increments that needed the stabilization
  double time = 0.0, wall = 0.0;
  PetscBool completed = PETSC_FALSE;
  PetscBool stopped = PETSC_FALSE;  // ended cleanly by -load_stop_after before the schedule's end
  int interrupted = 0;  // the signal that stopped it at a safe point (then also stopped; 0: none)
  std::string failure;  // why it stopped, when it did not complete
};

PetscErrorCode LoadStepperOptionsFromCommandLine(MPI_Comm comm, LoadStepperOptions *o);
// Adds the force-balance test to SNES's own (rtol/atol/stol): |R| <= force_rtol * (size of the
// reactions and external loads), which stays reachable when stiff penalties put the round-off
// floor of |R| above any fixed atol (load_stepper_convergence.cpp); and the monitor of the tangent
// shift's work that the progress lines report (tangent_shift.h).
PetscErrorCode LoadStepperSetConvergenceTest(Problem *problem, SNES snes, const LoadStepperOptions &o);
// Runs the schedule, one increment after the other: attempt, then commit or cut back
// (load_stepper.cpp). On failure writes the last converged state (if not yet written) and
// returns with result->completed false and the reason; the caller decides the exit code.
// With ck.restart set, continues from that checkpoint; writes checkpoints as ck asks.
PetscErrorCode LoadStepperRun(Problem *problem, SNES snes, OutputFile *out,
                              const LoadStepperOptions &o, const CheckpointOptions &ck,
                              LoadStepperResult *result);

} // namespace etfe
