// Load stepping (see load_stepper.h): a time loop over the load time, as PETSc's TSSolve.
// Each increment is
//   NextIncrement     step-size control: the next increment, ending no later than its stage;
//   AttemptIncrement  predictor and Newton solve from the committed state (it commits nothing,
//                     so the same increment can be attempted again);
// and then, converged:
//   CheckStabilizedIncrement  a stabilized answer whose force carries the load is no equilibrium:
//                     cut back as a failed one (load_stepper_equilibrium.cpp);
//   RepeatLaggedIncrement  (-contact_lagged_repeat) solved again while its lagged statuses change;
//   CommitIncrement   material history, contact states, work, U and load time committed;
//   GrowIncrement     step-size control: a cut increment grows again after easy ones;
//   ReportIncrement, WriteIncrementResults  progress line and monitors; output and checkpoints;
// or failed:
//   IncrementFailure  why (SNES's reason, the element or node at fault, the way out);
//   CutBack           (U back at the committed state) the increment halved, the run stopped
//                     once -load_max_cutbacks halvings are spent.
// Before the first increment, a film whose constraints leave a rigid motion free is refused
// (free_rigid_motions.h).
// Committed state = (U, material history, contact states, load time): a failed attempt leaves
// history and contact untouched, so a cut-back repeats the increment from exactly its start.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>

#include "etfe/assembly/assembly.h"
#include "etfe/assembly/free_rigid_motions.h"
#include "etfe/solver/interrupt.h"
#include "etfe/kernels/status.h"
#include "etfe/solver/load_stepper.h"
#include "etfe/base/log_events.h"
#include "etfe/solver/pc_refresh.h"
#include "etfe/solver/tangent_shift.h"
#include "load_stepper_internal.h"

namespace etfe {

using namespace load_stepping;

const char *const kStabilizeWhen[3] = {"never", "failure", "always"};

PetscErrorCode LoadStepperOptionsFromCommandLine(MPI_Comm comm, LoadStepperOptions *o) {
  PetscFunctionBeginUser;
  PetscOptionsBegin(comm, nullptr, "Load stepping", "LoadStepper");
  PetscCall(PetscOptionsInt("-load_increments",
                            "Number of load increments over the whole schedule (split evenly over "
                            "its stages)",
                            "", o->increments, &o->increments, nullptr));
  PetscCall(PetscOptionsInt("-load_max_cutbacks", "Halvings of one increment before giving up",
                            "", o->max_cutbacks, &o->max_cutbacks, nullptr));
  PetscCall(PetscOptionsInt("-load_grow_after",
                            "Easy increments in a row before a cut increment doubles again", "",
                            o->grow_after, &o->grow_after, nullptr));
  PetscCall(PetscOptionsInt("-load_easy_iterations", "Newton iterations that count as easy", "",
                            o->easy_iterations, &o->easy_iterations, nullptr));
  PetscCall(PetscOptionsBool("-load_extrapolate",
                             "Predict each increment by linear extrapolation of the last two", "",
                             o->extrapolate, &o->extrapolate, nullptr));
  PetscCall(PetscOptionsBool("-load_tangent_predictor",
                             "Predict each increment with the tangent at the committed state (one linear solve)",
                             "", o->tangent_predictor, &o->tangent_predictor, nullptr));
  PetscCall(PetscOptionsReal("-load_tangent_predictor_shift",
                             "Extra tangent-only diagonal shift (relative to E h) in the tangent predictor's solve (a "
                             "slack film's predictor then moves less far; the answer is unchanged)",
                             "", o->tangent_predictor_shift, &o->tangent_predictor_shift, nullptr));
  PetscCall(PetscOptionsInt("-load_max_it",
                            "Newton iteration limit of every increment but the history's first, which keeps "
                            "-snes_max_it for the slack start (0: -snes_max_it for all)",
                            "", o->max_it, &o->max_it, nullptr));
  PetscCall(PetscOptionsInt("-load_monitor", "Print one line per increment (0: quiet)", "",
                            o->monitor, &o->monitor, nullptr));
  PetscCall(PetscOptionsInt("-load_stop_after", "End the run cleanly after this many increments",
                            "", o->stop_after, &o->stop_after, nullptr));
  PetscCall(PetscOptionsReal("-load_force_rtol",
                             "Converged when |R| <= this * (norm of reactions and external loads)",
                             "", o->force_rtol, &o->force_rtol, nullptr));
  PetscCall(PetscOptionsReal("-load_force_roundoff",
                             "Also converged when |R| <= this * eps |x|max E h0 sqrt(triangles), the round-off floor "
                             "of the membrane forces, which dense meshes (~10^5-10^6 triangles) reach above the force "
                             "test (0: off)",
                             "", o->force_roundoff, &o->force_roundoff, nullptr));
  PetscCall(PetscOptionsReal("-load_plastic_strain_limit",
                             "Warn (once, naming the element, its position and the increment) when the equivalent "
                             "plastic strain passes this: the small-strain yield law's range (0: never)",
                             "", o->plastic_strain_limit, &o->plastic_strain_limit, nullptr));
  PetscCall(PetscOptionsEList("-load_stabilize_when",
                              "Viscous stabilization of an increment: never, failure (an increment whose Newton solve "
                              "failed is solved again stabilized before it is cut back) or always",
                              "", kStabilizeWhen, 3, kStabilizeWhen[o->stabilize_when], &o->stabilize_when, nullptr));
  PetscCall(PetscOptionsReal("-load_stabilize",
                             "Stabilizing force per node and mm of the increment's motion, relative to E h0 (slack or "
                             "compressed film; its work is reported)",
                             "", o->stabilize, &o->stabilize, nullptr));
  PetscCall(PetscOptionsReal("-load_stabilize_rtol",
                             "Proximal passes: solve a stabilized increment again from its answer until the "
                             "stabilizing force is at most this times the reactions and loads (0: no passes)",
                             "", o->stabilize_rtol, &o->stabilize_rtol, nullptr));
  PetscCall(PetscOptionsInt("-load_stabilize_passes", "Most proximal passes per increment", "", o->stabilize_passes,
                            &o->stabilize_passes, nullptr));
  PetscCall(PetscOptionsReal("-load_stabilize_force_max",
                             "A stabilized increment is an equilibrium while its stabilizing force carries at most this "
                             "share of the forces in play (resultant and moment against the loads, contact forces and "
                             "reactions); above it the increment is cut back, and the run fails \"not in "
                             "equilibrium\" once the cut-backs are spent (0: no limit)",
                             "", o->stabilize_force_max, &o->stabilize_force_max, nullptr));
  PetscCall(PetscOptionsReal("-load_stabilize_work_max",
                             "A run whose stabilizing force did more than this share of the work done on the film "
                             "(increments' work magnitudes) fails \"not in equilibrium\" at its end (0: no limit)",
                             "", o->stabilize_work_max, &o->stabilize_work_max, nullptr));
  PetscCall(PetscOptionsBool("-load_check_supports",
                             "Refuse a load history whose DOF constraints leave a rigid motion of the film free (a "
                             "translation or rotation no support touches) unless rigid contact supports may hold it; "
                             "false: only print the free motions",
                             "", o->check_supports, &o->check_supports, nullptr));
  PetscCall(PetscOptionsReal("-etfe_signal_grace",
                             "After SIGTERM, SIGINT, SIGUSR1 or SIGXCPU: seconds Newton may go on to finish the increment "
                             "under way; then the run stops at the last converged increment (checkpoint, results "
                             "\"interrupted\", exit status 75)",
                             "", o->signal_grace, &o->signal_grace, nullptr));
  PetscInt n = 2;
  PetscCall(PetscOptionsIntArray("-etfe_test_fail_alone",
                                 "Testing: rank r raises an error alone after increment k (r,k), the others go on",
                                 "", o->fail_alone, &n, nullptr));
  PetscOptionsEnd();
  PetscCheck(o->signal_grace >= 0, comm, PETSC_ERR_ARG_OUTOFRANGE,
             "-etfe_signal_grace %g: use seconds >= 0 (0: stop within the first Newton iteration after the signal)",
             (double)o->signal_grace);
  PetscCheck(o->stabilize_force_max >= 0 && o->stabilize_work_max >= 0, comm, PETSC_ERR_ARG_OUTOFRANGE,
             "-load_stabilize_force_max %g, -load_stabilize_work_max %g: use shares >= 0 (0: no limit)",
             (double)o->stabilize_force_max, (double)o->stabilize_work_max);
  PetscCheck(o->stabilize > 0 && o->stabilize_rtol >= 0 && o->stabilize_passes >= 0, comm, PETSC_ERR_ARG_OUTOFRANGE,
             "-load_stabilize %g, -load_stabilize_rtol %g, -load_stabilize_passes %" PetscInt_FMT
             ": use a positive stabilization, a tolerance >= 0 and passes >= 0", (double)o->stabilize,
             (double)o->stabilize_rtol, o->stabilize_passes);
  // Bounds keep the step arithmetic (increments + stages, 2^cutbacks) far from overflow and the
  // smallest increment far above the round-off of the load time.
  const PetscInt max_increments = 1000000, max_cutbacks = 30;
  PetscCheck(o->increments >= 1 && o->increments <= max_increments, comm, PETSC_ERR_ARG_OUTOFRANGE,
             "-load_increments %" PetscInt_FMT ": use 1 to %" PetscInt_FMT " increments", o->increments,
             max_increments);
  PetscCheck(o->max_cutbacks >= 0 && o->max_cutbacks <= max_cutbacks, comm, PETSC_ERR_ARG_OUTOFRANGE,
             "-load_max_cutbacks %" PetscInt_FMT ": use 0 to %" PetscInt_FMT " (each halves the increment)",
             o->max_cutbacks, max_cutbacks);
  PetscCheck(o->max_it >= 0, comm, PETSC_ERR_ARG_OUTOFRANGE,
             "-load_max_it %" PetscInt_FMT ": use a positive limit, or 0 for -snes_max_it", o->max_it);
  PetscFunctionReturn(0);
}

namespace {

// U = U_n + dU_c + d with K(U_n) d = -dR/de, where dR/de is the change of the residual when the
// prescribed values and loads move from t to t_new with the free DOFs held (a one-sided
// difference with a small fraction e of the increment: K_fc dU_c plus the load change). The
// tangent is taken at t before the load time moves on, so the time only goes forward; the
// caller sets t_new on U. The tangent is a converged state's (TangentShiftConverged: it must not
// depend on the last Newton solve, which a restarted run has not made) with extra_shift (relative
// to E h, -load_tangent_predictor_shift) more on its diagonal.
PetscErrorCode TangentPredictor(Problem *P, SNES snes, Vec Un, double t, double t_new, double extra_shift, Vec U) {
  const double e = 1e-6;
  Vec R0, R1, d;
  KSP ksp;
  KSPConvergedReason kr;
  PetscFunctionBeginUser;
  PetscCall(VecDuplicate(Un, &R0));
  PetscCall(VecDuplicate(Un, &R1));
  PetscCall(VecDuplicate(Un, &d));
  PetscCall(VecCopy(Un, U));
  PetscCall(ProblemSetLoadTime(P, t, U));
  PetscCall(FormResidual(nullptr, U, R0, P));
  PetscCall(FormJacobian(snes, U, P->J, P->J, P));
  const double shift = TangentShiftConverged(P) + extra_shift * P->AxialStiffness();
  if (shift > 0) PetscCall(MatShift(P->J, shift));
  PetscCall(ProblemSetLoadTime(P, t + e * (t_new - t), U));
  PetscCall(FormResidual(nullptr, U, R1, P));
  PetscCall(VecAXPY(R1, -1.0, R0));
  PetscCall(VecScale(R1, 1.0 / e));
  {
    PetscScalar *r;
    PetscCall(VecGetArray(R1, &r));
    for (PetscInt dof : P->con_owned_dof) r[dof] = 0.0;  // the constrained part is dU_c itself
    PetscCall(VecRestoreArray(R1, &r));
  }
  PetscCall(SNESGetKSP(snes, &ksp));
  PetscCall(KSPSetOperators(ksp, P->J, P->J));
  // A singular tangent (a flat film without prestress) fails the factorization: no solve with
  // it (MUMPS would stop the run in its solve phase), and the factorization starts again from a
  // new analysis in Newton's first solve (see NewtonSolve); the plain predictor is kept.
  // The set-up's failure is this rank's (a block solver may fail on one rank only): all ranks
  // take the same branch, since the solve is collective.
  PC pc;
  PCFailedReason failed_here;
  int failed = 0;
  PetscCall(KSPSetUp(ksp));
  PetscCall(KSPGetPC(ksp, &pc));
  PetscCall(PCGetFailedReasonRank(pc, &failed_here));
  failed = failed_here != PC_NOERROR;
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &failed, 1, MPI_INT, MPI_MAX, P->comm));
  if (!failed) {
    PetscCall(KSPSolve(ksp, R1, d));
    PetscCall(KSPGetConvergedReason(ksp, &kr));
  } else {
    PetscBool factor;
    PetscCall(PetscObjectTypeCompareAny((PetscObject)pc, &factor, PCLU, PCCHOLESKY, ""));
    if (factor) PetscCall(PCReset(pc));
    kr = KSP_DIVERGED_PC_FAILED;
  }
  PetscCall(VecCopy(Un, U));
  if (kr > 0) PetscCall(VecAXPY(U, -1.0, d));  // a failed solve leaves the plain predictor
  PetscCall(VecDestroy(&R0));
  PetscCall(VecDestroy(&R1));
  PetscCall(VecDestroy(&d));
  PetscFunctionReturn(0);
}




PetscErrorCode WriteCheckpoint(LoadStepper *ps) {
  const LoadStepper &s = *ps;
  StepperState st;
  PetscFunctionBeginUser;
  st.t = s.t, st.dt = s.dt, st.dt_last = s.dt_last, st.step = s.step, st.converged_states = s.converged_states;
  st.easy = s.easy, st.cutbacks = s.res->cutbacks, st.newton = s.res->newton_iterations;
  PetscCall(CheckpointWrite(s.P, s.ck.file, st, s.U_committed, s.U_previous, OutputRunId(s.out)));
  ps->checkpoint_step = s.step;
  PetscCall(PetscTime(&ps->checkpoint_time));
  PetscFunctionReturn(0);
}

PetscErrorCode RestartFromCheckpoint(LoadStepper *s) {
  StepperState st;
  PetscFunctionBeginUser;
  PetscCall(CheckpointRead(s->P, s->ck.restart, &st, s->U_committed, s->U_previous, s->ck.branch));
  s->t = st.t, s->dt = st.dt, s->dt_last = st.dt_last;
  s->step = st.step, s->converged_states = st.converged_states, s->easy = st.easy;
  s->res->cutbacks = st.cutbacks, s->res->newton_iterations = st.newton;
  PetscCall(VecCopy(s->U_committed, s->P->U));
  // The load time of the checkpoint, so that what depends on it before the next increment (the
  // stress-free shape of a laid-on pattern, hence the internal forces of the increment's work)
  // is that of the uninterrupted run.
  PetscCall(ProblemSetLoadTime(s->P, s->t, s->P->U));
  for (auto &term : s->P->terms) PetscCall(term->Restarted(*s->P));  // as after the checkpoint's increment
  if (s->ck.branch)
    for (auto &term : s->P->terms) PetscCall(term->Branched(*s->P, s->t));
  PetscCall(PetscPrintf(s->P->comm, "%s: from %s at increment %" PetscInt_FMT ", load time %g\n",
                        s->ck.branch ? "restart (branch)" : "restart", s->ck.restart, s->step, s->t));
  PetscFunctionReturn(0);
}

// The start state (load time 0, or the checkpoint's), written as step 0 when it is one.
PetscErrorCode LoadStepperBegin(LoadStepper *s) {
  Problem *P = s->P;
  PetscFunctionBeginUser;
  PetscCall(PetscTime(&s->t0));
  s->checkpoint_time = s->t0;
  PetscCall(SNESGetTolerances(s->snes, &s->snes_atol, &s->snes_rtol, &s->snes_stol, &s->snes_max_it, &s->snes_max_f));
  PetscCall(VecDuplicate(P->U, &s->U_committed));
  PetscCall(VecDuplicate(P->U, &s->U_previous));
  PetscCall(ProblemSetLoadTime(P, 0.0, P->U));
  PetscCall(VecCopy(P->U, s->U_committed));
  PetscCall(VecCopy(P->U, s->U_previous));
  PetscCall(SNESGetFunction(s->snes, &s->F, nullptr, nullptr));
  // Reactions of the initial state, then the initial state itself as step 0. A scene's initial
  // guess is not an equilibrium state: only a true start state is step 0.
  PetscCall(ProblemUpdateReactions(P, P->U));
  if (!P->has_initial_guess && !s->ck.restart[0]) PetscCall(OutputWriteStep(s->out, P, P->U, 0, 0.0));
  if (s->ck.restart[0]) PetscCall(RestartFromCheckpoint(s));
  // The work of an increment is the trapezoid of the internal forces along its displacement (a
  // restart recomputes them bit for bit from the checkpoint's U and history).
  PetscCall(VecDuplicate(P->U, &s->Fint));
  PetscCall(VecDuplicate(P->U, &s->Fint_committed));
  PetscCall(VecDuplicate(P->U, &s->dU));
  PetscCall(FormInternalForce(P, s->U_committed, s->Fint_committed));
  s->res->completed = PETSC_FALSE;
  PetscFunctionReturn(0);
}

// Step-size control, forward: the next increment is dt long but ends no later than its stage.
Increment NextIncrement(const LoadStepper &s) {
  Increment inc;
  const double stage_end = std::floor(s.t + kTimeEps) + 1.0;
  inc.t = s.t;
  inc.dt_try = std::min(s.dt, stage_end - s.t);
  inc.t_new = (stage_end - (s.t + inc.dt_try) < kTimeEps) ? stage_end : s.t + inc.dt_try;
  return inc;
}

// Where Newton starts: the committed state, extrapolated along the last increment or moved by
// the tangent predictor.
PetscErrorCode PredictIncrement(LoadStepper *s, const Increment &inc) {
  Problem *P = s->P;
  const LoadStepperOptions &o = s->o;
  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(LogEvents().predictor, 0, 0, 0, 0));
  PetscCall(VecCopy(s->U_committed, P->U));
  // Extrapolate only within a stage: at a stage end the load path turns (loading -> unloading).
  // (increments never cross a stage end, so away from one the last increment is in this stage)
  const bool same_stage = std::fabs(s->t - std::round(s->t)) > kTimeEps;
  // Within a stage the extrapolation carries the path's curvature; where there is none to
  // extrapolate (first increment, a new stage) the tangent predictor takes the jump.
  if (o.extrapolate && s->dt_last > 0.0 && s->converged_states >= 2 && same_stage) {
    const double ratio = (inc.t_new - inc.t) / s->dt_last;
    PetscCall(VecAXPBYPCZ(P->U, ratio, -ratio, 1.0, s->U_committed, s->U_previous));
  } else if (o.tangent_predictor && s->converged_states >= 1)
    PetscCall(TangentPredictor(P, s->snes, s->U_committed, inc.t, inc.t_new, o.tangent_predictor_shift, P->U));
  PetscCall(PetscLogEventEnd(LogEvents().predictor, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

// One Newton solve from P->U; its iterations add to the increment's and the run's.
PetscErrorCode NewtonSolve(LoadStepper *s, Increment *inc) {
  PetscInt its;
  PetscFunctionBeginUser;
  PetscCall(SNESSolve(s->snes, nullptr, s->P->U));
  PetscCall(SNESGetConvergedReason(s->snes, &inc->reason));
  PetscCall(SNESGetIterationNumber(s->snes, &its));
  PetscCall(SNESGetFunctionNorm(s->snes, &inc->fnorm));
  inc->its += its;
  s->res->newton_iterations += its;
  if (inc->reason == SNES_DIVERGED_LINEAR_SOLVE) {
    // A factorization that failed (a singular tangent at a wild iterate) leaves PETSc 3.18's MUMPS
    // refusing every later numeric factorization of the same pattern ("called after analysis
    // phase fails", then INFOG(1) = -3 in the solve): the retry starts from a new analysis.
    // (Factorizations only: an AMG hierarchy built on the shifted matrix is not to be reset.)
    KSP ksp;
    PC pc;
    PetscBool factor;
    PetscCall(SNESGetKSP(s->snes, &ksp));
    PetscCall(KSPGetPC(ksp, &pc));
    PetscCall(PetscObjectTypeCompareAny((PetscObject)pc, &factor, PCLU, PCCHOLESKY, ""));
    if (factor) PetscCall(PCReset(pc));
  }
  PetscFunctionReturn(0);
}

// The increment solved with the viscous stabilization (stabilization.cpp) anchored at the
// committed state: from the committed state again after a failed plain solve (restart), else
// from the prediction. Proximal passes move the anchor to the answer and solve again until the
// stabilizing force is at most -load_stabilize_rtol of the reactions and loads.
PetscErrorCode StabilizedSolve(LoadStepper *s, Increment *inc, bool restart) {
  Problem *P = s->P;
  const LoadStepperOptions &o = s->o;
  PetscFunctionBeginUser;
  if (restart) {
    PetscCall(VecCopy(s->U_committed, P->U));
    PetscCall(ProblemSetLoadTime(P, inc->t_new, P->U));
  }
  inc->stabilized = true;
  PetscCall(StabilizationBegin(P, o.stabilize, s->U_committed));
  PetscCall(NewtonSolve(s, inc));
  for (PetscInt pass = 0; inc->Converged() && o.stabilize_rtol > 0 && pass < o.stabilize_passes; ++pass) {
    PetscReal size;
    PetscCall(StabilizationForceNorm(P, P->U, &size));
    if (size <= o.stabilize_rtol * P->diagnostics.force_scale) break;
    PetscCall(StabilizationMoveAnchor(P, P->U));
    PetscCall(NewtonSolve(s, inc));
  }
  // The force at the answer, against what the film takes from outside (load_stepper_equilibrium.cpp
  // decides whether the answer is an equilibrium).
  if (inc->Converged()) {
    PetscCall(FormInternalForce(P, P->U, s->Fint));
    PetscCall(StabilizationMeasure(P, P->U, s->Fint, &inc->stab));
  }
  StabilizationEnd(P);
  PetscFunctionReturn(0);
}

// Once per run: the first increment whose committed plastic strain passes the limit.
PetscErrorCode WarnPlasticStrain(LoadStepper *s) {
  Problem *P = s->P;
  const LoadStepperOptions &o = s->o;
  double ep, x[3];
  PetscInt element;
  PetscFunctionBeginUser;
  if (s->strain_warned || o.plastic_strain_limit <= 0 || !P->HasPlasticStrain()) PetscFunctionReturn(0);
  PetscCall(LargestPlasticStrain(P, &ep, &element, x));
  if (ep <= o.plastic_strain_limit) PetscFunctionReturn(0);
  s->strain_warned = true;
  PetscCall(PetscPrintf(P->comm,
                        "etfe: WARNING increment %" PetscInt_FMT " (load time %.5f): element %" PetscInt_FMT
                        " at (%.0f, %.0f, %.0f) mm has an equivalent plastic strain of %.3f, beyond "
                        "-load_plastic_strain_limit %g: the small-strain yield law (additive split of the "
                        "Green-Lagrange strain) no longer describes the film there. It is drawn far past its yield "
                        "stress: look for a support that holds the film next to a drawn edge, or smaller drawing "
                        "values\n",
                        s->step, s->t, element, x[0], x[1], x[2], ep, (double)o.plastic_strain_limit));
  PetscFunctionReturn(0);
}

// An attempt at the increment: predictor, the prescribed values of t_new, and the Newton solve.
// It starts from the committed state and commits nothing, so it can be made again.
PetscErrorCode AttemptIncrement(LoadStepper *s, Increment *inc) {
  Problem *P = s->P;
  const LoadStepperOptions &o = s->o;
  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(LogEvents().increment, 0, 0, 0, 0));
  PetscCall(PetscTime(&inc->start));
  PetscCall(PredictIncrement(s, *inc));
  const double seconds = P->clock.Seconds(inc->t_new) - P->clock.Seconds(inc->t);
  for (Material *law : P->Materials()) law->SetIncrementSeconds(seconds);
  PetscCall(ProblemSetLoadTime(P, inc->t_new, P->U));
  inc->max_it = (s->step > 0 && o.max_it > 0) ? std::min(o.max_it, s->snes_max_it) : s->snes_max_it;
  PetscCall(SNESSetTolerances(s->snes, s->snes_atol, s->snes_rtol, s->snes_stol, inc->max_it, s->snes_max_f));
  inc->its = 0;
  const bool always = o.stabilize_when == 2;
  PetscBool krylov_failed = PETSC_FALSE;
  if (!always) PetscCall(NewtonSolve(s, inc));
  if (!always && !inc->Converged()) PetscCall(KrylovSolveFailed(s->snes, &krylov_failed));
  // Neither a failed Krylov solve (cut back) nor an interrupted one (the run stops) is stabilized.
  if (always || (!inc->Converged() && o.stabilize_when == 1 && !krylov_failed && !InterruptGaveUp()))
    PetscCall(StabilizedSolve(s, inc, !always));
  PetscCall(PetscLogEventEnd(LogEvents().increment, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

// The largest number of repeats a term asks for (PhysicsTerm::RepeatLimit; 0: none).
PetscInt RepeatLimit(const Problem &P) {
  PetscInt limit = 0;
  for (const auto &term : P.terms) limit = std::max(limit, term->RepeatLimit());
  return limit;
}

// A term whose commit revises what the solve held fixed (the lagged law with
// -contact_lagged_repeat): a converged increment is solved again, from its answer, while the
// states its commit would set differ from those it was solved with (PhysicsTerm::Revise), at
// most that many times. A repeat that fails to converge leaves the last converged solve and its
// states, which the commit then treats as the thesis's law does: a repeat never cuts an
// increment back.
PetscErrorCode RepeatLaggedIncrement(LoadStepper *s, Increment *inc) {
  Problem *P = s->P;
  PetscInt changed = 0, r = 0;
  PetscFunctionBeginUser;
  const PetscInt limit = RepeatLimit(*P);
  if (limit <= 0) PetscFunctionReturn(0);
  if (!s->U_solved) PetscCall(VecDuplicate(P->U, &s->U_solved));
  for (auto &term : P->terms)
    if (term->RepeatLimit() > 0) PetscCall(term->BeginRepeats(*P));
  for (; r < limit; ++r) {
    changed = 0;
    for (auto &term : P->terms) {
      PetscInt mine = 0;
      if (term->RepeatLimit() > r) PetscCall(term->Revise(*P, &mine));
      changed += mine;
    }
    if (!changed) break;
    ++s->lagged_repeats;
    PetscCall(VecCopy(P->U, s->U_solved));
    const SNESConvergedReason solved = inc->reason;
    PetscCall(NewtonSolve(s, inc));
    if (!inc->Converged()) {
      PetscCall(VecCopy(s->U_solved, P->U));
      for (auto &term : P->terms)
        if (term->RepeatLimit() > 0) PetscCall(term->UndoRevise(*P));
      inc->reason = solved;
      break;
    }
  }
  if (changed) ++s->lagged_unsettled;  // the limit reached, or a repeat failed
  PetscFunctionReturn(0);
}

// The work done on the film over the converged increment (trapezoid of the internal forces at its
// two ends, the end's with the just committed history) and the tangent shift's work.
PetscErrorCode AccountIncrementWork(LoadStepper *s) {
  Problem *P = s->P;
  SolveDiagnostics &d = P->diagnostics;
  PetscScalar w;
  PetscFunctionBeginUser;
  PetscCall(FormInternalForce(P, P->U, s->Fint));
  PetscCall(VecAXPY(s->Fint_committed, 1.0, s->Fint));
  PetscCall(VecWAXPY(s->dU, -1.0, s->U_committed, P->U));
  PetscCall(VecDot(s->Fint_committed, s->dU, &w));
  d.increment_work = 0.5 * PetscRealPart(w);
  d.increment_shift_work = d.shift_work;
  s->work_total += d.increment_work;
  s->work_magnitude += std::fabs(d.increment_work);
  s->shift_work_total += d.shift_work;
  PetscCall(VecCopy(s->Fint, s->Fint_committed));
  PetscFunctionReturn(0);
}

// Commits a converged attempt: material history (committed here only), the work, U and the load
// time as the new committed state, and the physics terms' states (contact, chambers, layer
// pairs).
PetscErrorCode CommitIncrement(LoadStepper *s, const Increment &inc) {
  Problem *P = s->P;
  PetscFunctionBeginUser;
  PetscCall(CommitHistory(P, P->U));
  // From here on the committed state's own stress (every law: a group's own too).
  for (Material *law : P->Materials()) law->SetIncrementSeconds(0.0);
  PetscCall(AccountIncrementWork(s));
  PetscCall(VecCopy(s->U_committed, s->U_previous));
  PetscCall(VecCopy(P->U, s->U_committed));
  s->dt_last = inc.t_new - inc.t;
  s->t = inc.t_new;
  for (auto &term : P->terms) PetscCall(term->Commit(*P, s->t));
  ++s->converged_states;
  ++s->step;
  AccountStabilizedIncrement(s, inc);
  PetscCall(WarnPlasticStrain(s));
  PetscFunctionReturn(0);
}

// Step-size control after a converged increment: a cut increment doubles again (up to the
// nominal one) after -load_grow_after easy increments in a row.
void GrowIncrement(LoadStepper *s, const Increment &inc) {
  if (inc.its <= s->o.easy_iterations && s->dt < s->dt_nominal && ++s->easy >= s->o.grow_after) {
    s->dt = std::min(2.0 * s->dt, s->dt_nominal);
    s->easy = 0;
  }
}

// Step-size control after a failed attempt: the increment halves. True (the cut-backs are spent)
// once it has halved more than -load_max_cutbacks times below the nominal one.
bool CutBack(LoadStepper *s, const Increment &inc) {
  ++s->res->cutbacks;
  s->easy = 0;
  s->dt = 0.5 * inc.dt_try;
  return s->dt < s->dt_nominal / std::pow(2.0, (double)s->o.max_cutbacks) * (1 - 1e-9);
}


// Output and checkpoint timing after a converged increment: results every -output_every
// increments, at the end and where -load_stop_after stops the run; checkpoints every
// -checkpoint_every and at such a stop. *stop: the run ends here cleanly.
PetscErrorCode WriteIncrementResults(LoadStepper *s, bool *stop) {
  PetscFunctionBeginUser;
  const bool last = s->Finished();
  const bool stop_here = s->o.stop_after >= 0 && s->step >= s->o.stop_after;
  if (s->out && (last || stop_here || s->step % OutputEvery(s->out) == 0))
    PetscCall(OutputWriteStep(s->out, s->P, s->P->U, s->step, s->t));
  if ((s->ck.every > 0 && s->step % s->ck.every == 0) || (stop_here && !last)) PetscCall(WriteCheckpoint(s));
  *stop = stop_here && !last;
  PetscFunctionReturn(0);
}

// The last converged state is always in the results; the result and the work summary.
PetscErrorCode LoadStepperEnd(LoadStepper *s) {
  Problem *P = s->P;
  LoadStepperResult *res = s->res;
  PetscLogDouble t1;
  PetscFunctionBeginUser;
  PetscCall(VecCopy(s->U_committed, P->U));
  PetscCall(ProblemSetLoadTime(P, s->t, P->U));
  PetscCall(ProblemUpdateReactions(P, P->U));
  // (a signal's stop leaves it to the checkpoint: the continued results then list the same steps)
  if (OutputLastStep(s->out) != s->step && !res->interrupted) PetscCall(OutputWriteStep(s->out, P, P->U, s->step, s->t));
  PetscCall(StabilizationSummary(s));  // may find the run not in equilibrium
  res->completed = res->failure.empty() ? PETSC_TRUE : PETSC_FALSE;
  // The base state of branches (-checkpoint_final): only a history that ran to its end.
  if (s->ck.final && res->completed && !res->stopped && s->Finished() && s->checkpoint_step != s->step)
    PetscCall(WriteCheckpoint(s));
  res->steps = s->step;
  res->time = s->t;
  PetscCall(PetscTime(&t1));
  res->wall = t1 - s->t0;
  if (s->o.monitor > 0 && P->TangentShiftAbsolute() > 0)
    PetscCall(PetscPrintf(P->comm,
                          "etfe: work done on the film %.6e N mm; the tangent shift as a pseudo-transient term would "
                          "dissipate %.3e N mm (%.2e of it, sum over Newton iterations of shift |dx|^2)%s\n",
                          s->work_total, s->shift_work_total,
                          s->work_total != 0 ? s->shift_work_total / std::fabs(s->work_total) : 0.0,
                          s->ck.restart[0] ? " since the restart" : ""));
  if (RepeatLimit(*P) > 0)
    PetscCall(PetscPrintf(P->comm,
                          "etfe: lagged law: %" PetscInt_FMT " repeated solves with revised statuses "
                          "(-contact_lagged_repeat %" PetscInt_FMT "); %" PetscInt_FMT " increments committed at that "
                          "limit or after a repeat that failed (statuses possibly not settled)\n",
                          s->lagged_repeats, RepeatLimit(*P), s->lagged_unsettled));
  PetscCall(SNESSetTolerances(s->snes, s->snes_atol, s->snes_rtol, s->snes_stol, s->snes_max_it, s->snes_max_f));
  PetscCall(VecDestroy(&s->Fint));
  PetscCall(VecDestroy(&s->Fint_committed));
  PetscCall(VecDestroy(&s->dU));
  PetscCall(VecDestroy(&s->U_committed));
  PetscCall(VecDestroy(&s->U_previous));
  PetscCall(VecDestroy(&s->U_solved));
  PetscFunctionReturn(0);
}

} // namespace

PetscErrorCode LoadStepperRun(Problem *P, SNES snes, OutputFile *out, const LoadStepperOptions &o,
                              const CheckpointOptions &ck, LoadStepperResult *res) {
  LoadStepper s(P, snes, out, o, ck, res);
  PetscFunctionBeginUser;
  PetscCall(CheckSupportsHoldRigidMotions(P, P->U, o.check_supports));
  PetscCall(LoadStepperBegin(&s));
  while (!s.Finished()) {
    Increment inc = NextIncrement(s);
    PetscCall(AttemptIncrement(&s, &inc));
    bool stop = false, checkpoint = false;
    PetscCall(StopWithinIncrement(&s, inc, &stop));
    if (stop) {  // the last converged state is the committed one
      if (s.checkpoint_step != s.step) PetscCall(WriteCheckpoint(&s));
      break;
    }
    CheckStabilizedIncrement(s, &inc);
    if (inc.unbalanced) {
      // The stabilization carries the load: cut back like a failed solve (in a smaller increment
      // a slack region's stabilizing force shrinks, a carried load's does not); once the
      // cut-backs are spent the run stops at the committed state, "not in equilibrium".
      PetscCall(VecCopy(s.U_committed, P->U));
      const bool exhausted = CutBack(&s, inc);
      PetscCall(ReportUnbalancedIncrement(&s, inc, exhausted));
      if (exhausted) break;
      continue;
    }
    if (!inc.Converged()) {
      // The committed state back (history and contact were never touched), the increment halved.
      IncrementFailure failure;
      PetscCall(DiagnoseFailure(s, inc, &failure));
      PetscCall(VecCopy(s.U_committed, P->U));
      const bool exhausted = CutBack(&s, inc);
      PetscCall(ReportFailedIncrement(&s, inc, failure, exhausted));
      if (exhausted) break;
      continue;
    }
    PetscCall(RepeatLaggedIncrement(&s, &inc));
    PetscCall(CommitIncrement(&s, inc));
    GrowIncrement(&s, inc);
    PetscCall(ReportIncrement(&s, inc));
    PetscCall(WriteIncrementResults(&s, &stop));
    if (stop) res->stopped = PETSC_TRUE;
    PetscCall(SafePoint(&s, &checkpoint, &stop));
    if (checkpoint) PetscCall(WriteCheckpoint(&s));
    if (stop) break;
  }
  PetscCall(LoadStepperEnd(&s));
  PetscFunctionReturn(0);
}

} // namespace etfe
