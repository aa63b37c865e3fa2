// Scene registry (-scene, -scene_list) and the shared mesh input (-mesh_file).
#include <petscsys.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "etfe/assembly/input_plausibility.h"
#include "etfe/mesh/cad_reader.h"
#include "etfe/mesh/gmsh_reader.h"
#include "etfe/mesh/mesh_options.h"
#include "etfe/base/rank0.h"
#include "etfe/scenes/scene_registry.h"

namespace etfe {

PetscErrorCode SceneBuild_Hencky(MPI_Comm, SceneSpec *, SceneObserver *);
PetscErrorCode SceneBuild_Patch(MPI_Comm, SceneSpec *, SceneObserver *);
PetscErrorCode SceneBuild_Capstan(MPI_Comm, SceneSpec *, SceneObserver *);
PetscErrorCode SceneBuild_Catenoid(MPI_Comm, SceneSpec *, SceneObserver *);
PetscErrorCode SceneBuild_Saddle(MPI_Comm, SceneSpec *, SceneObserver *);
PetscErrorCode SceneBuild_Annulus(MPI_Comm, SceneSpec *, SceneObserver *);
PetscErrorCode SceneBuild_Structure(MPI_Comm, SceneSpec *, SceneObserver *);
PetscErrorCode SceneBuild_Strip(MPI_Comm, SceneSpec *, SceneObserver *);

namespace {
PetscFunctionList scene_list = nullptr;
struct SceneEntry {
  std::string name, what, files;
};
std::vector<SceneEntry> scene_entries;  // for -scene_list, in registration order
}

PetscErrorCode SceneRegister(const char name[], SceneBuilder builder, const char what[], const char files[]) {
  PetscFunctionBeginUser;
  PetscCall(PetscFunctionListAdd(&scene_list, name, builder));
  scene_entries.push_back({name, what ? what : "", files ? files : ""});
  PetscFunctionReturn(0);
}

PetscErrorCode SceneRegisterAll(void) {
  PetscFunctionBeginUser;
  if (scene_list) PetscFunctionReturn(0);
  PetscCall(SceneRegister("hencky", SceneBuild_Hencky,
                          "clamped circular membrane under pressure, against Hencky's closed form",
                          "options/hencky.opts"));
  PetscCall(SceneRegister("patch", SceneBuild_Patch,
                          "in-plane stretch of a rectangle (uniaxial, biaxial, shear; load/unload stages)",
                          "options/patch.opts"));
  PetscCall(SceneRegister("capstan", SceneBuild_Capstan,
                          "film strip over a fixed pipe pulled to gross slip: effective friction coefficient",
                          "options/capstan.opts"));
  PetscCall(SceneRegister("catenoid", SceneBuild_Catenoid,
                          "form finding of a soap film between two rings, against the catenoid",
                          "options/catenoid.opts"));
  PetscCall(SceneRegister("saddle", SceneBuild_Saddle,
                          "the thesis's saddle: form finding, cutting patterns, stretch fabrication over the arch, "
                          "pressurization",
                          "options/saddle/ff_r*_s*.opts, dd1511.opts, dd1531.opts, pd*.opts, dd1511_pressure*.opts"));
  PetscCall(SceneRegister("annulus", SceneBuild_Annulus,
                          "pretensioned annulus, rigid hub rotated: wrinkled zone and torque against Stein & "
                          "Hedgepeth's tension-field closed form",
                          "options/annulus.opts"));
  PetscCall(SceneRegister("structure", SceneBuild_Structure,
                          "your own structure: a Gmsh mesh whose physical groups are held, drawn, loaded (pressure, "
                          "wind, snow, self-weight) or laid on rigid supports, by options keyed by group name",
                          "options/structure/*.opts (docs/own-structure.md; verify_*.opts and lab_strip_*.opts: the "
                          "built-in scenes' cases as its options)"));
  PetscCall(SceneRegister("strip", SceneBuild_Strip,
                          "uniaxial strip in the lab: stress relaxation and creep against time (viscoelastic_plastic)",
                          "options/strip_relaxation.opts, options/strip_creep.opts"));
  PetscFunctionReturn(0);
}

namespace {

// A pressure off by a unit (Pa or kPa for MPa), at its largest over the stage ends.
PetscErrorCode ReportPressurePlausibility(MPI_Comm comm, const SceneSpec &scene) {
  int stages = 0;
  double pmax = 0.0;
  PetscFunctionBeginUser;
  for (const Schedule &sc : scene.schedules) stages = std::max(stages, sc.NumStages());
  if (scene.loads_checked) PetscFunctionReturn(0);
  for (const PressureSpec &p : scene.pressures)
    for (int t = 0; t <= stages; ++t) pmax = std::max(pmax, std::fabs(p.value.At(scene.schedules, t)));
  PetscCall(ReportPlausibility(
      comm, CheckPressure("scene " + scene.name + ": the pressure (-" + scene.name + "_* options)", pmax)));
  PetscFunctionReturn(0);
}

} // namespace

PetscErrorCode SceneCreateFromOptions(MPI_Comm comm, SceneSpec *scene, SceneObserver *observer) {
  char name[64] = "";
  PetscBool set = PETSC_FALSE, list = PETSC_FALSE;
  SceneBuilder build = nullptr;
  PetscFunctionBeginUser;
  PetscCall(SceneRegisterAll());
  PetscOptionsBegin(comm, nullptr, "Scene", "Scene");
  PetscCall(PetscOptionsFList("-scene", "Scene to build", "", scene_list, name, name, sizeof name,
                              &set));
  PetscCall(PetscOptionsBool("-scene_list", "List the registered scenes and exit", "", list, &list,
                             nullptr));
  PetscOptionsEnd();
  if (list) {
    PetscCall(PetscPrintf(comm, "scenes (-scene <name>; run one with: scripts/run <options file>; every one but the "
                                "saddle's stretch is a case of the general scene, structure, given its inputs):\n"));
    for (const SceneEntry &e : scene_entries)
      PetscCall(PetscPrintf(comm, "  %-9s %s\n            options files: %s\n", e.name.c_str(), e.what.c_str(),
                            e.files.c_str()));
    PetscFunctionReturn(0);
  }
  PetscBool help = PETSC_FALSE;
  PetscCall(PetscOptionsHasHelp(nullptr, &help));
  if (!set && help) {
    // -help without a scene: show every scene's options (each builder reads its own).
    for (const SceneEntry &e : scene_entries) {
      SceneSpec throwaway;
      SceneObserver unused;
      PetscCall(PetscFunctionListFind(scene_list, e.name.c_str(), &build));
      PetscCall(build(comm, &throwaway, &unused));
      SceneObserverDestroy(&unused);
    }
    scene->name.clear();
    PetscFunctionReturn(0);
  }
  PetscCheck(set, comm, PETSC_ERR_USER_INPUT,
             "no scene given: add -scene <name> (or an options file that sets it); -scene_list "
             "shows the registered scenes");
  PetscCall(PetscFunctionListFind(scene_list, name, &build));
  PetscCheck(build, comm, PETSC_ERR_ARG_UNKNOWN_TYPE,
             "-scene %s is not a registered scene; -scene_list shows them", name);
  scene->name = name;
  PetscCall(build(comm, scene, observer));
  // Whatever a builder made of its options, the load data must be finite numbers.
  for (const Schedule &sc : scene->schedules) {
    PetscCheck(std::isfinite(sc.initial), comm, PETSC_ERR_ARG_OUTOFRANGE, "scene %s: schedule %s starts at %g",
               name, sc.name.c_str(), sc.initial);
    for (size_t k = 0; k < sc.values.size(); ++k)
      PetscCheck(std::isfinite(sc.values[k]), comm, PETSC_ERR_ARG_OUTOFRANGE,
                 "scene %s: schedule %s has the value %g at stage %zu; check the options that set it", name,
                 sc.name.c_str(), sc.values[k], k + 1);
  }
  // The lists indexed by the mesh exist on rank 0 only (scene_registry.h).
  std::string err;
  for (const DofConstraint &c : scene->constraints)
    if (err.empty() && !(std::isfinite(c.value.coef[0]) && std::isfinite(c.value.coef[1])))
      err = "scene " + std::string(name) + ": the prescribed displacement of node " + std::to_string(c.node) +
            " is not finite; check the scene's options";
  for (const NodalForce &f : scene->nodal_forces)
    if (err.empty() && !(std::isfinite(f.value.coef[0]) && std::isfinite(f.value.coef[1])))
      err = "scene " + std::string(name) + ": the force on node " + std::to_string(f.node) +
            " is not finite; check the scene's options";
  PetscCall(Rank0Outcome(comm, err.empty() ? 1 : 0, err, PETSC_ERR_ARG_OUTOFRANGE));
  for (const PressureSpec &p : scene->pressures)
    PetscCheck(std::isfinite(p.value.coef[0]) && std::isfinite(p.value.coef[1]), comm, PETSC_ERR_ARG_OUTOFRANGE,
               "scene %s: the pressure is not finite", name);
  PetscCall(ReportPressurePlausibility(comm, *scene));
  PetscCall(SceneWriteMesh(comm, *scene));
  PetscFunctionReturn(0);
}

PetscErrorCode SceneWriteMesh(MPI_Comm comm, const SceneSpec &scene) {
  char path[PETSC_MAX_PATH_LEN] = "";
  PetscBool set = PETSC_FALSE;
  std::string err;
  PetscFunctionBeginUser;
  PetscOptionsBegin(comm, nullptr, "Scene mesh", "Scene");
  PetscCall(PetscOptionsString("-scene_mesh_out",
                               "Write the scene's mesh with its node and element groups as Gmsh (a generated scene's "
                               "mesh becomes a file the general scene, -scene structure, reads)",
                               "", path, path, sizeof path, &set));
  PetscOptionsEnd();
  if (!set) PetscFunctionReturn(0);
  int ok = 1;
  if (SceneHoldsMesh(comm)) {
    const std::filesystem::path dir = std::filesystem::path(path).parent_path();
    std::error_code ec;  // a failure to make it shows as the write's own error
    if (!dir.empty()) std::filesystem::create_directories(dir, ec);
    ok = WriteGmshFile(path, scene.mesh, &err) ? 1 : 0;
  }
  PetscCall(Rank0Outcome(comm, ok, "-scene_mesh_out: " + err, PETSC_ERR_FILE_WRITE));
  PetscCall(PetscPrintf(comm, "scene %s: mesh and its groups written to %s\n", scene.name.c_str(), path));
  PetscFunctionReturn(0);
}

PetscErrorCode SceneReadMesh(MPI_Comm comm, const char path[], MeshData *mesh) {
  PetscMPIInt rank;
  int ok = 1;
  std::string err;
  double cad_size;
  PetscFunctionBeginUser;
  PetscBool welds = PETSC_FALSE;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCall(MeshCadSizeFromOptions(comm, path, &cad_size));
  PetscOptionsBegin(comm, nullptr, "Mesh file", "Mesh");
  PetscCall(PetscOptionsBool("-mesh_welds",
                             "Edges of three or more triangles are welds of layers (a three-layer cushion's rim), "
                             "not an error",
                             "", welds, &welds, nullptr));
  PetscOptionsEnd();
  if (rank == 0) {
    ok = ReadMeshFile(path, cad_size, mesh, &err) ? 1 : 0;
    mesh->welds = welds;
    ok = ok && MeshOrient(mesh, &err) && MeshCheck(*mesh, 0.0, &err) ? 1 : 0;
  }
  PetscCall(Rank0Outcome(comm, ok, err, PETSC_ERR_FILE_READ));
  for (const std::string &note : mesh->notes) PetscCall(PetscPrintf(comm, "mesh %s: %s\n", path, note.c_str()));
  if (rank == 0) PetscCall(ReportPlausibility(PETSC_COMM_SELF, CheckMeshExtent(mesh->coords.data(), mesh->NumNodes(), path)));
  mesh->source = path;
  PetscFunctionReturn(0);
}

bool SceneHoldsMesh(MPI_Comm comm) {
  PetscMPIInt rank = 0;
  MPI_Comm_rank(comm, &rank);
  return rank == 0;
}

} // namespace etfe
