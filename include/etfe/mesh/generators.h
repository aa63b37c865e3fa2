// Structured mesh generators for the scenes (any density by option). PETSc-free.
#pragma once
#include <cmath>

#include "etfe/mesh/mesh_data.h"

namespace etfe {

enum class DiagonalPattern { Right, Left, Alternate, Crossed };

// The largest mesh a generator makes, in triangles: far past what runs on a workstation, and far
// below an int overflow in the generators' index arithmetic. Scenes check their -mesh_* options
// against it before generating.
constexpr double kMaxGeneratedTriangles = 16777216.0;  // 2^24

// Triangles of an n1 x n2 cell mesh with triangles_per_cell each, refined `refine` times (each
// doubles n1 and n2); computed in double so that no option value can overflow it.
inline double GeneratedTriangles(double n1, double n2, double triangles_per_cell, double refine) {
  return n1 * n2 * triangles_per_cell * std::pow(4.0, refine);
}

// Rectangle [x0, x0+lx] x [y0, y0+ly] in the plane z = 0 with nx x ny cells, each split into two
// triangles (four with Crossed: a centre node per cell). perturb moves interior nodes randomly
// by up to perturb * cell size (deterministic, seed) to make irregular meshes for patch tests.
// Node sets: left, right, bottom, top, corner_ll, corner_lr, corner_ul, corner_ur, all.
MeshData MakeRectangleMesh(double x0, double y0, double lx, double ly, int nx, int ny,
                           DiagonalPattern pattern, double perturb, unsigned seed);

// Disc of radius r centred at the origin in z = 0 with `rings` rings of nodes (ring i has 6 i
// nodes): 6 rings^2 triangles of near-equal size. Node sets: rim, centre, all.
MeshData MakeDiscMesh(double radius, int rings);

// Annulus a <= r <= b centred at the origin in z = 0: rings 0..nr of nt nodes each (ring 0 at the
// hub), alternating diagonals. Node sets: hub (r = a), outer (r = b), all.
MeshData MakeAnnulusMesh(double a, double b, int nr, int nt);

// Strip of width `width` laid stress free on the cylinder of radius r around the Y axis over the
// wrap angle theta [rad], symmetric about +Z (the capstan rig): the rectangle of nx x ny cells
// (length r theta along the wrap, y across, alternating diagonals) bent onto it. Node sets as
// the rectangle's: left (end A, at -theta/2), right (end B), bottom, top, corners, all.
MeshData MakeWrappedStripMesh(double radius, double theta, double width, int nx, int ny);

// Tube (open cylinder) of radius r around the Z axis, z in [z0, z0 + length], ntheta cells
// around (periodic seam) and nz along, diagonals alternating. Node sets: bottom (z = z0),
// top, middle (the ring at mid height when nz is even), all.
MeshData MakeTubeMesh(double radius, double z0, double length, int ntheta, int nz);

} // namespace etfe
