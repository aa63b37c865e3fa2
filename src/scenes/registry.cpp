// Scene registry (-scene, -scene_list) and the shared mesh input (-mesh_file).
#include <petscsys.h>

#include <cmath>
#include <string>
#include <vector>

#include "etfe/mesh/gmsh_reader.h"
#include "etfe/rank0.h"
#include "etfe/scene_registry.h"

namespace etfe {

PetscErrorCode SceneBuild_Hencky(MPI_Comm, SceneSpec *, SceneObserver *);
PetscErrorCode SceneBuild_Patch(MPI_Comm, SceneSpec *, SceneObserver *);
PetscErrorCode SceneBuild_Capstan(MPI_Comm, SceneSpec *, SceneObserver *);
PetscErrorCode SceneBuild_Catenoid(MPI_Comm, SceneSpec *, SceneObserver *);
PetscErrorCode SceneBuild_Saddle(MPI_Comm, SceneSpec *, SceneObserver *);
PetscErrorCode SceneBuild_Annulus(MPI_Comm, SceneSpec *, SceneObserver *);

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
  PetscFunctionReturn(0);
}

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
    PetscCall(PetscPrintf(comm, "scenes (-scene <name>; run one with: scripts/run <options file>):\n"));
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
  for (const auto *list : {&scene->constraints})
    for (const DofConstraint &c : *list)
      PetscCheck(std::isfinite(c.value.coef[0]) && std::isfinite(c.value.coef[1]), comm, PETSC_ERR_ARG_OUTOFRANGE,
                 "scene %s: the prescribed displacement of node %d is not finite; check the scene's options", name,
                 c.node);
  for (const NodalForce &f : scene->nodal_forces)
    PetscCheck(std::isfinite(f.value.coef[0]) && std::isfinite(f.value.coef[1]), comm, PETSC_ERR_ARG_OUTOFRANGE,
               "scene %s: the force on node %d is not finite; check the scene's options", name, f.node);
  PetscCheck(std::isfinite(scene->pressure.value.coef[0]) && std::isfinite(scene->pressure.value.coef[1]), comm,
             PETSC_ERR_ARG_OUTOFRANGE, "scene %s: the pressure is not finite", name);
  PetscFunctionReturn(0);
}

PetscErrorCode MeshReadAndBroadcast(MPI_Comm comm, const char path[], MeshData *mesh) {
  PetscMPIInt rank;
  int ok = 1;
  std::string err;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  if (rank == 0) {
    ok = ReadGmshFile(path, mesh, &err) && MeshOrient(mesh, &err) && MeshCheck(*mesh, 0.0, &err) ? 1 : 0;
  }
  PetscCall(Rank0Outcome(comm, ok, err, PETSC_ERR_FILE_READ));
  for (const std::string &note : mesh->notes) PetscCall(PetscPrintf(comm, "mesh %s: %s\n", path, note.c_str()));
  // Broadcast coordinates, triangles and the named sets.
  long long sizes[3] = {(long long)mesh->coords.size(), (long long)mesh->triangles.size(),
                        (long long)mesh->node_sets.size() + (long long)mesh->element_sets.size()};
  PetscCallMPI(MPI_Bcast(sizes, 3, MPI_LONG_LONG, 0, comm));
  mesh->coords.resize(sizes[0]);
  mesh->triangles.resize(sizes[1]);
  PetscCallMPI(MPI_Bcast(mesh->coords.data(), (int)sizes[0], MPI_DOUBLE, 0, comm));
  PetscCallMPI(MPI_Bcast(mesh->triangles.data(), (int)sizes[1], MPI_INT, 0, comm));
  // Sets: serialise as (kind, name length, name, count, ids).
  std::vector<int> buf;
  if (rank == 0) {
    for (int kind = 0; kind < 2; ++kind)
      for (auto &kv : kind == 0 ? mesh->node_sets : mesh->element_sets) {
        buf.push_back(kind);
        buf.push_back((int)kv.first.size());
        for (char c : kv.first) buf.push_back(c);
        buf.push_back((int)kv.second.size());
        buf.insert(buf.end(), kv.second.begin(), kv.second.end());
      }
  }
  long long nbuf = (long long)buf.size();
  PetscCallMPI(MPI_Bcast(&nbuf, 1, MPI_LONG_LONG, 0, comm));
  buf.resize(nbuf);
  PetscCallMPI(MPI_Bcast(buf.data(), (int)nbuf, MPI_INT, 0, comm));
  if (rank != 0) {
    size_t k = 0;
    while (k < buf.size()) {
      int kind = buf[k++], len = buf[k++];
      std::string name(buf.begin() + k, buf.begin() + k + len);
      k += len;
      int n = buf[k++];
      std::vector<int> ids(buf.begin() + k, buf.begin() + k + n);
      k += n;
      (kind == 0 ? mesh->node_sets : mesh->element_sets)[name] = std::move(ids);
    }
  }
  mesh->source = path;
  PetscFunctionReturn(0);
}

} // namespace etfe
