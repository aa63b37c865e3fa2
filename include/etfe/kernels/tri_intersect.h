// Whether two triangles in space pass through each other: the narrow phase of the mesh's
// self-intersection check (src/mesh/self_intersection.cpp). PETSc-free.
//
// Only the interiors count. Triangles that touch at a vertex, along an edge, or where one's edge
// or vertex lies on the other without going through it, are not crossing: separate layers of a
// cushion meet so along their rim. Everything within `tol` (a length, e.g. 1e-6 of the element
// size) is taken as touching.
#pragma once

namespace etfe {

enum class TriContact {
  None,      // apart, or touching only (within tol)
  Cross,     // the interiors cross along a segment longer than tol; *point is on it
  Coplanar,  // both in one plane (within tol) and overlapping by more than tol times their size
};

// a, b: the three corners of each triangle (9 numbers, x y z per corner). point: 3 numbers, set
// for Cross and Coplanar (a point of the common part). Degenerate triangles give None.
TriContact TriangleContact(const double a[9], const double b[9], double tol, double point[3]);

} // namespace etfe
