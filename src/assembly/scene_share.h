// What each rank takes of the scene description (assembly layer, private): the scene's lists
// indexed by scene nodes and elements, restricted to the rank's part of the mesh and renumbered
// to its local ids. Rank 0, the only rank that holds the global description, sends each share.
#pragma once
#include <petscsys.h>

#include <vector>

#include "etfe/mesh/local_mesh.h"
#include "etfe/description/scene.h"

namespace etfe {

struct SceneShare {
  std::vector<DofConstraint> constraints;    // node: local id (owned or ghost); the scene's order
  std::vector<NodalForce> forces;            // node: local id of an owned node
  std::vector<std::vector<PetscInt>> pressure_elements;  // per pressure load: local element ids
  std::vector<double> initial_guess;         // 3 per owned node, or empty
  std::vector<double> element_stress_ratio;  // per local element, or empty
  std::vector<double> element_reference;     // 9 per local element, or empty
  std::vector<double> element_thickness;     // per local element, or empty
  std::vector<double> element_md;            // 3 per local element, or empty
  std::vector<int> element_material;         // per local element, or empty (SceneSpec::element_material)
  std::vector<PetscInt> d_nnz, o_nnz;        // preallocation of the owned rows (3x3 blocks)
};

// Collective. Checks the description on rank 0 (node, element and array sizes against the mesh;
// a bad entry is an error on every rank naming it), then distributes the mesh
// (LocalMeshDistribute) with each rank's share of the lists.
PetscErrorCode SceneDistribute(MPI_Comm comm, const SceneSpec &scene, LocalMesh *mesh, SceneShare *share);

} // namespace etfe
