// The drawing planner (see plan.h): TAO searches the final drawing values; each evaluation is a
// whole stretch run, scored per element by the fabrication criteria (kernels/plan_criteria.h).
#include "etfe/analyses/plan.h"

#include <petsctao.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <numeric>
#include <sstream>

#include "etfe/assembly/assembly.h"
#include "etfe/kernels/status.h"
#include "etfe/assembly/problem.h"

namespace etfe {

namespace {

// One stretch run as the planner sees it.
struct Evaluation {
  std::vector<double> x;         // final values of the variables [mm]
  std::vector<double> residual;  // per element (mises, strain, eq) / sqrt(N), then the drawing term
  double objective = 0.0;        // |residual|^2
  bool completed = false;
  std::string failure;
  PetscInt newton = 0;
  double wall = 0.0;
  // The criteria in numbers: elements below/above the band, with emin below the limit, with the
  // equivalent strain at or above its limit, and the extremes.
  int below = 0, above = 0, wrinkled = 0, eq_over = 0, elements = 0;
  double mises_min = 0, mises_max = 0, minor_min = 0, eq_max = 0;
  bool Met() const { return completed && below + above + wrinkled + eq_over == 0; }
};

struct Planner {
  MPI_Comm comm;
  const PlanOptions *o;
  PlanStretchRun run;
  void *ctx;
  std::vector<std::vector<double>> shape;  // per variable: the case's stages / its final value
  std::vector<Evaluation> evals;
  PetscInt elements = -1;
  double wall = 0.0;
};

// One stage value as the written plan gives it (10 significant digits), so a stretch run of the
// search uses exactly the numbers a user re-running the written plan gets.
std::string StageText(double value) {
  std::ostringstream s;
  s.precision(10);
  s << value;
  return s.str();
}

// The variable's stages at final value x: the case's proportions, rounded as written.
std::vector<double> StageValuesAt(const std::vector<double> &shape, double final_value) {
  std::vector<double> v;
  for (double s : shape) v.push_back(std::strtod(StageText(s * final_value).c_str(), nullptr));
  return v;
}

std::string Stages(const std::vector<double> &shape, double final_value) {
  std::string s;
  for (double v : StageValuesAt(shape, final_value)) s += (s.empty() ? "" : ",") + StageText(v);
  return s;
}

std::string Values(const std::vector<double> &x) {
  std::ostringstream s;
  s.precision(4);
  s << std::fixed;
  for (size_t k = 0; k < x.size(); ++k) s << (k ? ", " : "") << x[k];
  return s.str();
}

void Score(const PlanOptions &o, const PlanRunFields &f, Evaluation *e) {
  const size_t n = f.mises.size();
  e->elements = (int)n;
  e->mises_min = n ? *std::min_element(f.mises.begin(), f.mises.end()) : 0;
  e->mises_max = n ? *std::max_element(f.mises.begin(), f.mises.end()) : 0;
  e->minor_min = n ? *std::min_element(f.minor.begin(), f.minor.end()) : 0;
  e->eq_max = n ? *std::max_element(f.eq.begin(), f.eq.end()) : 0;
  e->residual.assign(3 * n + 1, 0.0);
  PlanCriteria search = o.criteria;
  search.mises_band *= 1.0 - o.margin;
  search.max_eq_strain *= 1.0 - o.margin;
  search.minor_limit += o.margin * search.minor_unit;
  const double scale = 1.0 / std::sqrt((double)std::max<size_t>(1, n));
  for (size_t i = 0; i < n; ++i) {
    // Scored against the tightened criteria, counted against the real ones (the same kernel).
    double v[3], real[3];
    if (PlanElementViolations(search, f.mises[i], f.minor[i], f.eq[i], v) != KERNEL_OK) v[0] = v[1] = v[2] = 1e3;
    if (PlanElementViolations(o.criteria, f.mises[i], f.minor[i], f.eq[i], real) != KERNEL_OK)
      real[0] = real[1] = real[2] = 1.0;
    if (real[0] > 0) ++(f.mises[i] < o.criteria.mises_target ? e->below : e->above);
    e->wrinkled += real[1] > 0;
    e->eq_over += real[2] > 0;
    for (int k = 0; k < 3; ++k) e->residual[3 * i + k] = v[k] * scale;
  }
  double mean = 0.0;
  for (double xi : e->x) mean += xi / (o.upper * e->x.size());
  e->residual.back() = std::sqrt(o.draw_weight) * mean;
}

PetscErrorCode PrintEvaluation(const Planner &p, const char *what, const Evaluation &e) {
  PetscFunctionBeginUser;
  if (!e.completed) {
    PetscCall(PetscPrintf(p.comm, "plan: %s %s: the stretch run failed (%s)\n", what, Values(e.x).c_str(),
                          e.failure.c_str()));
    PetscFunctionReturn(0);
  }
  PetscCall(PetscPrintf(p.comm,
                        "plan: %s %s: objective %.6e; Mises %.4f..%.4f MPa (%d below, %d above the band), %s "
                        "%.3e (%d below %g), eq. plastic strain %.4f (%d at or above %g); %s; %" PetscInt_FMT
                        " Newton, %.1f s\n",
                        what, Values(e.x).c_str(), e.objective, e.mises_min, e.mises_max, e.below, e.above,
                        p.o->wrinkle_stress ? "smin" : "emin", e.minor_min, e.wrinkled, p.o->criteria.minor_limit,
                        e.eq_max, e.eq_over,
                        p.o->criteria.max_eq_strain, e.Met() ? "criteria met" : "criteria NOT met", e.newton, e.wall));
  PetscFunctionReturn(0);
}

// The stretch run at final values x (memoised: TAO revisits points, and the rounded plan often is
// one already run).
PetscErrorCode Evaluate(Planner &p, const std::vector<double> &x, size_t *index) {
  PetscFunctionBeginUser;
  for (size_t k = 0; k < p.evals.size(); ++k)
    if (p.evals[k].x == x) {
      *index = k;
      PetscFunctionReturn(0);
    }
  StageValues stages;
  for (size_t v = 0; v < x.size(); ++v) stages[p.o->variables[v]] = StageValuesAt(p.shape[v], x[v]);
  PlanRunFields f;
  f.minor_is_stress = p.o->wrinkle_stress;
  PetscCall(p.run(p.comm, p.ctx, stages, &f));
  Evaluation e;
  e.x = x;
  e.completed = f.completed;
  e.failure = f.failure;
  e.newton = f.newton;
  e.wall = f.wall;
  p.wall += f.wall;
  if (p.elements < 0) {
    PetscCheck(f.completed, p.comm, PETSC_ERR_NOT_CONVERGED,
               "plan: the case's own schedule (%s) does not run (%s): the planner starts from it, so make it "
               "run first", Values(x).c_str(), f.failure.c_str());
    p.elements = (PetscInt)f.mises.size();
  }
  if (f.completed) {
    Score(*p.o, f, &e);
  } else {
    // A failed run is scored as every element far outside every criterion, so the search retreats.
    e.residual.assign(3 * p.elements + 1, 10.0 / std::sqrt((double)p.elements));
  }
  e.objective = std::inner_product(e.residual.begin(), e.residual.end(), e.residual.begin(), 0.0);
  p.evals.push_back(e);
  *index = p.evals.size() - 1;
  char what[32];
  std::snprintf(what, sizeof what, "run %zu", p.evals.size());
  PetscCall(PrintEvaluation(p, what, e));
  PetscFunctionReturn(0);
}

// The stretch run at TAO's scaled unknowns z = x / upper (drawing values clamped to the bounds).
PetscErrorCode EvaluateScaled(Planner &p, Vec z, size_t *index) {
  const PetscScalar *a;
  PetscInt n;
  std::vector<double> x;
  PetscFunctionBeginUser;
  PetscCall(VecGetLocalSize(z, &n));
  PetscCall(VecGetArrayRead(z, &a));
  x.resize(n);
  for (PetscInt i = 0; i < n; ++i) x[i] = std::clamp((double)a[i] * p.o->upper, p.o->lower, p.o->upper);
  PetscCall(VecRestoreArrayRead(z, &a));
  PetscCall(Evaluate(p, x, index));
  PetscFunctionReturn(0);
}

PetscErrorCode TaoResidual(Tao, Vec z, Vec r, void *ctx) {
  auto *p = (Planner *)ctx;
  size_t k;
  PetscScalar *a;
  PetscFunctionBeginUser;
  PetscCall(EvaluateScaled(*p, z, &k));
  PetscCall(VecGetArray(r, &a));
  for (size_t i = 0; i < p->evals[k].residual.size(); ++i) a[i] = p->evals[k].residual[i];
  PetscCall(VecRestoreArray(r, &a));
  PetscFunctionReturn(0);
}

PetscErrorCode TaoObjective(Tao, Vec z, PetscReal *f, void *ctx) {
  auto *p = (Planner *)ctx;
  size_t k;
  PetscFunctionBeginUser;
  PetscCall(EvaluateScaled(*p, z, &k));
  *f = p->evals[k].objective;
  PetscFunctionReturn(0);
}

PetscErrorCode WritePlan(const Planner &p, const Evaluation &start, const Evaluation &plan, const char *tao_type) {
  PetscMPIInt rank;
  int ok = 1;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(p.comm, &rank));
  if (rank == 0) {
    const std::filesystem::path path(p.o->output);
    std::error_code ec;
    if (path.has_parent_path()) std::filesystem::create_directories(path.parent_path(), ec);
    std::ofstream out(path);
    const PlanCriteria &c = p.o->criteria;
    const bool stress = p.o->wrinkle_stress;
    auto criteria = [stress](const Evaluation &e) {
      char buf[320];
      std::snprintf(buf, sizeof buf,
                    "Mises %.4f..%.4f MPa (%d below, %d above the band), %s %.3e (%d elements below), eq. plastic "
                    "strain %.4f (%d at or above), of %d elements",
                    e.mises_min, e.mises_max, e.below, e.above, stress ? "smin" : "emin", e.minor_min, e.wrinkled,
                    e.eq_max, e.eq_over, e.elements);
      return std::string(buf);
    };
    char head[512];
    std::snprintf(head, sizeof head,
                  "# Drawing schedule planned by etfe -analysis plan (TAO %s, %zu stretch runs, %.1f s).\n"
                  "# Criteria: Mises (PK2) within %g MPa +- %g %%, minor principal %s >= %g, equivalent plastic "
                  "strain < %g; then the least drawing.\n",
                  tao_type, p.evals.size(), p.wall, c.mises_target, 100 * c.mises_band, stress ? "stress" : "strain",
                  c.minor_limit, c.max_eq_strain);
    out << head << "# " << (plan.Met() ? "Met" : "NOT met") << " by this schedule: " << criteria(plan) << ".\n"
        << "# The case's own schedule (final " << Values(start.x) << "): " << criteria(start) << ".\n"
        << "# Use after the case: etfe -options_file <case>.opts -options_file " << p.o->output << "\n";
    for (size_t v = 0; v < p.o->variables.size(); ++v)
      out << "-" << p.o->variables[v] << " " << Stages(p.shape[v], plan.x[v]) << "\n";
    ok = out.good() ? 1 : 0;
  }
  PetscCallMPI(MPI_Bcast(&ok, 1, MPI_INT, 0, p.comm));
  PetscCheck(ok, p.comm, PETSC_ERR_FILE_WRITE, "plan: cannot write %s (-plan_output)", p.o->output.c_str());
  PetscFunctionReturn(0);
}

} // namespace

PetscErrorCode PlanGatherFields(Problem *P, PlanRunFields *fields) {
  CellFields f;
  PetscFunctionBeginUser;
  PetscCall(ComputeCellFields(P, P->U, &f, false));
  const int n = (int)f.mises.size();
  if (f.ep_bar.empty()) f.ep_bar.assign(n, 0.0);  // an elastic film: no plastic strain
  std::vector<int> counts(P->size), displs(P->size, 0);
  PetscCallMPI(MPI_Allgather(&n, 1, MPI_INT, counts.data(), 1, MPI_INT, P->comm));
  for (int r = 1; r < P->size; ++r) displs[r] = displs[r - 1] + counts[r - 1];
  const int N = displs[P->size - 1] + counts[P->size - 1];
  std::vector<double> *minor = fields->minor_is_stress ? &f.smin : &f.emin;
  for (auto [mine, all] : {std::make_pair(&f.mises, &fields->mises), std::make_pair(minor, &fields->minor),
                           std::make_pair(&f.ep_bar, &fields->eq)}) {
    all->resize(N);
    PetscCallMPI(MPI_Allgatherv(mine->data(), n, MPI_DOUBLE, all->data(), counts.data(), displs.data(), MPI_DOUBLE,
                                P->comm));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode PlanOptionsFromCommandLine(MPI_Comm comm, const std::string &results_stem, PlanOptions *o) {
  char *name_ptrs[16];
  PetscInt nnames = 16;
  PetscBool set = PETSC_FALSE;
  PetscReal bounds[2] = {o->lower, o->upper};
  PetscInt nbounds = 2;
  PetscBool bounds_set = PETSC_FALSE;
  char output[PETSC_MAX_PATH_LEN] = "";
  PetscFunctionBeginUser;
  PlanCriteria &c = o->criteria;
  PetscOptionsBegin(comm, nullptr, "Drawing planner (-analysis plan)", "Plan");
  PetscCall(PetscOptionsStringArray("-plan_variables",
                                    "Per-stage options whose final values are searched (default saddle_draw_a,b,c,d)",
                                    "", name_ptrs, &nnames, &set));
  PetscCall(PetscOptionsRealArray("-plan_bounds", "Lower,upper bound of every final value [mm] (frame limit 80, L721)",
                                  "", bounds, &nbounds, &bounds_set));
  PetscCall(PetscOptionsReal("-plan_mises_target", "Mises stress the film should reach [MPa] (first yield S_y1)", "",
                             c.mises_target, &c.mises_target, nullptr));
  PetscCall(PetscOptionsReal("-plan_mises_band", "Relative half-width of the Mises band", "", c.mises_band,
                             &c.mises_band, nullptr));
  PetscCall(PetscOptionsReal("-plan_min_strain", "Smallest minor principal GL strain allowed (0: no wrinkle)", "",
                             c.minor_limit, &c.minor_limit, nullptr));
  static const char *const tests[] = {"strain", "stress"};
  PetscInt test = o->wrinkle_stress ? 1 : 0;
  PetscCall(PetscOptionsEList("-plan_wrinkle_test",
                              "Wrinkle criterion: strain (minor principal strain >= -plan_min_strain, the thesis's) or "
                              "stress (minor principal stress >= 0, the tension-field model's taut test)",
                              "", tests, 2, tests[test], &test, nullptr));
  o->wrinkle_stress = test == 1;
  if (o->wrinkle_stress) c.minor_limit = 0.0, c.minor_unit = 0.1;  // MPa
  PetscCall(PetscOptionsReal("-plan_max_eq_strain", "Equivalent plastic strain must stay below this", "",
                             c.max_eq_strain, &c.max_eq_strain, nullptr));
  PetscCall(PetscOptionsReal("-plan_margin",
                             "Fraction by which the search tightens the criteria (a safety margin against rounding)", "",
                             o->margin, &o->margin, nullptr));
  PetscCall(PetscOptionsReal("-plan_draw_weight", "Weight of the mean drawing in the objective (least drawing)", "",
                             o->draw_weight, &o->draw_weight, nullptr));
  PetscCall(PetscOptionsInt("-plan_max_runs", "Stretch runs the search may spend", "", o->max_runs, &o->max_runs,
                            nullptr));
  PetscCall(PetscOptionsReal("-plan_round", "Resolution of the written drawing values [mm]", "", o->round, &o->round,
                             nullptr));
  PetscCall(PetscOptionsString("-plan_output", "Options file the schedule is written to (default <results>_plan.opts)",
                               "", output, output, sizeof output, nullptr));
  PetscOptionsEnd();
  o->variables.clear();
  if (set) {
    for (PetscInt i = 0; i < nnames; ++i) {
      o->variables.push_back(name_ptrs[i][0] == '-' ? name_ptrs[i] + 1 : name_ptrs[i]);
      PetscCall(PetscFree(name_ptrs[i]));
    }
  } else {
    o->variables = {"saddle_draw_a", "saddle_draw_b", "saddle_draw_c", "saddle_draw_d"};
  }
  PetscCheck((!bounds_set || nbounds == 2) && bounds[0] >= 0 && bounds[1] > bounds[0], comm, PETSC_ERR_ARG_OUTOFRANGE,
             "-plan_bounds needs two values 0 <= lower < upper (mm)");
  o->lower = bounds[0], o->upper = bounds[1];
  PetscCheck(c.mises_target > 0 && c.mises_band > 0 && c.mises_band < 1, comm, PETSC_ERR_ARG_OUTOFRANGE,
             "-plan_mises_target must be > 0 and -plan_mises_band in (0, 1)");
  PetscCheck(c.max_eq_strain > 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "-plan_max_eq_strain must be > 0");
  PetscCheck(o->margin >= 0 && o->margin < 1, comm, PETSC_ERR_ARG_OUTOFRANGE, "-plan_margin must be in [0, 1)");
  PetscCheck(o->draw_weight >= 0 && o->max_runs >= 1 && o->round >= 0, comm, PETSC_ERR_ARG_OUTOFRANGE,
             "-plan_draw_weight and -plan_round must be >= 0, -plan_max_runs >= 1");
  o->output = output[0] ? std::string(output) : results_stem + "_plan.opts";
  PetscFunctionReturn(0);
}

PetscErrorCode PlanRun(MPI_Comm comm, const PlanOptions &o, PlanStretchRun run, void *ctx) {
  Planner p{comm, &o, run, ctx, {}, {}, -1, 0.0};
  const PetscInt n = (PetscInt)o.variables.size();
  std::vector<double> x0(n);
  PetscFunctionBeginUser;
  // The case's schedule gives the staging and the start.
  for (PetscInt v = 0; v < n; ++v) {
    const auto it = o.case_arrays.find(o.variables[v]);
    PetscCheck(it != o.case_arrays.end(), comm, PETSC_ERR_USER_INPUT,
               "plan: -%s is not a per-stage option of this case's scene: -plan_variables names the options "
               "searched (the saddle stretch offers saddle_draw_a,b,c,d and saddle_pressure_cycle)",
               o.variables[v].c_str());
    const std::vector<double> &stages = it->second;
    PetscCheck(!stages.empty() && stages.back() > 0, comm, PETSC_ERR_USER_INPUT,
               "plan: the case must give -%s with a positive final stage: the planner keeps its stages' proportions "
               "and searches the final value (-plan_variables names the options)", o.variables[v].c_str());
    p.shape.emplace_back();
    for (double s : stages) p.shape.back().push_back(s / stages.back());
    x0[v] = std::clamp(stages.back(), o.lower, o.upper);
  }
  PetscCall(PetscPrintf(comm, "plan: %" PetscInt_FMT " variables, bounds [%g, %g] mm; Mises %g MPa +- %g %%, %s >= %g, "
                        "eq. plastic strain < %g, drawing weight %g; at most %" PetscInt_FMT " stretch runs\n",
                        n, o.lower, o.upper, o.criteria.mises_target, 100 * o.criteria.mises_band,
                        o.wrinkle_stress ? "smin" : "emin", o.criteria.minor_limit, o.criteria.max_eq_strain,
                        o.draw_weight, o.max_runs));
  size_t start;
  PetscCall(Evaluate(p, x0, &start));

  // TAO on every rank alike (the stretch runs are collective; every rank sees the same gathered
  // fields, so every rank's search takes the same steps). Unknowns scaled by the upper bound.
  Tao tao;
  Vec z, lb, ub, r;
  PetscCall(VecCreateSeq(PETSC_COMM_SELF, n, &z));
  PetscCall(VecDuplicate(z, &lb));
  PetscCall(VecDuplicate(z, &ub));
  PetscCall(VecCreateSeq(PETSC_COMM_SELF, 3 * p.elements + 1, &r));
  for (PetscInt v = 0; v < n; ++v) PetscCall(VecSetValue(z, v, x0[v] / o.upper, INSERT_VALUES));
  PetscCall(VecAssemblyBegin(z));
  PetscCall(VecAssemblyEnd(z));
  PetscCall(VecSet(lb, o.lower / o.upper));
  PetscCall(VecSet(ub, 1.0));
  PetscCall(TaoCreate(PETSC_COMM_SELF, &tao));
  PetscCall(TaoSetOptionsPrefix(tao, "plan_"));
  PetscCall(TaoSetType(tao, TAOPOUNDERS));
  PetscCall(TaoSetSolution(tao, z));
  PetscCall(TaoSetVariableBounds(tao, lb, ub));
  PetscCall(TaoSetResidualRoutine(tao, r, TaoResidual, &p));
  PetscCall(TaoSetObjective(tao, TaoObjective, &p));
  PetscCall(TaoSetGradient(tao, nullptr, TaoDefaultComputeGradient, &p));
  PetscCall(TaoSetMaximumFunctionEvaluations(tao, o.max_runs));
  PetscCall(TaoSetFromOptions(tao));
  TaoType tao_type;
  PetscCall(TaoGetType(tao, &tao_type));
  const std::string type = tao_type;  // TAO owns the name
  PetscCall(TaoSolve(tao));
  TaoConvergedReason reason;
  PetscCall(TaoGetConvergedReason(tao, &reason));
  PetscCall(PetscPrintf(comm, "plan: TAO %s stopped: %s\n", type.c_str(), TaoConvergedReasons[reason]));
  PetscCall(TaoDestroy(&tao));
  PetscCall(VecDestroy(&z));
  PetscCall(VecDestroy(&lb));
  PetscCall(VecDestroy(&ub));
  PetscCall(VecDestroy(&r));

  // The best run, rounded to what a frame can be set to, run once more if rounding moved it.
  size_t best = start;
  for (size_t k = 0; k < p.evals.size(); ++k)
    if (p.evals[k].completed && p.evals[k].objective < p.evals[best].objective) best = k;
  std::vector<double> xr = p.evals[best].x;
  if (o.round > 0)
    for (double &xi : xr) xi = std::clamp(std::round(xi / o.round) * o.round, o.lower, o.upper);
  size_t plan;
  PetscCall(Evaluate(p, xr, &plan));
  const std::string header = "plan: " + std::to_string(p.evals.size()) + " stretch runs";
  PetscCall(PetscPrintf(comm, "%s, %.1f s (%.1f s per run)\n", header.c_str(), p.wall, p.wall / p.evals.size()));
  PetscCall(PrintEvaluation(p, "case's own schedule, final", p.evals[start]));
  PetscCall(PrintEvaluation(p, "planned schedule, final", p.evals[plan]));
  PetscCall(WritePlan(p, p.evals[start], p.evals[plan], type.c_str()));
  PetscCall(PetscPrintf(comm, "plan: schedule written to %s; run it after the case: -options_file %s\n",
                        o.output.c_str(), o.output.c_str()));
  PetscFunctionReturn(0);
}

} // namespace etfe
