// Geodesic cutting lines on a triangle mesh (-cutpattern_strip_width). PETSc-free.
//
// Tracing: "straightest geodesics" (Polthier & Schmies 1998). Inside a triangle the line is
// straight; across an edge it goes on straight in the two triangles unfolded into one plane
// (the direction is turned about the edge from one triangle's plane into the other's); through
// a vertex it leaves so that the total angle theta of the triangles around the vertex is split
// evenly, theta/2 on either side (theta = 2 pi on a flat or developable surface, where this is
// the straight line again). A trace ends where it reaches a boundary edge or boundary vertex.
// On a developable mesh (plane, cylinder, cone) the traced line is exactly a geodesic: its
// flattened image is straight.
//
// Insertion: the traced polyline becomes mesh edges by splitting, in order, every edge it crosses
// at the crossing itself (each triangle on that edge into two, joining the new node to the
// opposite vertex: the children lie in the parent's plane, so the surface and its area do not
// change). So the seam is the traced line, not a path along element edges. Where the line passes
// close to a node (a crossing within `relocate` of an edge's length from it), splitting alone
// would leave slivers; the node is then moved onto the line instead, to that crossing (along the
// edge it lies on, so it stays on the surface), and the line goes through it: its triangles
// change shape (checked: none turns over and their smallest quality keeps `keep_quality` of what
// it was) and the surface moves by at most the move times the angle between the node's
// triangles. A node that may not move (on the boundary where it is not straight, on another
// cutting line, in a named line: TriSurface::fixed) or whose move fails the check keeps its
// place and the line is moved to it instead (the old snap: the seam then steps by at most that
// distance, reported). Where the node's triangles are developable but bent (a cylinder, a cone:
// angles summing to 2 pi), moving it would make the surface non-developable, so it stays and only
// crossings within 0.05 of an edge go to it (the seam steps by at most 5 % of an edge there). Crossings within `tol` mm of a node always go to the node. The polyline's
// segments are marked as cut edges; the strips are the pieces of the mesh between cut edges
// (SurfaceComponents).
//
// Layouts: coords 3 per node (mm); tris 3 node ids per triangle, consistently oriented;
// nbr 3 per triangle: the triangle across edge k (nodes k, k+1 mod 3), -1 on the boundary.
#pragma once
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace etfe {

struct TriSurface {
  std::vector<double> coords;
  std::vector<int> tris;
  std::vector<int> parent;  // the triangle of the input mesh each triangle lies in
  std::vector<int> nbr;     // SurfaceBuildNeighbours
  std::vector<int> vtri;    // SurfaceBuildNeighbours: one triangle holding each node
  std::set<std::pair<int, int>> cut;  // cut edges, (smaller id, larger id)
  // For every node added by a split: the edge (a, b) it was put on.
  std::vector<std::pair<int, int>> new_node_edge;
  // Nodes that must not move onto a cutting line (named lines); empty: none. Grown with the mesh.
  std::vector<char> fixed;
  int NumNodes() const { return (int)(coords.size() / 3); }
  int NumTris() const { return (int)(tris.size() / 3); }
};

// Surface from plain arrays (parent = identity) with neighbours. False with a message for an
// edge in more than two triangles or two neighbours that disagree on orientation.
bool SurfaceFromArrays(const std::vector<double> &coords, const std::vector<int> &tris, TriSurface *s,
                       std::string *err);
bool SurfaceBuildNeighbours(TriSurface *s, std::string *err);
bool SurfaceVertexOnBoundary(const TriSurface &s, int v);

// A point of a traced line: on the edge (a, b), a < b, at a + t (b - a); or at the vertex a
// (b = -1, t = 0). x: its coordinates.
struct SurfacePoint {
  int a = -1, b = -1;
  double t = 0.0;
  double x[3] = {0.0, 0.0, 0.0};
};

struct GeodesicPath {
  std::vector<SurfacePoint> points;  // the crossings after the start, in order
  std::vector<int> segment_tri;      // triangle of the segment ending at points[i]
  std::vector<double> segment_dir;   // 3 per segment: its unit direction
  double length = 0.0;               // mm, from the start to the last point
  int vertices_passed = 0;           // interior vertices passed by the theta/2 rule
  bool reached_boundary = false;     // false: stopped after max_steps crossings
};

// Traces from the point P of triangle tri (on it or inside) in the direction d (projected on the
// triangle's plane; it must point into the triangle where P is on its edge). Stops at the
// boundary or after max_steps crossings (reached_boundary false). False only for bad input
// (zero direction, degenerate triangle) with a message.
bool GeodesicTrace(const TriSurface &s, int tri, const double P[3], const double d[3], int max_steps,
                   GeodesicPath *out, std::string *err);

// The triangle around vertex v whose corner holds the direction d (projected on each triangle's
// plane; the best fit where the corners are not flat): *tri and the unit direction *dir in it.
bool GeodesicStartAtVertex(const TriSurface &s, int v, const double d[3], int *tri, double dir[3]);
// The theta/2 rule at the interior vertex v: ray (a unit direction in triangle tri, leaving v into
// it) turned by half the total angle around v. False at a boundary vertex.
bool GeodesicOppositeAtVertex(const TriSurface &s, int v, int tri, const double ray[3], int *tri_out,
                              double dir_out[3]);
// Total angle of the triangles around v (2 pi on a flat interior vertex).
double SurfaceVertexAngle(const TriSurface &s, int v);

// How a line is inserted (see the top of this file).
struct LineInsertOptions {
  double relocate = 0.2;      // fraction of an edge: a node this near the line is moved onto it
  double tol = 0.0;           // mm: a crossing this near a node goes to the node
  double keep_quality = 0.5;  // a moved node's triangles keep this fraction of their smallest quality
  double quality_floor = 0.0;  // and stay at least this good (moves one after another add up)
  int shared_node = -1;        // a node the line may pass although on another line (radial seams' centre)
};
struct LineInsertStats {
  double line_moved = 0.0;  // mm: the largest distance from a traced point to the node standing for it
  int relocated = 0;        // mesh nodes moved onto the line
  double relocated_max = 0.0;  // mm: the largest such move
  int snapped = 0;          // crossings moved to a node that could not move (beyond tol)
};

// Inserts the polyline (consecutive points in one triangle of s, as GeodesicTrace gives them)
// as cut edges (see the top of this file). *vertices: the line as node ids; *stats may be null.
// False with a message when the line crosses or touches an existing cut line, or crosses one
// triangle twice (the segment is then no edge).
bool SurfaceInsertLine(TriSurface *s, const std::vector<SurfacePoint> &line, const LineInsertOptions &o,
                       std::vector<int> *vertices, LineInsertStats *stats, std::string *err);
// The same with relocate = snap, tol 0; *moved (may be null): stats.line_moved.
bool SurfaceInsertLine(TriSurface *s, const std::vector<SurfacePoint> &line, double snap,
                       std::vector<int> *vertices, double *moved, std::string *err);

// The section of s by the plane n . x = c, as lines from boundary to boundary (each a list of
// crossings in order, as GeodesicTrace gives them; a node on the plane counts on its + side, so
// the line passes it at a crossing next to it, which the insertion takes to the node). Closed
// loops of the section are left out and counted in *loops (may be null).
std::vector<std::vector<SurfacePoint>> SurfacePlaneSection(const TriSurface &s, const double n[3], double c,
                                                           int *loops);

// Turning angle (rad) between consecutive segments of a polyline of nodes of s: the largest.
double PolylineMaxTurn(const TriSurface &s, const std::vector<int> &nodes);

// Pieces of the surface between cut edges (flood fill across the other edges): label per
// triangle, 0..count-1; returns count. Needs the neighbours.
int SurfaceComponents(const TriSurface &s, std::vector<int> *label);

// 4 sqrt(3) A / (l1^2 + l2^2 + l3^2): 1 for an equilateral triangle, 0 for a degenerate one.
double TriangleQuality(const double *x0, const double *x1, const double *x2);
double TriangleArea(const double *x0, const double *x1, const double *x2);
// (x1 - x0) x (x2 - x0) of triangle t by its node order: the normal with length twice the area.
void SurfaceTriangleNormal(const TriSurface &s, int t, double n[3]);

} // namespace etfe
