// Physical time of a load history: each stage of the schedules lasts a number of seconds, and a
// hold stage (inserted into every schedule, so the boundary values stay where the previous stage
// left them) lets time pass at fixed loads. PETSc-free but for the options reader.
//
// Load time t runs over the stages (schedule.h); the clock maps it to seconds, linearly within a
// ramp stage and logarithmically within a hold (equal load-time increments are equal ratios of
// elapsed time, so the increments are short where relaxation is fast). The clock is a function of
// the load time alone: cut-backs, restarts and checkpoints keep it without state of their own.
#pragma once
#include <petscsys.h>

#include <vector>

#include "etfe/description/scene.h"

namespace etfe {

struct StageClock {
  std::vector<double> duration;  // seconds of each stage (empty: no physical time)
  std::vector<char> hold;        // per stage: a hold (log-spaced in time)
  double hold_first = 1.0;       // a hold's clock is first ((1 + D/first)^x - 1), x in [0, 1]

  bool Active() const { return !duration.empty(); }
  // Seconds since the start at load time t (0 when inactive).
  double Seconds(double t) const;
};

// -load_stage_duration (seconds per stage of the scene's schedules, or one value for all),
// -load_hold_after / -load_hold_duration (hold stages inserted after the given stages, into every
// schedule of the scene) and -load_hold_first. Refuses a hold in a form-finding run.
PetscErrorCode StageClockFromOptions(MPI_Comm comm, bool formfind, SceneSpec *scene, StageClock *clock);

} // namespace etfe
