// This rank's part of the scene's mesh: its METIS elements, their nodes (owned first, then
// ghosts) with PETSc and scene numbers, the named sets restricted to them and the reference
// geometry of every local element. Built by LocalMeshDistribute (src/mesh/distribute.cpp): the
// global mesh exists on rank 0 only (the reader), which partitions it and sends each rank its
// share, one rank at a time.
#pragma once
#include <petscsys.h>

#include <cstddef>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "etfe/kernels/membrane.h"
#include "etfe/mesh/byte_buffer.h"
#include "etfe/mesh/mesh_data.h"

namespace etfe {

struct LocalMesh {
  std::string source;                     // file name or generator description, for messages
  std::size_t share_bytes = 0;            // what rank 0 sent this rank at set-up (its whole share)
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
  // The scene mesh's named sets (every name on every rank), restricted to this rank: local node
  // ids (owned and ghost) and local element ids, ascending.
  std::map<std::string, std::vector<PetscInt>> node_sets, element_sets;
  std::vector<MembraneReference> ref;     // reference geometry per local element
  // The MD direction per local element (3 each) where the film's parts differ; empty: one axis.
  std::vector<double> md;
  const double *MdAxis(PetscInt e, const double *uniform) const { return md.empty() ? uniform : &md[3 * e]; }
  // With a stress-free shape apart from the placed one (SceneSpec::element_reference): both as
  // triangles in the element's MD frame, 6 per local element (node 0 at the origin), and the
  // blend (0: placed, 1: stress free) that ref was built for (LocalMeshBlendReference).
  std::vector<double> ref_placed, ref_free;
  double ref_blend = 0.0;
  PetscInt NumLocal() const { return num_owned + num_ghost; }
};

// One rank's share as the reader computes it, handed to a ShareWriter: the rank's nodes and
// elements (scene ids, in local order) and, per scene node, its local id there (-1: not local).
struct RankShare {
  int rank;
  PetscInt num_owned;
  const std::vector<PetscInt> &nodes, &elements, &local_of;
};
// Appends what else a rank needs of data indexed by scene nodes or elements (rank 0 only).
using ShareWriter = std::function<void(const RankShare &, ByteWriter *)>;

// Collective. On rank 0, mesh is the scene's global mesh (elsewhere it is not read): METIS
// partitions the elements; a node belongs to the lowest rank among its elements; PETSc ids number
// nodes rank by rank, keeping the scene's order inside a rank (a rank's matrix rows are
// contiguous); ghosts follow the owned nodes in PETSc order. Each rank receives its elements,
// nodes, coordinates and sets, the exact preallocation of its owned rows (3x3 blocks in and off
// the diagonal part: d_nnz, o_nnz) and what `extra` wrote for it, left in *extra_in.
PetscErrorCode LocalMeshDistribute(MPI_Comm comm, const MeshData &mesh, const ShareWriter &extra, LocalMesh *local,
                                   std::vector<PetscInt> *d_nnz, std::vector<PetscInt> *o_nnz, ByteReader *extra_in);

// Builds ref for every local element with MD axis md_axis. element_reference (9 per local
// element, or empty) is each element's stress-free shape when it is not where its nodes are; its
// MD axis is md_axis on the placed triangle, carried to the stress-free one by the triangle's own
// map. A degenerate element is an error naming it (collective).
PetscErrorCode LocalMeshBuildReference(MPI_Comm comm, const double md_axis[3], const std::vector<double> &element_reference,
                                       LocalMesh *local);

// Rebuilds ref from (1 - s) ref_placed + s ref_free (a lay-on stage ramps s from 0 to 1); a
// degenerate blend is an error naming the element (collective).
PetscErrorCode LocalMeshBlendReference(MPI_Comm comm, LocalMesh *local, double s);

} // namespace etfe
