// This rank's part of the scene's mesh: its METIS elements, their nodes (owned first, then
// ghosts) with PETSc and scene numbers, and the reference geometry of every local element.
// Built by LocalMeshCreate (src/mesh/distribute.cpp) from the global mesh every rank holds
// during set-up.
#pragma once
#include <petscsys.h>

#include <vector>

#include "etfe/kernels/membrane.h"
#include "etfe/mesh/mesh_data.h"

namespace etfe {

struct LocalMesh {
  PetscInt num_nodes_global = 0, num_elements_global = 0;
  PetscInt num_owned = 0, num_ghost = 0;  // local nodes: owned first, then ghosts
  PetscInt owned_start = 0;               // PETSc (global) id of the first owned node
  std::vector<PetscInt> global_id;        // per local node: PETSc id
  std::vector<PetscInt> natural_id;       // per local node: id in the scene's mesh
  std::vector<double> X;                  // reference coordinates, 3 per local node
  PetscInt num_elements = 0;              // local elements (this rank's METIS part)
  PetscInt element_start = 0;             // PETSc-order id of the first local element
  std::vector<int> tri;                   // local node ids, 3 per local element
  std::vector<PetscInt> element_natural;  // per local element: id in the scene's mesh
  std::vector<MembraneReference> ref;     // reference geometry per local element
  PetscInt NumLocal() const { return num_owned + num_ghost; }
};

// How the global mesh was numbered, for the set-up that follows (constraints, loads, matrix
// preallocation): per scene node its PETSc id, and its local id on this rank (-1: not local).
struct MeshNumbering {
  std::vector<PetscInt> petsc_id, local_of;
};

// Partitions the elements (METIS on rank 0, broadcast), numbers the nodes (a node belongs to
// the lowest rank among its elements; PETSc ids rank by rank) and builds the local elements'
// reference geometry with MD axis md_axis (collective).
PetscErrorCode LocalMeshCreate(MPI_Comm comm, const MeshData &mesh, const double md_axis[3], LocalMesh *local,
                               MeshNumbering *numbering);

} // namespace etfe
