// Scenes (scenes layer): a scene is a description (scene.h) plus what it watches of a run (a
// SceneObserver: its report, a per-increment monitor). Builders are registered by name (-scene
// <name>, -scene_list) and fill both from their options; the app hands the observer to the
// problem it builds from the description.
#pragma once
#include <petscsys.h>

#include "etfe/mesh/mesh_data.h"
#include "etfe/problem.h"
#include "etfe/scene.h"

namespace etfe {

typedef PetscErrorCode (*SceneBuilder)(MPI_Comm, SceneSpec *, SceneObserver *);

PetscErrorCode SceneRegisterAll(void);
// what: one line on what the scene computes; files: its options files (both for -scene_list).
PetscErrorCode SceneRegister(const char name[], SceneBuilder builder, const char what[], const char files[]);
// Builds the scene named by -scene (collective). Unknown names list the registered ones.
PetscErrorCode SceneCreateFromOptions(MPI_Comm comm, SceneSpec *scene, SceneObserver *observer);

// Reads the mesh named by -mesh_file on rank 0 and broadcasts it; used by scenes that accept a
// Gmsh file instead of their generator.
PetscErrorCode MeshReadAndBroadcast(MPI_Comm comm, const char path[], MeshData *mesh);

} // namespace etfe
