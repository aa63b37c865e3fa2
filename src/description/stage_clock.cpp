// Physical time of a load history (see stage_clock.h).
#include "etfe/description/stage_clock.h"

#include <cmath>

namespace etfe {

double StageClock::Seconds(double t) const {
  if (!Active()) return 0.0;
  const int n = (int)duration.size();
  t = std::fmin(std::fmax(t, 0.0), (double)n);
  const int s = std::min((int)std::floor(t), n - 1);
  double base = 0.0;
  for (int k = 0; k < s; ++k) base += duration[k];
  const double x = t - s, D = duration[s];
  if (hold[s] && D > 0.0) return base + hold_first * std::expm1(x * std::log1p(D / hold_first));
  return base + D * x;
}

namespace {

// Every schedule gets a stage after stage `after` (1-based; 0: before the first) that keeps the
// value there.
void InsertHoldStage(SceneSpec *scene, int after) {
  for (Schedule &sc : scene->schedules) {
    const double v = after == 0 ? sc.initial : sc.values[(size_t)after - 1];
    sc.values.insert(sc.values.begin() + after, v);
  }
}

} // namespace

PetscErrorCode StageClockFromOptions(MPI_Comm comm, bool formfind, SceneSpec *scene, StageClock *clock) {
  const PetscInt max_stages = 256;
  PetscReal duration[256] = {0.0}, hold_duration[256] = {0.0};
  PetscInt hold_after[256] = {0};
  PetscInt nd = max_stages, nh = max_stages, nhd = max_stages;
  PetscBool set_d = PETSC_FALSE, set_h = PETSC_FALSE, set_hd = PETSC_FALSE;
  PetscFunctionBeginUser;
  PetscOptionsBegin(comm, nullptr, "Physical time of the load history", "LoadStepper");
  PetscCall(PetscOptionsRealArray("-load_stage_duration",
                                  "Seconds each stage of the scene's schedule lasts (one value per stage, or one for "
                                  "all); gives the load history a clock for time-dependent laws (none: no time passes)",
                                  "", duration, &nd, &set_d));
  PetscCall(PetscOptionsIntArray("-load_hold_after",
                                 "Insert a hold stage after each of these stages of the scene's schedule (1 = after "
                                 "the first; 0 = before it): the loads stay, time passes",
                                 "", hold_after, &nh, &set_h));
  PetscCall(PetscOptionsRealArray("-load_hold_duration", "Seconds of each hold of -load_hold_after", "", hold_duration,
                                  &nhd, &set_hd));
  PetscCall(PetscOptionsReal("-load_hold_first",
                             "Seconds at which a hold's log-spaced increments start (the clock within a hold is "
                             "first ((1 + duration/first)^x - 1) for its load time x in [0, 1])",
                             "", clock->hold_first, &clock->hold_first, nullptr));
  PetscOptionsEnd();
  if (!set_d) nd = 0;
  if (!set_h) nh = 0;
  if (!set_hd) nhd = 0;
  const PetscInt nstages = scene->NumStages();
  PetscCheck(!(formfind && (nh > 0 || nd > 0)), comm, PETSC_ERR_ARG_INCOMP,
             "-load_hold_after/-load_stage_duration: form finding (-analysis formfind) prescribes the stress and has "
             "no time; holds and stage durations are for load histories (-analysis stretch)");
  PetscCheck(nh == 0 || !scene->schedules.empty(), comm, PETSC_ERR_ARG_INCOMP,
             "-load_hold_after: scene %s has no load schedule to hold", scene->name.c_str());
  PetscCheck(nh == nhd, comm, PETSC_ERR_ARG_SIZ,
             "-load_hold_after has %" PetscInt_FMT " stages but -load_hold_duration %" PetscInt_FMT
             " durations; give one duration per hold",
             nh, nhd);
  PetscCheck(nd == 0 || nd == 1 || nd == nstages, comm, PETSC_ERR_ARG_SIZ,
             "-load_stage_duration has %" PetscInt_FMT " values for a schedule of %" PetscInt_FMT
             " stages: give one per stage or one for all",
             nd, nstages);
  PetscCheck(clock->hold_first > 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "-load_hold_first %g: use a time > 0 s",
             (double)clock->hold_first);
  for (PetscInt k = 0; k < nd; ++k)
    PetscCheck(duration[k] >= 0 && std::isfinite(duration[k]), comm, PETSC_ERR_ARG_OUTOFRANGE,
               "-load_stage_duration: stage %" PetscInt_FMT " lasts %g s; durations must be >= 0", k + 1,
               (double)duration[k]);
  for (PetscInt k = 0; k < nh; ++k) {
    PetscCheck(hold_after[k] >= 0 && hold_after[k] <= nstages && (k == 0 || hold_after[k] > hold_after[k - 1]), comm,
               PETSC_ERR_ARG_OUTOFRANGE,
               "-load_hold_after: %" PetscInt_FMT " is not a stage end of this schedule (0 .. %" PetscInt_FMT
               ", increasing)",
               hold_after[k], nstages);
    PetscCheck(hold_duration[k] > 0 && std::isfinite(hold_duration[k]), comm, PETSC_ERR_ARG_OUTOFRANGE,
               "-load_hold_duration: hold %" PetscInt_FMT " lasts %g s; a hold must last > 0 s", k + 1,
               (double)hold_duration[k]);
  }
  if (nd == 0 && nh == 0) PetscFunctionReturn(0);
  clock->duration.assign((size_t)nstages, nd == 0 ? 0.0 : duration[0]);
  for (PetscInt k = 0; k < nd; ++k) clock->duration[(size_t)k] = duration[k];
  clock->hold.assign((size_t)nstages, 0);
  // From the last hold back, so the earlier stage numbers stay valid.
  for (PetscInt k = nh - 1; k >= 0; --k) {
    InsertHoldStage(scene, (int)hold_after[k]);
    clock->duration.insert(clock->duration.begin() + hold_after[k], hold_duration[k]);
    clock->hold.insert(clock->hold.begin() + hold_after[k], 1);
  }
  PetscFunctionReturn(0);
}

} // namespace etfe
