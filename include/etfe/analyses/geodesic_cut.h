// Strips of a given width cut by seams (-cutpattern_strip_width): each physical surface (or all
// the triangles when there is none) is cut by straightest geodesics (etfe/kernels/geodesic.h)
// or plane sections (layout 1) into strips, which -analysis cutpattern then flattens.
//
// The lines: a transverse geodesic is traced through the surface's middle (the interior node
// nearest its area centroid) across the strip direction, both ways to the boundary; the first
// cutting line is the geodesic through that node along the strip direction; the others cross the
// transverse geodesic at arc lengths k W (k = +-1, +-2, ...) from the middle, at right angles to
// it, while at least W/4 is left to the boundary; each is traced both ways until it leaves the
// surface. So the strips are W wide on the transverse geodesic (the two edge strips take what is
// left: W/4 to 5W/4); away from it they widen or narrow as the surface's curvature makes
// geodesics part or meet (Gaussian curvature K < 0 or > 0; exactly W on a developable surface).
// With `equal`, n lines instead split the transverse geodesic into n + 1 equal parts at most W.
// Plane sections (layout 1) pass through the same points, normal to the transverse direction at
// the middle. The lines are inserted into the mesh as conforming seams (edge splits at the
// crossings, nodes within `snap` of an edge's length moved onto them: etfe/kernels/geodesic.h),
// the pieces between them are the strips <name>_01, <name>_02, ... in order
// across, and the edges two strips share become cut_<a>_<b> in CutPatternPrepareSurface.
#pragma once
#include <string>
#include <vector>

#include "etfe/mesh/mesh_data.h"

namespace etfe {

struct GeodesicCutOptions {
  double width = 0.0;  // W, mm; 0 = off (strips from the physical groups)
  int direction = 0;   // the cutting lines' direction at the middle: 0 x, 1 y, 2 z
  // Crossings within this fraction of an edge's length go to its node. Measured on saddles
  // (z = c (x^2 - y^2), 24 and 48 cells across, W 100..200 mm): 0.1 left triangles of quality
  // 0.08 that folded one strip of six in the flattening, 0.2 kept quality >= 0.17 and none folded.
  // Now the fraction within which a mesh node is moved onto the line (the line kept where it
  // was traced); only a node that may not move (boundary, named line, another seam) or whose
  // move would spoil its triangles still takes the line to it (the old snap).
  double snap = 0.2;
  double tol = -1.0;          // mm: crossings this near a node go to it (< 0: 1e-3 x the mean edge)
  double keep_quality = 0.5;  // a moved node's triangles keep this fraction of their smallest quality
  int layout = 0;  // 0: geodesics, 1: plane sections parallel to the strip direction, 2: radial gores
  bool whole_if_narrow = false;  // a surface not wider than `width` is one strip (else refused)
  // Strips of equal width on the transverse geodesic, as few as keep them at most `width` wide
  // (else: a line through the middle, then W apart, the edge strips taking what is left).
  bool equal = false;
  // A 1-D physical group (-cutpattern_strip_start, geodesic layout): the first seam is the
  // geodesic started at the group's middle node (the node nearest half its length) along the
  // group's segment there, instead of the surface's middle along `direction`; the other seams
  // start at right angles across the transverse geodesic through that node, as from the middle.
  // Empty: the surface's middle. Only the surface holding that node is started there.
  std::string start_line;
};

// Replaces *mesh by the cut mesh with one element set per strip: each physical surface (or the
// whole mesh when it has none) is cut on its own, strips <surface>_NN (strip_NN without groups);
// nodes two surfaces share and nodes of named lines stay where they are. False with a message
// naming the option for: overlapping physical surfaces, a width below the mean edge length or wider than
// the surface, a direction normal to the surface, a line that does not reach the boundary
// (a closed or winding surface), lines that meet or cross, a start line that is no 1-D group,
// has a node on no triangle or whose middle node lies on the boundary.
bool GeodesicCutStrips(MeshData *mesh, const GeodesicCutOptions &o, std::vector<std::string> *notes,
                       std::string *err);

} // namespace etfe
