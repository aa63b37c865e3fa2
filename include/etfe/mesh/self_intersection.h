// The check that a mesh read from a file does not pass through itself: no two triangles that
// share no node may cross (etfe/kernels/tri_intersect.h says what counts: interiors crossing by
// more than 1e-6 of the mean edge length; touching at a vertex or along an edge does not). Run
// on rank 0 by ReadMeshFile before the mesh is distributed. PETSc-free.
//
// Coplanar overlap: two layers lying flat on each other are the start of a cushion inflated from
// flat, so coplanar triangles of different element groups (no group in common) may overlap;
// overlap within one group (or of triangles in no group) is a fold lying on itself and refused.
// A broad phase on a uniform grid of cells about twice the mean bounding-box size keeps it near
// linear in the number of triangles.
#pragma once
#include <string>

#include "etfe/mesh/mesh_data.h"

namespace etfe {

// True when no two triangles cross; else false with a message naming the two triangles (with
// their file tags), a point of the crossing, and the way out. A mesh with bad node ids passes
// (MeshCheck refuses it with its own message).
bool MeshCheckIntersections(const MeshData &mesh, std::string *err);

// Whether ReadMeshFile runs MeshCheckIntersections (-mesh_check_intersections, read by
// MeshCadSizeFromOptions with the other options of a mesh file; default on).
void SetMeshIntersectionCheck(bool on);
bool MeshIntersectionCheck();

} // namespace etfe
