// The load stepper's reports: the progress line, the description of a failed increment, the
// cut-back line (see load_stepper.cpp for the loop).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>

#include "etfe/assembly/assembly.h"
#include "load_stepper_internal.h"

namespace etfe {
namespace load_stepping {

namespace {

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

std::string Clock(double seconds) {
  const long s = (long)std::llround(std::max(0.0, seconds));
  char buf[32];
  std::snprintf(buf, sizeof buf, "%ld:%02ld:%02ld", s / 3600, (s / 60) % 60, s % 60);
  return buf;
}

// One line per increment: where the load history is (step k/N, %, the stage's meaning), how the
// increment went (Newton iterations, residual, contact states inline) and the time to the end.
PetscErrorCode PrintProgress(const LoadStepper &s, const Increment &inc, std::string terms, double now) {
  Problem *P = s.P;
  const SolveDiagnostics &d = P->diagnostics;
  const double t = s.t;
  PetscFunctionBeginUser;
  const int stage = std::min((int)std::floor(t - 1e-9), s.nstages - 1) + 1;
  const double done = t / s.t_end, elapsed_s = now - s.t0;
  // With a clock (-load_stage_duration, -load_hold_*): the physical time after the increment.
  char seconds[48] = "";
  if (P->clock.Active()) std::snprintf(seconds, sizeof seconds, "  time %.6g s", P->clock.Seconds(t));
  char cut[96] = "";
  if (s.res->cutbacks) std::snprintf(cut, sizeof cut, "  cut-backs %lld", (long long)s.res->cutbacks);
  // A stabilized increment says so, with its force's work against the increment's on the film and
  // its share of the forces in play (load_stepper_equilibrium.cpp).
  if (inc.stabilized)
    std::snprintf(cut + std::strlen(cut), sizeof cut - std::strlen(cut),
                  "  stabilized (%.1e of the work, %.1e of the forces)",
                  d.increment_work != 0 ? inc.stab.work / std::fabs(d.increment_work) : 0.0, ForceShare(inc.stab));
  // With a tangent shift: the increment's work on the film and what the shift would dissipate.
  if (P->TangentShiftAbsolute() > 0) {
    char buf[128];
    std::snprintf(buf, sizeof buf, "  work %.3e N mm shift %.1e (%.1e of it)", d.increment_work,
                  d.increment_shift_work,
                  d.increment_work != 0 ? d.increment_shift_work / std::fabs(d.increment_work) : 0.0);
    terms += buf;
  }
  PetscCall(PetscPrintf(P->comm,
                        "step %5" PetscInt_FMT "/%" PetscInt_FMT " %5.1f%%  t %.5f  stage %d/%d %s%s  newton %2" PetscInt_FMT
                        "  |R| %.2e%s%s  %.2f s  elapsed %s  ETA %s\n",
                        s.step, s.per_stage * s.nstages, 100.0 * done, t, stage, s.nstages,
                        StageDescription(P->scene, t).c_str(), seconds, inc.its, (double)inc.fnorm, terms.c_str(), cut,
                        now - inc.start, Clock(elapsed_s).c_str(),
                        done > 0 ? Clock(elapsed_s * (1.0 - done) / done).c_str() : "-"));
  PetscFunctionReturn(0);
}

} // namespace

// Collective: gathers what IncrementFailure needs after a failed attempt (F: its last residual).
PetscErrorCode DiagnoseFailure(const LoadStepper &s, const Increment &inc, IncrementFailure *f) {
  Problem *P = s.P;
  PetscFunctionBeginUser;
  f->reason = inc.reason;
  f->its = inc.its;
  PetscCall(WorstNode(P, s.F, &f->worst_node, &f->worst));
  f->bad_element = P->diagnostics.bad_element;
  f->bad_status = P->diagnostics.bad_status;
  for (const auto &term : P->terms) {
    const std::string hint = term->LineSearchHint(*P);
    if (!hint.empty()) f->hint += "; " + hint;
  }
  f->load_max_it = inc.max_it < s.snes_max_it;
  {
    KSP ksp;
    PC pc;
    KSPType kt;
    PCType pt;
    PetscCall(SNESGetKSP(s.snes, &ksp));
    PetscCall(KSPGetPC(ksp, &pc));
    PetscCall(KSPGetType(ksp, &kt));
    PetscCall(PCGetType(pc, &pt));
    f->linear = std::string(kt ? kt : "?") + " + " + (pt ? pt : "?");
    PetscCall(KSPGetConvergedReason(ksp, &f->ksp_reason));
    PetscCall(KSPGetIterationNumber(ksp, &f->ksp_its));
  }
  PetscFunctionReturn(0);
}

// A converged increment seen from outside: the progress line (every -load_monitor increments,
// the first, a stage's end, the last and after a cut-back), the scene's monitor, contact probes.
PetscErrorCode ReportIncrement(LoadStepper *s, const Increment &inc) {
  Problem *P = s->P;
  const LoadStepperOptions &o = s->o;
  PetscLogDouble now;
  PetscFunctionBeginUser;
  PetscCall(PetscTime(&now));
  const bool print = o.monitor > 0 && (s->step % o.monitor == 0 || s->step == 1 || s->AtStageEnd() || s->Finished() ||
                                       s->res->cutbacks != s->cutbacks_printed || inc.stabilized);
  // Every term hears of every commit (it may sum what happens between printed lines).
  std::string terms;
  for (auto &term : P->terms) terms += term->Progress(print);
  if (print) {
    s->cutbacks_printed = s->res->cutbacks;
    PetscCall(PrintProgress(*s, inc, terms, now));
  }
  if (P->observer.step_monitor) PetscCall(P->observer.step_monitor(P, P->observer.ctx, s->step, s->t, o.monitor));
  if (s->out)
    for (auto &term : P->terms) PetscCall(term->IncrementOutput(*P, OutputStem(s->out), s->step, s->t));
  PetscFunctionReturn(0);
}

// A failed attempt seen from outside: the cut-back line, and the run's failure once the
// cut-backs are spent.
PetscErrorCode ReportFailedIncrement(LoadStepper *s, const Increment &inc, const IncrementFailure &failure,
                                     bool exhausted) {
  const std::string why = failure.Message();
  PetscFunctionBeginUser;
  if (s->o.monitor)
    PetscCall(PetscPrintf(s->P->comm,
                          "step %5" PetscInt_FMT "  t %8.5f -> %.5f failed: %s; cutting back to dt %.3e\n",
                          s->step + 1, inc.t, inc.t_new, why.c_str(), s->dt));
  if (exhausted)
    s->res->failure = std::string("increment ") + std::to_string(s->step + 1) + " (load time " +
                      std::to_string(inc.t) + " -> " + std::to_string(inc.t_new) + ") did not converge after " +
                      std::to_string(s->o.max_cutbacks) + " cut-backs: " + why;
  PetscFunctionReturn(0);
}

} // namespace load_stepping
} // namespace etfe
