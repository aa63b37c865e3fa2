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
  // With a stress-free shape apart from the placed one (SceneSpec::element_reference): both as
  // triangles in the element's MD frame, 6 per local element (node 0 at the origin), and the
  // blend (0: placed, 1: stress free) that ref was built for (LocalMeshBlendReference).
  std::vector<double> ref_placed, ref_free;
  double ref_blend = 0.0;
  PetscInt NumLocal() const { return num_owned + num_ghost; }
};

// How the global mesh was numbered, for the set-up that follows (constraints, loads, matrix
// preallocation): per scene node its PETSc id, and its local id on this rank (-1: not local).
struct MeshNumbering {
  std::vector<PetscInt> petsc_id, local_of;
};

// Partitions the elements (METIS on rank 0, broadcast), numbers the nodes (a node belongs to
// the lowest rank among its elements; PETSc ids rank by rank) and builds the local elements'
// reference geometry with MD axis md_axis (collective). element_reference (9 per scene element,
// or empty) is each element's stress-free shape when it is not where its nodes are; its MD axis
// is md_axis on the placed triangle, carried to the stress-free one by the triangle's own map.
PetscErrorCode LocalMeshCreate(MPI_Comm comm, const MeshData &mesh, const double md_axis[3],
                               const std::vector<double> &element_reference, LocalMesh *local,
                               MeshNumbering *numbering);

// Rebuilds ref from (1 - s) ref_placed + s ref_free (a lay-on stage ramps s from 0 to 1); a
// degenerate blend is an error naming the element (collective).
PetscErrorCode LocalMeshBlendReference(MPI_Comm comm, LocalMesh *local, double s);

} // namespace etfe
