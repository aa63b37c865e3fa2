// Scenes (scenes layer): a scene is a description (scene.h) plus what it watches of a run (a
// SceneObserver: its report, a per-increment monitor). Builders are registered by name (-scene
// <name>, -scene_list) and fill both from their options; the app hands the observer to the
// problem it builds from the description.
#pragma once
#include <petscsys.h>

#include "etfe/mesh/mesh_data.h"
#include "etfe/assembly/problem.h"
#include "etfe/description/scene.h"

namespace etfe {

typedef PetscErrorCode (*SceneBuilder)(MPI_Comm, SceneSpec *, SceneObserver *);

PetscErrorCode SceneRegisterAll(void);
// what: one line on what the scene computes; files: its options files (both for -scene_list).
PetscErrorCode SceneRegister(const char name[], SceneBuilder builder, const char what[], const char files[]);
// Builds the scene named by -scene (collective). Unknown names list the registered ones.
PetscErrorCode SceneCreateFromOptions(MPI_Comm comm, SceneSpec *scene, SceneObserver *observer);

// The global mesh lives on rank 0 only, the reader: a builder makes or reads it there
// (SceneHoldsMesh), fills what is indexed by it (sets, constraints, loads, element data) from it
// there, and decides anything that depends on it there too, reporting to every rank with
// Rank0Outcome (rank0.h). On the other ranks the mesh stays empty, so loops over it do nothing;
// ProblemCreate sends each rank its share. What an observer needs of the mesh it finds in its
// setup, on the distributed problem (SceneObserver::setup).
bool SceneHoldsMesh(MPI_Comm comm);
// -scene_mesh_out FILE: rank 0 writes the built scene's mesh with its groups as Gmsh (collective).
PetscErrorCode SceneWriteMesh(MPI_Comm comm, const SceneSpec &scene);
// Reads, orients and checks the Gmsh file on rank 0 (the mesh of the other ranks gets the source
// name only); used by scenes that accept a file instead of their generator. A CAD file (STEP,
// IGES, BREP) is meshed by Gmsh there at -mesh_cad_size (etfe/mesh/cad_reader.h); a mesh whose
// extent is implausible for a membrane (etfe/kernels/plausibility.h) gets a warning.
PetscErrorCode SceneReadMesh(MPI_Comm comm, const char path[], MeshData *mesh);

} // namespace etfe
