// The drawing planner (-analysis plan): searches a stretch case's drawing schedule with
// PETSc's TAO so that the drawn film meets the fabrication criteria (kernels/plan_criteria.h) with
// the least drawing, and writes the schedule as an options file ready to run.
//
// The unknowns are the final values of the options named by -plan_variables (by default the
// saddle's -saddle_draw_a,b,c,d); every earlier stage keeps the case's own proportion to the final
// value (Table 5.5's staging for the thesis cases), so a plan changes how far the frame is drawn,
// not how the drawing is split into stages. Each evaluation is a whole stretch run from the
// stress-free start: with proportional stages no stage is shared between two evaluations, so
// nothing can be restarted from a checkpoint.
#pragma once
#include <petscsys.h>

#include <map>
#include <string>
#include <vector>

#include "etfe/kernels/plan_criteria.h"
#include "etfe/description/scene.h"

namespace etfe {

struct PlanOptions {
  std::vector<std::string> variables;  // option names without '-', each a per-stage array
  double lower = 0.0, upper = 80.0;    // bounds of every final value (the frame's 80 mm, L721)
  PlanCriteria criteria;
  // The wrinkle test: the minor principal strain (the thesis's eps_min, default) or the minor
  // principal stress (the tension-field model's taut test: a film in tension does not wrinkle
  // however its Poisson contraction makes eps_min negative).
  bool wrinkle_stress = false;
  // The search scores against criteria tightened by this fraction (the band's half-width and the
  // equivalent-strain limit shrunk, the minor limit raised by margin x its unit): the least-drawing
  // term pulls the optimum onto the edge of what it scores, so the margin keeps the reported,
  // untightened criteria met after the rounding to -plan_round.
  double margin = 0.1;
  double draw_weight = 0.01;  // weight of the mean drawing (relative to upper) in the objective
  PetscInt max_runs = 40;     // stretch runs the search may spend
  double round = 0.1;         // resolution of the written values (a frame's screw) [mm]
  std::string output;         // the options file written
  // The case's per-stage arrays as its scene resolved them (SceneSpec::stage_options): the start
  // and the staging of the search.
  StageValues case_arrays;
};

// What one stretch run leaves for the planner: per element (gathered over the ranks, same order
// on every rank) the PK2 Mises stress, the minor principal GL strain (or PK2 stress when
// minor_is_stress, set by the planner before the run) and the equivalent plastic strain; whether
// the run completed; its Newton iterations and wall time.
struct PlanRunFields {
  bool completed = false;
  std::string failure;
  PetscInt newton = 0;
  double wall = 0.0;
  bool minor_is_stress = false;
  std::vector<double> mises, minor, eq;
};

struct Problem;
// The fields of the problem's current state, gathered (collective).
PetscErrorCode PlanGatherFields(Problem *problem, PlanRunFields *fields);

// Runs the case (collective) with the per-stage options in stages replacing the case's own
// (SceneSpec::stage_overrides: the options database is left as the user gave it) and fills the
// fields.
typedef PetscErrorCode (*PlanStretchRun)(MPI_Comm comm, void *ctx, const StageValues &stages, PlanRunFields *fields);

// results_stem: the case's results file without extension (the plan goes beside it).
PetscErrorCode PlanOptionsFromCommandLine(MPI_Comm comm, const std::string &results_stem, PlanOptions *o);
PetscErrorCode PlanRun(MPI_Comm comm, const PlanOptions &o, PlanStretchRun run, void *ctx);

} // namespace etfe
