// The drawing planner's driver (plan_driver.h).
#include "plan_driver.h"

#include <filesystem>

#include "case_setup.h"
#include "etfe/io/checkpoint.h"
#include "etfe/io/output.h"
#include "etfe/analyses/plan.h"
#include "etfe/scenes/scene_registry.h"
#include "options_check.h"
#include "run_report.h"

namespace etfe {

namespace {

// A stretch case built from the options database; c->P stays null when no scene is named.
PetscErrorCode StretchCaseCreate(MPI_Comm comm, Case *c, const StageValues &stages = {}) {
  SceneSpec scene;
  scene.stage_overrides = stages;
  SceneObserver observer;
  PetscFunctionBeginUser;
  PetscCall(SceneCreateFromOptions(comm, &scene, &observer));
  if (scene.name.empty()) PetscFunctionReturn(0);
  PetscCall(CreateCase(comm, false, std::move(scene), observer, c));
  PetscFunctionReturn(0);
}

// One stretch run of the case, its per-stage options replaced by the drawing planner's stages: no
// results file, no monitor, the per-element criteria fields gathered on every rank.
PetscErrorCode PlanStretchOnce(MPI_Comm comm, void *, const StageValues &stages, PlanRunFields *fields) {
  Case c;
  LoadStepperResult res;
  PetscFunctionBeginUser;
  PetscCall(StretchCaseCreate(comm, &c, stages));
  c.lso.monitor = 0;
  PetscCall(LoadStepperRun(c.P, c.snes, nullptr, c.lso, CheckpointOptions(), &res));
  fields->completed = res.completed && !res.stopped;
  fields->failure = res.stopped ? "stopped by -load_stop_after" : res.failure;
  fields->newton = res.newton_iterations;
  fields->wall = res.wall;
  if (fields->completed) PetscCall(PlanGatherFields(c.P, fields));
  PetscCall(CaseDestroy(&c));
  PetscFunctionReturn(0);
}

} // namespace

PetscErrorCode RunPlan(MPI_Comm comm, PetscBool help_only) {
  Case c;
  OutputOptions oo;
  PlanOptions po;
  PetscFunctionBeginUser;
  PetscCall(StretchCaseCreate(comm, &c));
  PetscCheck(c.P || help_only, comm, PETSC_ERR_USER_INPUT,
             "-analysis plan needs a stretch case: -options_file options/saddle/dd1511.opts "
             "-analysis plan");
  if (!c.P) PetscFunctionReturn(0);
  PetscCall(OutputOptionsFromCommandLine(comm, c.P->scene.name.c_str(), &oo));
  PetscCall(PlanOptionsFromCommandLine(
      comm, std::filesystem::path(oo.path).replace_extension("").string(), &po));
  po.case_arrays = c.P->scene.stage_options;
  if (!help_only) {
    PetscCall(CheckUnusedOptions(comm, PETSC_TRUE));
    PetscCall(PrintHeader(c.P, c.snes));
  }
  PetscCall(CaseDestroy(&c));
  if (help_only) PetscFunctionReturn(0);
  PetscCall(PlanRun(comm, po, PlanStretchOnce, nullptr));
  PetscCall(CheckUnusedOptions(comm, PETSC_FALSE));
  PetscFunctionReturn(0);
}

} // namespace etfe
