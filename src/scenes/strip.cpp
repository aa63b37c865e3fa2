// Strip scene: the ETFE lab's uniaxial tests on a flat strip in its plane, with physical time
// (-load_stage_duration, -load_hold_*): relaxation (the right edge drawn to a strain, then held)
// and creep (a dead force on the right edge, then held). Left edge on rollers in X, bottom edge
// on rollers in Y, so the strip is homogeneous: every element carries the test's state. Each
// increment writes time, strain and stress to <results>_strip.csv (or -strip_history) and, at the
// monitor's rate, a line.
#include <petscsys.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include "etfe/assembly.h"
#include "etfe/csv_history.h"
#include "etfe/mesh/generators.h"
#include "etfe/mesh/mesh_options.h"
#include "etfe/scene_registry.h"
#include "real_array_option.h"

namespace etfe {

namespace {

enum class StripTest { Relaxation, Creep };
const char *const kStripTests[] = {"relaxation", "creep"};

struct StripInputs {
  double length = 100.0, width = 10.0;  // mm
  StripTest test = StripTest::Relaxation;
  double strain = 0.01;  // engineering strain at schedule value 1 (relaxation)
  double stress = 5.0;   // nominal stress F / (width h0) at schedule value 1 [MPa] (creep)
  std::vector<double> schedule = {1.0};
  std::string history;
  MeshOptions mesh;
};

struct StripContext {
  StripTest test;
  std::string history;
};

// The homogeneous state as the elements' mean: GL strain Exx, PK2 Sxx, and from them the
// engineering strain and the nominal (force per reference area) stress.
PetscErrorCode MeasureStrip(Problem *P, double *E, double *S, double *e_eng, double *s_nom) {
  CellFields c;
  double loc[3] = {0.0, 0.0, 0.0}, glob[3];
  PetscFunctionBeginUser;
  PetscCall(ComputeCellFields(P, P->U, &c, false));
  for (PetscInt e = 0; e < P->mesh.num_elements; ++e) {
    loc[0] += c.strain[3 * e], loc[1] += c.stress[3 * e];
    loc[2] += 1.0;
  }
  PetscCallMPI(MPI_Allreduce(loc, glob, 3, MPI_DOUBLE, MPI_SUM, P->comm));
  *E = glob[0] / glob[2], *S = glob[1] / glob[2];
  const double stretch = std::sqrt(1.0 + 2.0 * *E);
  *e_eng = stretch - 1.0, *s_nom = stretch * *S;
  PetscFunctionReturn(0);
}

PetscErrorCode StripStep(Problem *P, void *vctx, PetscInt step, double t, PetscInt print_every) {
  auto *c = (StripContext *)vctx;
  double E, S, e, s;
  PetscFunctionBeginUser;
  PetscCall(MeasureStrip(P, &E, &S, &e, &s));
  const double seconds = P->clock.Seconds(t);
  if (print_every > 0 && step % print_every == 0)
    PetscCall(PetscPrintf(P->comm, "strip: %s  time %.6g s  strain %.6e  stress %.6e MPa (nominal %.6e)\n",
                          kStripTests[(int)c->test], seconds, e, S, s));
  const std::string path = CsvHistoryPath(c->history, P->observer.results_stem, "_strip.csv");
  if (path.empty() || P->rank != 0) PetscFunctionReturn(0);
  FILE *out = CsvHistoryOpen(path, step, "step,load_time,seconds,strain_gl,strain,stress_pk2,stress_nominal");
  PetscCheck(out, PETSC_COMM_SELF, PETSC_ERR_FILE_OPEN, "strip: cannot write %s", path.c_str());
  std::fprintf(out, "%lld,%.10g,%.10g,%.12e,%.12e,%.12e,%.12e\n", (long long)step, t, seconds, E, e, S, s);
  std::fclose(out);
  PetscFunctionReturn(0);
}

PetscErrorCode StripReport(Problem *P, void *vctx) {
  auto *c = (StripContext *)vctx;
  double E, S, e, s;
  PetscFunctionBeginUser;
  PetscCall(MeasureStrip(P, &E, &S, &e, &s));
  PetscCall(PetscPrintf(P->comm, "strip: %s at the end (%.6g s): strain %.9e, stress %.9e MPa (nominal %.9e)\n",
                        kStripTests[(int)c->test], P->clock.Seconds(P->time), e, S, s));
  PetscFunctionReturn(0);
}

PetscErrorCode ReadStripOptions(MPI_Comm comm, StripInputs *in) {
  PetscInt test = (PetscInt)in->test;
  char history[PETSC_MAX_PATH_LEN] = "";
  PetscBool named = PETSC_FALSE;
  PetscFunctionBeginUser;
  PetscOptionsBegin(comm, nullptr, "Strip scene: uniaxial relaxation and creep tests", "Scene");
  PetscCall(PetscOptionsReal("-strip_length", "Length in X [mm]", "", in->length, &in->length, nullptr));
  PetscCall(PetscOptionsReal("-strip_width", "Width in Y [mm]", "", in->width, &in->width, nullptr));
  PetscCall(PetscOptionsEList("-strip_test",
                              "relaxation (the right edge drawn to -strip_strain) or creep (a dead force of "
                              "-strip_stress on the right edge)",
                              "", kStripTests, 2, kStripTests[test], &test, nullptr));
  PetscCall(PetscOptionsReal("-strip_strain", "Engineering strain at schedule value 1 (relaxation)", "", in->strain,
                             &in->strain, nullptr));
  PetscCall(PetscOptionsReal("-strip_stress",
                             "Nominal stress (force per reference width and thickness) at schedule value 1 [MPa] "
                             "(creep)",
                             "", in->stress, &in->stress, nullptr));
  PetscCall(OptionsRealArray(PetscOptionsObject, "-strip_schedule",
                             "Multipliers of the strain or stress at the end of each stage (a hold stage: "
                             "-load_hold_after)",
                             &in->schedule, &named));
  PetscCall(PetscOptionsString("-strip_history", "CSV of time, strain and stress per increment (default: beside the "
                                                 "results, <results>_strip.csv)",
                               "", history, history, sizeof history, nullptr));
  PetscOptionsEnd();
  in->test = (StripTest)test;
  in->history = history;
  in->mesh.keys = kMeshGrid;
  in->mesh.nx = 4, in->mesh.ny = 1;
  PetscCall(MeshOptionsFromCommandLine(comm, "strip scene", &in->mesh));
  PetscCheck(!named || !in->schedule.empty(), comm, PETSC_ERR_ARG_SIZ,
             "-strip_schedule is empty: give at least one stage value");
  PetscCheck(in->length > 0 && in->width > 0 && in->mesh.nx >= 1 && in->mesh.ny >= 1, comm, PETSC_ERR_ARG_OUTOFRANGE,
             "strip: need positive -strip_length/-strip_width and -mesh_nx/-mesh_ny >= 1");
  PetscCheck(std::isfinite(in->strain) && in->strain > -1 && std::isfinite(in->stress), comm, PETSC_ERR_ARG_OUTOFRANGE,
             "-strip_strain %g / -strip_stress %g: use a finite strain > -1 and a finite stress", in->strain,
             in->stress);
  PetscFunctionReturn(0);
}

// Creep: the force F = stress width h0 on the right edge, shared by the nodes' tributary lengths.
void AddEdgeForce(const StripInputs &in, double thickness, int is, SceneSpec *scene) {
  std::vector<std::pair<double, int>> edge;
  for (int n : scene->mesh.node_sets["right"]) edge.push_back({scene->mesh.coords[3 * n + 1], n});
  std::sort(edge.begin(), edge.end());
  const double force = in.stress * in.width * thickness;  // N at schedule value 1
  for (size_t k = 0; k < edge.size(); ++k) {
    const double lo = k == 0 ? edge[k].first : 0.5 * (edge[k - 1].first + edge[k].first);
    const double hi = k + 1 == edge.size() ? edge[k].first : 0.5 * (edge[k].first + edge[k + 1].first);
    scene->nodal_forces.push_back({edge[k].second, 0, {{force * (hi - lo) / in.width, 0.0}, {is, -1}}});
  }
}

} // namespace

PetscErrorCode SceneBuild_Strip(MPI_Comm comm, SceneSpec *scene, SceneObserver *observer) {
  StripInputs in;
  PetscFunctionBeginUser;
  PetscCall(ReadStripOptions(comm, &in));
  if (SceneHoldsMesh(comm))
    scene->mesh = MakeRectangleMesh(0.0, 0.0, in.length, in.width, (int)in.mesh.nx, (int)in.mesh.ny,
                                    in.mesh.pattern, 0.0, 12345u);
  const int is = scene->AddSchedule(
      Schedule{in.test == StripTest::Creep ? "stress" : "strain", 0.0, in.schedule, "", 1.0});
  auto &sets = scene->mesh.node_sets;
  for (int n : sets["all"]) scene->constraints.push_back({n, 2, {}});
  for (int n : sets["left"]) scene->constraints.push_back({n, 0, {}});
  for (int n : sets["bottom"]) scene->constraints.push_back({n, 1, {}});
  if (in.test == StripTest::Relaxation)
    for (int n : sets["right"]) scene->constraints.push_back({n, 0, {{in.strain * in.length, 0.0}, {is, -1}}});
  else {
    // The force per reference area needs the film's thickness, which the membrane reads later.
    PetscReal h = scene->thickness;
    PetscCall(PetscOptionsGetReal(nullptr, nullptr, "-membrane_thickness", &h, nullptr));
    AddEdgeForce(in, h, is, scene);
  }
  auto *ctx = new StripContext{in.test, in.history};
  observer->step_monitor = StripStep;
  observer->report = StripReport;
  observer->ctx = ctx;
  observer->destroy = [](void *c) { delete (StripContext *)c; };
  PetscFunctionReturn(0);
}

} // namespace etfe
