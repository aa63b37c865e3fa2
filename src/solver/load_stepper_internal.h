// The load stepper's state and an increment's attempt, shared by its loop (load_stepper.cpp) and
// its reports (load_stepper_report.cpp). Private to src/solver.
#pragma once
#include <petscsnes.h>

#include <cstdio>
#include <string>

#include "etfe/assembly/assembly.h"
#include "etfe/kernels/status.h"
#include "etfe/solver/load_stepper.h"

namespace etfe {
namespace load_stepping {

constexpr double kTimeEps = 1e-12;  // load times closer than this are the same

// The load history between increments: the committed state (what a checkpoint saves: load time,
// increment sizes, counters, the last two converged U) and the run's accounting.
struct LoadStepper {
  Problem *P;
  SNES snes;
  OutputFile *out;
  const LoadStepperOptions &o;
  const CheckpointOptions &ck;
  LoadStepperResult *res;
  // The schedule: stages of unit load time, per_stage nominal increments in each.
  int nstages;
  double t_end;
  PetscInt per_stage;
  double dt_nominal;
  // Committed: load time, the size of the next increment and of the last converged one.
  double t = 0.0, dt, dt_last = 0.0;
  PetscInt step = 0, easy = 0;  // easy: easy increments in a row
  // Extrapolate only from converged states: a scene's initial guess is not one.
  PetscInt converged_states;
  Vec U_committed = nullptr, U_previous = nullptr;  // converged states n and n-1
  // The film's internal forces at U_committed (committed history), and scratch for the work.
  Vec Fint_committed = nullptr, Fint = nullptr, dU = nullptr;
  Vec F = nullptr;  // SNES's residual (not owned), for failure messages
  // -contact_lagged_repeat: the last converged solve of the increment, and the repeated solves
  // and the increments whose statuses did not settle (over the run).
  Vec U_solved = nullptr;
  PetscInt lagged_repeats = 0, lagged_unsettled = 0;
  double work_total = 0.0, shift_work_total = 0.0;
  double work_magnitude = 0.0;  // sum of |work| of the increments (a load cycle does not cancel it)
  double stab_work_total = 0.0, stab_force_max = 0.0;  // of the stabilized increments
  // The stabilized increment whose force carried the largest share of the forces in play.
  struct {
    PetscInt step = -1;
    double share = 0.0;
    StabilizingForce force;
  } worst_stabilized;
  bool strain_warned = false;  // -load_plastic_strain_limit passed (warned once)
  // Progress lines: cut-backs shown so far, pair lift-offs since the last line.
  PetscInt cutbacks_printed = 0;
  PetscLogDouble t0 = 0.0;
  // The increment of the last checkpoint written and when (wall clock, -checkpoint_every_s).
  PetscInt checkpoint_step = -1;
  PetscLogDouble checkpoint_time = 0.0;
  // SNES's own tolerances, restored at the end (-load_max_it lowers max_it per increment).
  PetscReal snes_atol = 0.0, snes_rtol = 0.0, snes_stol = 0.0;
  PetscInt snes_max_it = 0, snes_max_f = 0;

  LoadStepper(Problem *P, SNES snes, OutputFile *out, const LoadStepperOptions &o, const CheckpointOptions &ck,
              LoadStepperResult *res)
      : P(P), snes(snes), out(out), o(o), ck(ck), res(res), nstages(P->scene.NumStages()), t_end(nstages),
        per_stage((o.increments + nstages - 1) / nstages), dt_nominal(1.0 / per_stage), dt(dt_nominal),
        converged_states(P->has_initial_guess ? 0 : 1) {}
  bool Finished() const { return t >= t_end - kTimeEps; }
  bool AtStageEnd() const { return std::fabs(t - std::round(t)) < kTimeEps; }
};

// One attempt at the increment from the committed load time t to t_new, and how its Newton solve
// ended. An attempt changes only the iterate (P->U, at load time t_new) and the trial states the
// residual leaves, never the committed state, so it can be made again for the same increment.
struct Increment {
  double t = 0.0, dt_try = 0.0, t_new = 0.0;
  PetscInt max_it = 0;  // Newton iteration limit of this attempt
  PetscLogDouble start = 0.0;
  SNESConvergedReason reason = SNES_CONVERGED_ITERATING;
  PetscInt its = 0;
  PetscReal fnorm = 0.0;
  // Stabilized (-load_stabilize_when): the stabilizing force at the answer; unbalanced: it carries
  // more of the forces in play than -load_stabilize_force_max allows (the attempt is refused).
  bool stabilized = false, unbalanced = false;
  StabilizingForce stab;
  bool Converged() const { return reason > 0; }
};

// Why an increment's Newton solve failed, with what it usually means and the way out.
struct IncrementFailure {
  SNESConvergedReason reason;
  PetscInt its;
  PetscInt worst_node;  // scene id of the largest residual entry, and its size
  double worst;
  PetscInt bad_element;  // the last element problem (SolveDiagnostics)
  int bad_status;
  std::string hint;    // "; " and the terms' line-search hints (PhysicsTerm::LineSearchHint), or ""
  bool load_max_it;    // the attempt's iteration limit was -load_max_it, not -snes_max_it
  std::string linear;  // the linear solver ("gmres + gamg"; "preonly + lu" for a direct one)
  KSPConvergedReason ksp_reason = KSP_CONVERGED_ITERATING;  // its last solve
  PetscInt ksp_its = 0;

  std::string Message() const {
    char why[512];
    const char *name = SNESConvergedReasons[reason];
    if (reason == SNES_DIVERGED_LINE_SEARCH && bad_status == KERNEL_OK)
      std::snprintf(why, sizeof why,
                    "%s (no step along the Newton direction reduced the residual; largest residual %.3e at node %lld%s)",
                    name, worst, (long long)worst_node, hint.c_str());
    else if (reason == SNES_DIVERGED_FUNCTION_DOMAIN || reason == SNES_DIVERGED_LINE_SEARCH)
      std::snprintf(why, sizeof why, "%s (last element problem: element %lld, %s; largest residual %.3e at node %lld)",
                    name, (long long)bad_element, KernelStatusName(bad_status), worst, (long long)worst_node);
    else if (reason == SNES_DIVERGED_LINEAR_SOLVE && linear.rfind("preonly", 0) != 0)
      std::snprintf(why, sizeof why,
                    "%s (the Krylov solve %s stopped with %s after %lld iterations: the preconditioner does not "
                    "carry this tangent; raise -ksp_max_it, try -etfe_pc_shift, or a direct solver: "
                    "-options_file options/solvers/mumps_lu.opts; largest residual %.3e at node %lld)",
                    name, linear.c_str(), KSPConvergedReasons[ksp_reason], (long long)ksp_its, worst,
                    (long long)worst_node);
    else if (reason == SNES_DIVERGED_LINEAR_SOLVE)
      std::snprintf(why, sizeof why,
                    "%s (the linear solver failed: a singular tangent, e.g. an unsupported rigid motion, or MUMPS out "
                    "of workspace with stiff penalties: -mat_mumps_icntl_14 400, -ksp_error_if_not_converged shows "
                    "its error; largest residual %.3e at node %lld)",
                    name, worst, (long long)worst_node);
    else
      std::snprintf(why, sizeof why, "%s after %lld Newton iterations (largest residual %.3e at node %lld%s)", name,
                    (long long)its, worst, (long long)worst_node,
                    reason == SNES_DIVERGED_MAX_IT && load_max_it ? "; the limit after the first increment is -load_max_it"
                                                                  : "");
    return why;
  }
};

// Whether a stabilized increment is an equilibrium (load_stepper_equilibrium.cpp). The
// stabilizing force f at the answer is the out-of-balance force of the unstabilized equations; its
// share of the forces in play is the larger of |sum f| / sum |g| and |sum (x - c) x f| /
// sum |x - c| |g| (g: what the film takes from outside, per node). More than
// -load_stabilize_force_max: the stabilization carries the load (inc->unbalanced).
double ForceShare(const StabilizingForce &f);
void CheckStabilizedIncrement(const LoadStepper &s, Increment *inc);
// An unbalanced increment is cut back: its line, and once the cut-backs are spent the run's
// failure, "not in equilibrium", naming the increment, the share, where the force is largest,
// the likely cause and the ways out.
PetscErrorCode ReportUnbalancedIncrement(LoadStepper *s, const Increment &inc, bool exhausted);
// A committed stabilized increment's work and force in the run's accounting.
void AccountStabilizedIncrement(LoadStepper *s, const Increment &inc);
// At the run's end: the stabilization summary line and, at the end of the schedule, the run's
// failure when the stabilizing force did more than -load_stabilize_work_max of the work done on
// the film (collective).
PetscErrorCode StabilizationSummary(LoadStepper *s);
// Why the attempt failed (SNES's reason, the element or node at fault, the way out).
PetscErrorCode DiagnoseFailure(const LoadStepper &s, const Increment &inc, IncrementFailure *f);
// A converged increment seen from outside: the progress line (every -load_monitor increments, the
// first, a stage's end, the last, after a cut-back and when stabilized), the scene's monitor,
// the terms' files (contact probes); the terms' progress text (PhysicsTerm::Progress).
PetscErrorCode ReportIncrement(LoadStepper *s, const Increment &inc);
// A failed attempt seen from outside: the cut-back line, and the run's failure once the
// cut-backs are spent.
PetscErrorCode ReportFailedIncrement(LoadStepper *s, const Increment &inc, const IncrementFailure &failure,
                                     bool exhausted);
// Collective, after a converged increment and its results (load_stepper_interrupt.cpp): whether
// a checkpoint of it is due (-checkpoint_every_s on rank 0's clock, -checkpoint_stage_end, a
// signal; none when one was just written) and whether a signal stops the run here.
PetscErrorCode SafePoint(LoadStepper *s, bool *checkpoint, bool *stop);
// After an attempt that Newton gave up because a signal's -etfe_signal_grace ran out: stop (the
// committed state is the last converged one), with the signal every rank agrees on.
PetscErrorCode StopWithinIncrement(LoadStepper *s, const Increment &inc, bool *stop);

} // namespace load_stepping
} // namespace etfe
