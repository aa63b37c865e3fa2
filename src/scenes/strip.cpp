// -scene strip: the ETFE lab's uniaxial tests on a flat strip in its plane, with physical time
// (-load_stage_duration, -load_hold_*), as a case of the general scene: relaxation (the right edge
// drawn to a strain, then held) and creep (a dead force on the right edge, then held). Left edge
// on rollers in X, bottom edge on rollers in Y, so the strip is homogeneous: every element carries
// the test's state. Each increment writes time, strain and stress to <results>_strip.csv (or
// -strip_history) and, at the monitor's rate, a line (-structure_check strip). The same cases as
// options only: options/structure/lab_strip_*.opts; this scene keeps its own option names.
#include <petscsys.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include "etfe/mesh/generators.h"
#include "etfe/mesh/mesh_options.h"
#include "etfe/scenes/scene_registry.h"
#include "real_array_option.h"
#include "structure_inputs.h"

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

// What the strip options give, as the general scene's inputs: left edge on rollers in X, bottom
// edge on rollers in Y, held in its plane; relaxation draws the right edge (strain x length times
// the multipliers), creep's force is added by the scene itself (AddEdgeForce).
PetscErrorCode StripPreset(MPI_Comm, StructureInputs *in, void *vctx) {
  const auto *p = (const StripInputs *)vctx;
  PetscFunctionBeginUser;
  for (const auto &gf : {std::make_pair("all", "z"), std::make_pair("left", "x"), std::make_pair("bottom", "y")}) {
    in->bcs.push_back(BcInput());
    in->bcs.back().group = gf.first, in->bcs.back().fix = gf.second;
  }
  if (p->test == StripTest::Relaxation) {
    in->bcs.push_back(BcInput());
    in->bcs.back().group = "right";
    in->bcs.back().move[0] = {"-strip_strain", p->schedule, p->strain * p->length};
  }
  CheckInput &ck = in->check;
  ck.name = "strip", ck.test = kStripTests[(int)p->test], ck.history = p->history, ck.given = true;
  PetscFunctionReturn(0);
}

} // namespace

PetscErrorCode SceneBuild_Strip(MPI_Comm comm, SceneSpec *scene, SceneObserver *observer) {
  StripInputs in;
  PetscFunctionBeginUser;
  PetscCall(ReadStripOptions(comm, &in));
  if (SceneHoldsMesh(comm))
    scene->mesh = MakeRectangleMesh(0.0, 0.0, in.length, in.width, (int)in.mesh.nx, (int)in.mesh.ny,
                                    in.mesh.pattern, 0.0, 12345u);
  PetscBool help = PETSC_FALSE;
  PetscCall(PetscOptionsHasHelp(nullptr, &help));
  if (help && scene->name.empty()) PetscFunctionReturn(0);  // -help without a scene: the options are shown
  PetscCall(StructureBuild(comm, scene, observer, true, StripPreset, &in));
  if (in.test == StripTest::Creep) {
    // The force per reference area needs the film's thickness, which the membrane reads later.
    PetscReal h = scene->thickness;
    PetscCall(PetscOptionsGetReal(nullptr, nullptr, "-membrane_thickness", &h, nullptr));
    const int is = scene->AddSchedule(Schedule{"stress", 0.0, in.schedule, "", 1.0});
    if (SceneHoldsMesh(comm)) AddEdgeForce(in, h, is, scene);
  }
  PetscFunctionReturn(0);
}

} // namespace etfe
