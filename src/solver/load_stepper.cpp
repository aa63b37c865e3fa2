// Load stepping (see load_stepper.h). Committed state = (U, material history, load time); a
// failed Newton solve restores U from the committed copy (history is untouched until commit),
// so a cut-back repeats the increment from exactly the state it started from.
#include <cmath>
#include <algorithm>
#include <cstdio>
#include <string>

#include "etfe/assembly.h"
#include "etfe/contact.h"
#include "etfe/kernels/status.h"
#include "etfe/load_stepper.h"

namespace etfe {

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
                             "of the membrane forces, which dense meshes (~10^6 triangles) reach above the force test "
                             "(0: off; 10 is safe)",
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
  PetscOptionsEnd();
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

struct ForceTest {
  Problem *problem;
  PetscReal rtol;
  PetscReal roundoff;        // factor of the membrane round-off floor (0: off)
  PetscReal floor = -1.0;    // N, computed at the first test
};

// eps |x|max E h0 sqrt(n): a force from element edges x_a - x_b of coordinates of size |x|
// carries a strain round-off eps |x| / l_e, i.e. eps |x| E h0 per element (l_e cancels), summed
// in 2-norm over n elements. Measured floors of |R| (DD1511 increment 1): 1.1e-8 N at 10^5,
// 3.5e-8 at 10^6 triangles; this estimate gives 1.4e-8 and 4.4e-8.
PetscErrorCode MembraneRoundoffFloor(Problem *P, PetscReal *floor) {
  PetscReal xmax = 0.0;
  PetscFunctionBeginUser;
  for (double x : P->mesh.X) xmax = std::max(xmax, (PetscReal)std::fabs(x));
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &xmax, 1, MPIU_REAL, MPIU_MAX, P->comm));
  *floor = PETSC_MACHINE_EPSILON * xmax * P->AxialStiffness() * std::sqrt((double)P->mesh.num_elements_global);
  PetscFunctionReturn(0);
}

PetscErrorCode ConvergedForceBalance(SNES snes, PetscInt it, PetscReal xnorm, PetscReal ynorm,
                                     PetscReal fnorm, SNESConvergedReason *reason, void *ctx) {
  auto *t = (ForceTest *)ctx;
  PetscFunctionBeginUser;
  PetscCall(SNESConvergedDefault(snes, it, xnorm, ynorm, fnorm, reason, nullptr));
  if (*reason != SNES_CONVERGED_ITERATING || it == 0) PetscFunctionReturn(0);
  Problem *P = t->problem;
  PetscReal tol = t->rtol * P->force_scale;
  if (P->contact) {
    // A penalty force k w is computed from displacements of size |u|, so it carries a
    // round-off of about eps k |u| per pair: no Newton iterate can balance below that.
    Vec X;
    PetscReal umax;
    PetscCall(SNESGetSolution(snes, &X));
    PetscCall(VecNorm(X, NORM_INFINITY, &umax));
    const double k = std::max(P->contact->params.kn, P->contact->params.kt) * P->contact->k_scale_max;
    const double floor = PenaltyRoundoffFloor(k, umax, P->contact->num_global);
    // Accepting on a floor that is a visible part of the forces would report a wrong answer as
    // converged; ContactCreate refuses most such penalties up front, this catches the rest.
    PetscCheck(!(fnorm > tol && fnorm <= floor && floor > kPenaltyFloorMax * P->force_scale), P->comm,
               PETSC_ERR_ARG_OUTOFRANGE,
               "-contact_kn %g / -contact_kt %g: the round-off of the penalty forces (%.3g N) is %.2g of the forces "
               "balanced (%.3g N), above the force tolerance of the test (%g of them), so this answer cannot be "
               "checked; the largest usable penalty here is ~%.1e N/mm",
               P->contact->params.kn, P->contact->params.kt, floor, floor / P->force_scale, P->force_scale,
               kPenaltyFloorMax, k * kPenaltyFloorMax * P->force_scale / floor);
    tol = std::max(tol, floor);
  }
  if (t->roundoff > 0) {
    if (t->floor < 0) PetscCall(MembraneRoundoffFloor(P, &t->floor));
    tol = std::max(tol, t->roundoff * t->floor);
  }
  if (fnorm <= tol) *reason = SNES_CONVERGED_FNORM_ABS;
  PetscFunctionReturn(0);
}

PetscErrorCode DestroyForceTest(void *ctx) {
  delete (ForceTest *)ctx;
  return 0;
}

// The tangent shift read as a pseudo-transient (proximal-point) term: Newton's step from x_k
// solves (K + s_k I) dx = -R, the step of a system with a viscous force s_k (x - x_k) that is
// gone at convergence. The energy it would dissipate in a solve is sum_k s_k |x_{k+1} - x_k|^2,
// with s_k the diagonal of the tangent the step was solved with and x_{k+1} the iterate the line
// search accepted (all DOFs; the constrained ones do not move in a solve). The predictor's extra
// shift is not in it: the predictor only chooses where Newton starts.
struct ShiftWorkMonitor {
  Problem *problem;
  Vec x_prev = nullptr;
};

PetscErrorCode ShiftWorkMonitorCall(SNES snes, PetscInt it, PetscReal, void *ctx) {
  auto *m = (ShiftWorkMonitor *)ctx;
  Problem *P = m->problem;
  Vec X;
  PetscFunctionBeginUser;
  PetscCall(SNESGetSolution(snes, &X));
  if (!m->x_prev) PetscCall(VecDuplicate(X, &m->x_prev));
  if (it == 0) {
    P->shift_work = 0.0;
  } else if (P->shift_applied > 0) {
    PetscReal dx;
    PetscCall(VecAXPY(m->x_prev, -1.0, X));
    PetscCall(VecNorm(m->x_prev, NORM_2, &dx));
    P->shift_work += P->shift_applied * dx * dx;
  }
  PetscCall(VecCopy(X, m->x_prev));
  PetscFunctionReturn(0);
}

PetscErrorCode DestroyShiftWorkMonitor(void **ctx) {
  auto *m = (ShiftWorkMonitor *)*ctx;
  PetscFunctionBeginUser;
  PetscCall(VecDestroy(&m->x_prev));
  delete m;
  *ctx = nullptr;
  PetscFunctionReturn(0);
}

// U = U_n + dU_c + d with K(U_n) d = -dR/de, where dR/de is the change of the residual when the
// prescribed values and loads move from t to t_new with the free DOFs held (a one-sided
// difference with a small fraction e of the increment: K_fc dU_c plus the load change). The
// tangent is taken at t before the load time moves on, so the time only goes forward; the
// caller sets t_new on U.
PetscErrorCode TangentPredictor(Problem *P, SNES snes, Vec Un, double t, double t_new, double shift, Vec U) {
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
  if (shift > 0) PetscCall(MatShift(P->J, shift * P->AxialStiffness()));
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
  PetscCall(KSPSolve(ksp, R1, d));
  PetscCall(KSPGetConvergedReason(ksp, &kr));
  PetscCall(VecCopy(Un, U));
  if (kr > 0) PetscCall(VecAXPY(U, -1.0, d));  // a failed solve leaves the plain predictor
  PetscCall(VecDestroy(&R0));
  PetscCall(VecDestroy(&R1));
  PetscCall(VecDestroy(&d));
  PetscFunctionReturn(0);
}

// Scene node id of the largest residual entry, for failure messages.
PetscErrorCode WorstNode(Problem *P, Vec F, PetscInt *node, double *value) {
  Vec a;
  PetscInt loc;
  PetscReal v;
  PetscFunctionBeginUser;
  PetscCall(VecDuplicate(F, &a));
  PetscCall(VecCopy(F, a));
  PetscCall(VecAbs(a));
  PetscCall(VecMax(a, &loc, &v));
  PetscCall(VecDestroy(&a));
  PetscInt mine = -1, n = loc / 3 - P->mesh.owned_start;
  if (loc >= 0 && n >= 0 && n < P->mesh.num_owned) mine = P->mesh.natural_id[n];
  PetscCallMPI(MPI_Allreduce(&mine, node, 1, MPIU_INT, MPI_MAX, P->comm));
  *value = v;
  PetscFunctionReturn(0);
}

// What the current stage does, from the schedules that change in it: "draw_a 4.20 mm, draw_d
// 2.40 mm" or "pressure 1.50 kPa" (at most two named).
std::string StageDescription(const SceneSpec &scene, double t) {
  const int nstages = scene.NumStages();
  const int s = std::max(0, std::min((int)std::floor(t - 1e-9), nstages - 1));
  std::string d;
  int shown = 0, more = 0;
  for (const Schedule &sc : scene.schedules) {
    const double a = sc.At(s), b = sc.At(s + 1);
    if (std::fabs(b - a) <= 1e-14 * (std::fabs(a) + std::fabs(b))) continue;
    if (shown == 2) {
      ++more;
      continue;
    }
    char buf[96];
    std::snprintf(buf, sizeof buf, "%s%s %.3g%s%s", shown ? ", " : "", sc.name.c_str(), sc.At(t) * sc.display_scale,
                  sc.unit.empty() ? "" : " ", sc.unit.c_str());
    d += buf;
    ++shown;
  }
  if (more) d += ", +" + std::to_string(more);
  return d.empty() ? "held" : d;
}

// One Newton solve of the increment to t_new from the predicted P->U, stabilized as o asks: at
// once (always) or after a failed plain solve, from the committed state again (failure). Returns
// the last solve's reason and function norm and all its Newton iterations; stab_work and
// stab_force are the stabilizing force's work and largest nodal size (0 unless stabilized).
struct IncrementSolve {
  SNESConvergedReason reason = SNES_CONVERGED_ITERATING;
  PetscInt its = 0;
  PetscReal fnorm = 0.0;
  bool stabilized = false;
  double stab_work = 0.0, stab_force = 0.0;
  PetscInt passes = 0;
};

PetscErrorCode SolveIncrement(Problem *P, SNES snes, const LoadStepperOptions &o, Vec U_committed, double t_new,
                              IncrementSolve *r) {
  PetscInt its;
  PetscFunctionBeginUser;
  auto solve = [&]() -> PetscErrorCode {
    PetscFunctionBeginUser;
    PetscCall(SNESSolve(snes, nullptr, P->U));
    PetscCall(SNESGetConvergedReason(snes, &r->reason));
    PetscCall(SNESGetIterationNumber(snes, &its));
    PetscCall(SNESGetFunctionNorm(snes, &r->fnorm));
    r->its += its;
    PetscFunctionReturn(0);
  };
  const bool always = o.stabilize_when == 2;
  if (!always) PetscCall(solve());
  if (always || (r->reason <= 0 && o.stabilize_when == 1)) {
    if (!always) {
      PetscCall(VecCopy(U_committed, P->U));
      PetscCall(ProblemSetLoadTime(P, t_new, P->U));
    }
    r->stabilized = true;
    PetscCall(StabilizationBegin(P, o.stabilize, U_committed));
    PetscCall(solve());
    Vec dU;
    PetscCall(VecDuplicate(P->U, &dU));
    for (; r->reason > 0 && o.stabilize_rtol > 0 && r->passes < o.stabilize_passes; ++r->passes) {
      PetscReal size;
      PetscCall(VecWAXPY(dU, -1.0, P->stabilization.anchor, P->U));
      PetscCall(VecPointwiseMult(dU, dU, P->stabilization.diagonal));
      PetscCall(VecNorm(dU, NORM_2, &size));
      if (size <= o.stabilize_rtol * P->force_scale) break;
      PetscCall(StabilizationMoveAnchor(P, P->U));
      PetscCall(solve());
    }
    PetscCall(VecDestroy(&dU));
    if (r->reason > 0) PetscCall(StabilizationMeasure(P, P->U, &r->stab_work, &r->stab_force));
    StabilizationEnd(P);
  }
  PetscFunctionReturn(0);
}

// Once per run: the first increment whose committed plastic strain passes the limit.
PetscErrorCode WarnPlasticStrain(Problem *P, const LoadStepperOptions &o, PetscInt step, double t, bool *warned) {
  double ep, x[3];
  PetscInt element;
  PetscFunctionBeginUser;
  if (*warned || o.plastic_strain_limit <= 0 || !P->material->HasPlasticStrain()) PetscFunctionReturn(0);
  PetscCall(LargestPlasticStrain(P, &ep, &element, x));
  if (ep <= o.plastic_strain_limit) PetscFunctionReturn(0);
  *warned = true;
  PetscCall(PetscPrintf(P->comm,
                        "etfe: WARNING increment %" PetscInt_FMT " (load time %.5f): element %" PetscInt_FMT
                        " at (%.0f, %.0f, %.0f) mm has an equivalent plastic strain of %.3f, beyond "
                        "-load_plastic_strain_limit %g: the small-strain yield law (additive split of the "
                        "Green-Lagrange strain) no longer describes the film there. It is drawn far past its yield "
                        "stress: look for a support that holds the film next to a drawn edge, or smaller drawing "
                        "values\n",
                        step, t, element, x[0], x[1], x[2], ep, (double)o.plastic_strain_limit));
  PetscFunctionReturn(0);
}

std::string Clock(double seconds) {
  const long s = (long)std::llround(std::max(0.0, seconds));
  char buf[32];
  std::snprintf(buf, sizeof buf, "%ld:%02ld:%02ld", s / 3600, (s / 60) % 60, s % 60);
  return buf;
}

// One line per increment: where the load history is (step k/N, %, the stage's meaning), how the
// increment went (Newton iterations, residual, contact states inline) and the time to the end.
PetscErrorCode PrintProgress(Problem *P, PetscInt step, PetscInt nominal, double t, double t_end, PetscInt its,
                             PetscReal fnorm, const PetscInt counts[4], double increment_s, double elapsed_s,
                             PetscInt cutbacks) {
  PetscFunctionBeginUser;
  const int nstages = P->scene.NumStages();
  const int stage = std::min((int)std::floor(t - 1e-9), nstages - 1) + 1;
  const double done = t / t_end;
  std::string contact;
  if (P->contact) {
    char buf[128], lifted[64] = "";
    if (counts[3]) std::snprintf(lifted, sizeof lifted, " (%lld lift-offs since the last line)", (long long)counts[3]);
    std::snprintf(buf, sizeof buf, "  contact open %lld stick %lld slip %lld%s", (long long)counts[0],
                  (long long)counts[1], (long long)counts[2], lifted);
    contact = buf;
  }
  char cut[48] = "";
  if (cutbacks) std::snprintf(cut, sizeof cut, "  cut-backs %lld", (long long)cutbacks);
  // With a tangent shift: the increment's work on the film and what the shift would dissipate.
  if (P->tangent_shift > 0) {
    char buf[128];
    std::snprintf(buf, sizeof buf, "  work %.3e N mm shift %.1e (%.1e of it)", P->increment_work,
                  P->increment_shift_work,
                  P->increment_work != 0 ? P->increment_shift_work / std::fabs(P->increment_work) : 0.0);
    contact += buf;
  }
  PetscCall(PetscPrintf(P->comm,
                        "step %5" PetscInt_FMT "/%" PetscInt_FMT " %5.1f%%  t %.5f  stage %d/%d %s  newton %2" PetscInt_FMT
                        "  |R| %.2e%s%s  %.2f s  elapsed %s  ETA %s\n",
                        step, nominal, 100.0 * done, t, stage, nstages, StageDescription(P->scene, t).c_str(), its,
                        (double)fnorm, contact.c_str(), cut, increment_s, Clock(elapsed_s).c_str(),
                        done > 0 ? Clock(elapsed_s * (1.0 - done) / done).c_str() : "-"));
  PetscFunctionReturn(0);
}

} // namespace

PetscErrorCode LoadStepperSetConvergenceTest(Problem *P, SNES snes, const LoadStepperOptions &o) {
  PetscFunctionBeginUser;
  PetscCall(SNESSetConvergenceTest(snes, ConvergedForceBalance, new ForceTest{P, o.force_rtol, o.force_roundoff},
                                   DestroyForceTest));
  PetscCall(SNESMonitorSet(snes, ShiftWorkMonitorCall, new ShiftWorkMonitor{P}, DestroyShiftWorkMonitor));
  PetscFunctionReturn(0);
}

PetscErrorCode LoadStepperRun(Problem *P, SNES snes, OutputFile *out, const LoadStepperOptions &o,
                              const CheckpointOptions &ck, LoadStepperResult *res) {
  const int nstages = P->scene.NumStages();
  const double t_end = nstages;
  const PetscInt per_stage = (o.increments + nstages - 1) / nstages;
  const double dt_nominal = 1.0 / per_stage, eps = 1e-12;
  double t = 0.0, dt = dt_nominal, dt_last = 0.0;
  // Extrapolate only from converged states: a scene's initial guess is not one.
  PetscInt converged_states = P->has_initial_guess ? 0 : 1;
  PetscInt step = 0, easy = 0, cutbacks_printed = 0, lifted_since_print = 0;
  Vec U_committed, U_previous, F, Fint, Fint_committed, dU;
  bool strain_warned = false;
  double work_total = 0.0, shift_work_total = 0.0, stab_work_total = 0.0, stab_force_max = 0.0;
  PetscLogDouble t0, t_inc;
  PetscReal snes_atol, snes_rtol, snes_stol;
  PetscInt snes_max_it, snes_max_f;
  PetscFunctionBeginUser;
  PetscCall(PetscTime(&t0));
  PetscCall(SNESGetTolerances(snes, &snes_atol, &snes_rtol, &snes_stol, &snes_max_it, &snes_max_f));
  PetscCall(VecDuplicate(P->U, &U_committed));
  PetscCall(VecDuplicate(P->U, &U_previous));
  PetscCall(ProblemSetLoadTime(P, 0.0, P->U));
  PetscCall(VecCopy(P->U, U_committed));
  PetscCall(VecCopy(P->U, U_previous));
  PetscCall(SNESGetFunction(snes, &F, nullptr, nullptr));
  // Reactions of the initial state, then the initial state itself as step 0. A scene's initial
  // guess is not an equilibrium state: only a true start state is step 0.
  PetscCall(ProblemUpdateReactions(P, P->U));
  if (!P->has_initial_guess && !ck.restart[0]) PetscCall(OutputWriteStep(out, P, P->U, 0, 0.0));
  if (ck.restart[0]) {
    StepperState st;
    PetscCall(CheckpointRead(P, ck.restart, &st, U_committed, U_previous));
    t = st.t, dt = st.dt, dt_last = st.dt_last;
    step = st.step, converged_states = st.converged_states, easy = st.easy;
    res->cutbacks = st.cutbacks, res->newton_iterations = st.newton;
    PetscCall(VecCopy(U_committed, P->U));
    PetscCall(PetscPrintf(P->comm, "restart: from %s at increment %" PetscInt_FMT ", load time %g\n", ck.restart,
                          step, t));
  }
  // The film's internal forces at the committed state (committed history): the work of an
  // increment is the trapezoid of them along its displacement (a restart recomputes them bit for
  // bit from the checkpoint's U and history).
  PetscCall(VecDuplicate(P->U, &Fint));
  PetscCall(VecDuplicate(P->U, &Fint_committed));
  PetscCall(VecDuplicate(P->U, &dU));
  PetscCall(FormInternalForce(P, U_committed, Fint_committed));
  auto checkpoint = [&]() -> PetscErrorCode {
    StepperState st;
    st.t = t, st.dt = dt, st.dt_last = dt_last, st.step = step, st.converged_states = converged_states;
    st.easy = easy, st.cutbacks = res->cutbacks, st.newton = res->newton_iterations;
    return CheckpointWrite(P, ck.file, st, U_committed, U_previous, OutputRunId(out));
  };
  res->completed = PETSC_FALSE;
  while (t < t_end - eps) {
    const double stage_end = std::floor(t + eps) + 1.0;
    const double dt_try = std::min(dt, stage_end - t);
    const double t_new = (stage_end - (t + dt_try) < eps) ? stage_end : t + dt_try;
    PetscCall(PetscTime(&t_inc));
    // Predictor: extrapolate the last converged increment, then impose the new prescribed values.
    PetscCall(VecCopy(U_committed, P->U));
    // ... and only within a stage: at a stage end the load path turns (loading -> unloading).
    // (increments never cross a stage end, so away from one the last increment is in this stage)
    const bool same_stage = std::fabs(t - std::round(t)) > eps;
    // Within a stage the extrapolation carries the path's curvature; where there is none to
    // extrapolate (first increment, a new stage) the tangent predictor takes the jump.
    if (o.extrapolate && dt_last > 0.0 && converged_states >= 2 && same_stage)
      PetscCall(VecAXPBYPCZ(P->U, (t_new - t) / dt_last, -(t_new - t) / dt_last, 1.0,
                            U_committed, U_previous));
    else if (o.tangent_predictor && converged_states >= 1)
      PetscCall(TangentPredictor(P, snes, U_committed, t, t_new, o.tangent_predictor_shift, P->U));
    PetscCall(ProblemSetLoadTime(P, t_new, P->U));
    const PetscInt max_it = (step > 0 && o.max_it > 0) ? std::min(o.max_it, snes_max_it) : snes_max_it;
    PetscCall(SNESSetTolerances(snes, snes_atol, snes_rtol, snes_stol, max_it, snes_max_f));
    IncrementSolve solved;
    PetscCall(SolveIncrement(P, snes, o, U_committed, t_new, &solved));
    const SNESConvergedReason reason = solved.reason;
    const PetscInt its = solved.its;
    const PetscReal fnorm = solved.fnorm;
    res->newton_iterations += its;
    if (reason > 0 && solved.stabilized) {
      ++res->stabilized;
      stab_work_total += solved.stab_work;
      stab_force_max = std::max(stab_force_max, solved.stab_force);
    }
    if (reason > 0) {
      PetscCall(CommitHistory(P, P->U));
      PetscCall(WarnPlasticStrain(P, o, step + 1, t_new, &strain_warned));
      {
        PetscScalar w;
        PetscCall(FormInternalForce(P, P->U, Fint));
        PetscCall(VecAXPY(Fint_committed, 1.0, Fint));
        PetscCall(VecWAXPY(dU, -1.0, U_committed, P->U));
        PetscCall(VecDot(Fint_committed, dU, &w));
        P->increment_work = 0.5 * PetscRealPart(w);
        P->increment_shift_work = P->shift_work;
        work_total += P->increment_work;
        shift_work_total += P->shift_work;
        PetscCall(VecCopy(Fint, Fint_committed));
      }
      PetscInt contact_counts[4] = {0, 0, 0, 0};
      if (P->contact) PetscCall(ContactCommit(P, contact_counts));
      // Pairs that lift off between two printed lines are counted, not each printed.
      lifted_since_print += contact_counts[3];
      contact_counts[3] = lifted_since_print;
      PetscCall(VecCopy(U_committed, U_previous));
      PetscCall(VecCopy(P->U, U_committed));
      dt_last = t_new - t;
      t = t_new;
      ++converged_states;
      ++step;
      PetscLogDouble now;
      PetscCall(PetscTime(&now));
      const bool stage_end_reached = std::fabs(t - std::round(t)) < eps;
      if (o.monitor > 0 && (step % o.monitor == 0 || step == 1 || stage_end_reached || t >= t_end - eps ||
                            res->cutbacks != cutbacks_printed)) {
        cutbacks_printed = res->cutbacks;
        PetscCall(PrintProgress(P, step, per_stage * nstages, t, t_end, its, fnorm, contact_counts, now - t_inc,
                                now - t0, res->cutbacks));
        lifted_since_print = 0;
      }
      if (P->observer.step_monitor) PetscCall(P->observer.step_monitor(P, P->observer.ctx, step, t, o.monitor));
      if (P->contact && out) PetscCall(ContactWriteProbes(P, OutputStem(out), step, t));
      const bool last = t >= t_end - eps;
      const bool stop = o.stop_after >= 0 && step >= o.stop_after;
      if (out && (last || stop || step % OutputEvery(out) == 0))
        PetscCall(OutputWriteStep(out, P, P->U, step, t));
      if (its <= o.easy_iterations && dt < dt_nominal && ++easy >= o.grow_after) {
        dt = std::min(2.0 * dt, dt_nominal);
        easy = 0;
      }
      if ((ck.every > 0 && step % ck.every == 0) || (stop && !last)) PetscCall(checkpoint());
      if (stop && !last) {
        res->stopped = PETSC_TRUE;
        break;
      }
      continue;
    }
    // Divergence: restore the committed state and halve the increment.
    ++res->cutbacks;
    easy = 0;
    PetscInt node;
    double worst = 0.0;
    PetscCall(WorstNode(P, F, &node, &worst));
    char why[512];
    const bool stiff_penalty = P->contact && P->contact->params.kn > 1e5 * P->AxialStiffness();
    if (reason == SNES_DIVERGED_LINE_SEARCH && P->bad_status == KERNEL_OK)
      std::snprintf(why, sizeof why, "%s (no step along the Newton direction reduced the residual; "
                    "largest residual %.3e at node %lld%s)",
                    SNESConvergedReasons[reason], worst, (long long)node,
                    stiff_penalty ? "; the contact penalties are very stiff: try a smaller -contact_kn/-contact_kt" : "");
    else if (reason == SNES_DIVERGED_FUNCTION_DOMAIN || reason == SNES_DIVERGED_LINE_SEARCH)
      std::snprintf(why, sizeof why, "%s (last element problem: element %lld, %s; largest residual "
                    "%.3e at node %lld)",
                    SNESConvergedReasons[reason], (long long)P->bad_element,
                    KernelStatusName(P->bad_status), worst, (long long)node);
    else if (reason == SNES_DIVERGED_LINEAR_SOLVE)
      std::snprintf(why, sizeof why, "%s (the linear solver failed: a singular tangent, e.g. an "
                    "unsupported rigid motion, or MUMPS out of workspace with stiff penalties: "
                    "-mat_mumps_icntl_14 400, -ksp_error_if_not_converged shows its error; largest "
                    "residual %.3e at node %lld)",
                    SNESConvergedReasons[reason], worst, (long long)node);
    else
      std::snprintf(why, sizeof why, "%s after %lld Newton iterations (largest residual %.3e at "
                    "node %lld%s)",
                    SNESConvergedReasons[reason], (long long)its, worst, (long long)node,
                    reason == SNES_DIVERGED_MAX_IT && max_it < snes_max_it
                        ? "; the limit after the first increment is -load_max_it" : "");
    PetscCall(VecCopy(U_committed, P->U));
    dt = 0.5 * dt_try;
    if (o.monitor)
      PetscCall(PetscPrintf(P->comm, "step %5" PetscInt_FMT "  t %8.5f -> %.5f failed: %s; cutting back to dt %.3e\n",
                            step + 1, t, t_new, why, dt));
    if (dt < dt_nominal / std::pow(2.0, (double)o.max_cutbacks) * (1 - 1e-9)) {
      res->failure = std::string("increment ") + std::to_string(step + 1) + " (load time " +
                     std::to_string(t) + " -> " + std::to_string(t_new) +
                     ") did not converge after " + std::to_string(o.max_cutbacks) +
                     " cut-backs: " + why;
      break;
    }
  }
  // The last converged state is always in the results.
  PetscCall(VecCopy(U_committed, P->U));
  PetscCall(ProblemSetLoadTime(P, t, P->U));
  PetscCall(ProblemUpdateReactions(P, P->U));
  if (OutputLastStep(out) != step) PetscCall(OutputWriteStep(out, P, P->U, step, t));
  res->completed = res->failure.empty() ? PETSC_TRUE : PETSC_FALSE;
  res->steps = step;
  res->time = t;
  PetscLogDouble t1;
  PetscCall(PetscTime(&t1));
  res->wall = t1 - t0;
  if (o.monitor > 0 && P->tangent_shift > 0)
    PetscCall(PetscPrintf(P->comm,
                          "etfe: work done on the film %.6e N mm; the tangent shift as a pseudo-transient term would "
                          "dissipate %.3e N mm (%.2e of it, sum over Newton iterations of shift |dx|^2)%s\n",
                          work_total, shift_work_total, work_total != 0 ? shift_work_total / std::fabs(work_total) : 0.0,
                          ck.restart[0] ? " since the restart" : ""));
  if (res->stabilized) {
    PetscReal reaction_max;
    PetscCall(VecMaxNodalNorm(P->reaction, &reaction_max));
    PetscCall(PetscPrintf(P->comm,
                          "etfe: %" PetscInt_FMT " increments stabilized (-load_stabilize %g, -load_stabilize_when %s): "
                          "the stabilizing force did %.3e N mm of work (%.2e of the work done on the film), largest "
                          "nodal stabilizing force %.3e N (%.2e of the largest reaction)%s\n",
                          res->stabilized, (double)o.stabilize, kStabilizeWhen[o.stabilize_when], stab_work_total,
                          work_total != 0 ? stab_work_total / std::fabs(work_total) : 0.0, stab_force_max,
                          reaction_max > 0 ? stab_force_max / reaction_max : 0.0,
                          ck.restart[0] ? " since the restart" : ""));
  }
  PetscCall(SNESSetTolerances(snes, snes_atol, snes_rtol, snes_stol, snes_max_it, snes_max_f));
  PetscCall(VecDestroy(&Fint));
  PetscCall(VecDestroy(&Fint_committed));
  PetscCall(VecDestroy(&dU));
  PetscCall(VecDestroy(&U_committed));
  PetscCall(VecDestroy(&U_previous));
  PetscFunctionReturn(0);
}

} // namespace etfe
