// Cutting patterns: flattening of one strip of the form-found surface (docs/theory.md §9.1, thesis
// §2.3).
//
// Every mesh edge is a "link" whose plane length l_i should equal its 3D length L_i. The plane
// node positions x minimise S(x) = sum_i w_i (l_i(x) - L_i)^2 (thesis eq. 2.23) by Gauss-Newton:
// K dx = R with K = A^T W A, R = -A^T W C (eqs. 2.29-2.31), assembled link by link like truss bars
// (eqs. 2.32-2.33, kernel etfe/kernels/flatten_link.h). Boundary links (edges of one triangle)
// weigh 1e12 so the cut and weld lines keep their length; interior links weigh 1. The rigid
// motion is removed by fixing one node and the y of a second node. By default the step adds
// the second-order terms of the boundary links and the boundary weight grows in stages (see
// FlattenOptions); second_order = 0 with weight_growth = 0 is the thesis' plain Gauss-Newton.
// The expansion of a line is (L2D - L3D) / L3D * 100 % (thesis Fig. 2.10).
//
// FlattenStrip runs serially (PETSc objects on PETSC_COMM_SELF, MATSEQAIJ + LU), so every rank
// of an MPI run may call it on its own strips; PETSc must be initialised.
#pragma once
#include <string>
#include <vector>

#include "etfe/mesh/mesh_data.h"

namespace etfe {

struct FlattenOptions {
  double boundary_weight = 1e12;  // w of links with one adjacent triangle (thesis §2.4.2)
  double interior_weight = 1.0;   // w of links between two triangles
  int max_iterations = 300;       // all stages together, before reporting non-convergence
  // The step: 0 = Gauss-Newton, K = A^T W A (thesis eq. 2.29); 1 = plus the second-order terms
  // w_i phi_i d2l_i/dx2 of the boundary links; 2 = plus those of all links (Newton). Any order
  // falls back to Gauss-Newton in an iteration where its step does not descend. All end at a
  // minimum of S; they differ in how fast (and, for strongly curved strips, at which one).
  // Measured on sphere and saddle strips 1200 mm long (R 400..2000 mm, widths 400 and 800 mm,
  // 25 mm mesh): order 1 with weight stages flattened 15 of 20 (the other 5 fold over, as
  // they should at up to 47 % link distortion), in 19-58 iterations but one (151); order 2
  // folded 3 of those 15 into a worse minimum; plain Gauss-Newton without stages flattened 9,
  // folded 1 and ran out of 300 iterations on the other 10.
  int second_order = 1;
  // Continuation of the boundary weight: stages interior_weight * weight_growth^k, ending at
  // boundary_weight, each started from the previous solution. With a large weight the
  // boundary links are near-constraints whose force w phi is not small, so a start far from
  // them gives Newton an indefinite K and Gauss-Newton slow linear convergence; the stages
  // keep every start close. weight_growth <= 1: one stage at boundary_weight (the thesis).
  double weight_growth = 100.0;
  // Converged when the largest nodal step is below step_rtol * (mean 3D link length) and S has
  // settled: |S_k - S_{k-1}| <= s_rtol * S_{k-1}, or S <= s_atol * sum_i w_i L_i^2 (an exact
  // development ends at round-off, where the relative change of S is noise). Stages before
  // the last stop at the looser stage_step_rtol.
  double step_rtol = 1e-10;
  double stage_step_rtol = 1e-6;
  double s_rtol = 1e-12;
  double s_atol = 1e-26;
  // 3D links shorter than this times the mean link length are rejected as degenerate input.
  double min_link_rel = 1e-9;
  // Named lines to measure: the node sets listed here (each must exist) plus every node set
  // whose name starts with one of the prefixes.
  std::vector<std::string> line_sets;
  std::vector<std::string> line_prefixes = {"cut_", "weld_"};
  // Target plane lengths per link, in the order of FlattenResult::links of the same strip
  // (compensation): when given, the links fit these instead of their 3D lengths.
  // The lines' length3d stays the 3D (design) length; link_error is against the target.
  std::vector<double> link_target;
  // A strip whose whole outline lies in one plane (a film cut to a plane frame: a cushion's foil)
  // keeps it: the outline nodes stay where they are in that plane and only the interior is
  // flattened (its links fit as above). The outline's 3D lengths are then kept exactly, as the
  // boundary weight aims to, and so is its shape: a free flattening of a lifted foil (a cushion's
  // start lens) bows the frame's straight sides outward to give the longer interior links room,
  // a pattern larger than the frame. Planar: every outline node within outline_plane_rtol times
  // the outline's largest distance from its centroid of the outline's best-fit plane, and the
  // strip's projection onto that plane without folds (a graph over the frame's plane);
  // otherwise, with link_target given (compensation: the outline's targets are not its 3D
  // place), or with hold_planar_outline false, the free flattening.
  bool hold_planar_outline = true;
  double outline_plane_rtol = 1e-6;
};

// A named line: the polyline through the mesh edges whose two nodes are both in the node set.
// Boundary edges are used when the set has any (a cut, weld or frame line); otherwise all mesh
// edges (an interior line, e.g. a centre line).
struct PatternLine {
  std::string name;
  double length3d = 0.0, length2d = 0.0;  // mm
  double expansion_pct = 0.0;             // (length2d - length3d) / length3d * 100
  bool on_boundary = true;
  int segments = 0;
  // One ordered list of node ids per connected piece; a closed piece repeats its first id last.
  std::vector<std::vector<int>> paths;
};

struct FlattenResult {
  // Plane coordinates, 2 per node (mm). The pattern is seen from the side that triangle 0's
  // normal (by its node order) points to, so a consistently oriented mesh gives counter-clockwise
  // triangles; the principal (long) axis lies along x, the bounding box starts at (0, 0).
  std::vector<double> xy;
  std::vector<int> links;              // 2 node ids per link, smaller id first
  std::vector<char> link_on_boundary;  // 1 for boundary links
  std::vector<double> link_length3d;   // L_i, mm (the target with FlattenOptions::link_target)
  std::vector<double> link_error;      // (l_i - L_i) / L_i
  int num_boundary_links = 0;
  std::string initial_guess;  // "projection" (best-fit plane), "unfolding" (triangle by triangle) or
                              // "outline plane" (FlattenOptions::hold_planar_outline)
  bool outline_held = false;  // the outline kept in its plane (FlattenOptions::hold_planar_outline)
  double S_initial = 0.0, S = 0.0;  // eq. 2.23 at the initial guess and at the end, mm^2
  std::vector<double> S_history;    // S after each iteration, at the weights of its stage
  int iterations = 0;               // all stages together
  int stages = 0;                   // boundary weight stages run (FlattenOptions::weight_growth)
  int second_order_steps = 0;       // iterations that took the opt.second_order step
  // The iteration with opt.second_order failed or folded, so the strip was flattened again from
  // the same layout by plain Gauss-Newton (second_order 0): iterations, S and the stages are its.
  bool gauss_newton_retry = false;
  bool converged = false;
  double max_rel_error = 0.0, rms_rel_error = 0.0;  // |l - L| / L over all links
  double max_rel_error_boundary = 0.0, max_rel_error_interior = 0.0;
  double rms_rel_error_interior = 0.0;
  // Boundary loops of node ids (not repeating the first id), interior on the left: outline[0] is
  // the outer loop (largest area), counter-clockwise; holes, if any, are clockwise.
  std::vector<std::vector<int>> outline;
  double outline_length3d = 0.0, outline_length2d = 0.0;  // all loops together, mm
  std::vector<PatternLine> lines;
};

// Flattens strip3d (a connected, manifold triangle mesh: every edge in one or two triangles).
// Returns false with a message in *err for bad input (non-finite or unused nodes, zero-length
// links, non-manifold or disconnected meshes, missing line sets), a singular system, a failed
// line search, a folded pattern or non-convergence within opt.max_iterations; *out then holds
// what was reached (for diagnosis), not a usable pattern.
bool FlattenStrip(const MeshData &strip3d, const FlattenOptions &opt, FlattenResult *out,
                  std::string *err);

// ---- Export (src/analyses/pattern_export.cpp) ---------------------------------------------------

// The drawings (etfe/analyses/pattern_sheet.h has the layers and labels): ASCII DXF R12 (AC1009) with
// $INSUNITS = 4 (mm), closed POLYLINEs on OUTLINE (the cut line: seam_allowance mm outside the
// pattern) and WELD (the pattern's edge), one layer per named line, the MD arrow on MD (when
// md_mark) and, when labels is set, the strip's name and dimensions on TEXT, clear of the outlines.
struct PatternDrawing {
  bool labels = true;
  double seam_allowance = 0.0;
  bool md_mark = false;
};
bool WritePatternDxf(const std::string &path, const FlattenResult &r, const std::string &strip_name,
                     const PatternDrawing &drawing, std::string *err);
inline bool WritePatternDxf(const std::string &path, const FlattenResult &r, const std::string &strip_name, bool labels,
                            std::string *err) {
  PatternDrawing d;
  d.labels = labels;
  return WritePatternDxf(path, r, strip_name, d, err);
}

// SVG 1.1 in mm (width/height in mm, viewBox in mm, y upwards as in the DXF): the DXF's content,
// one group per layer (id = its name in lower case), and a scale bar.
bool WritePatternSvg(const std::string &path, const FlattenResult &r, const std::string &strip_name,
                     const PatternDrawing &drawing, std::string *err);
inline bool WritePatternSvg(const std::string &path, const FlattenResult &r, const std::string &strip_name, bool labels,
                            std::string *err) {
  PatternDrawing d;
  d.labels = labels;
  return WritePatternSvg(path, r, strip_name, d, err);
}

// The outline loop offset outward by d (mm; the interior lies on its left): each vertex moved along
// its corner's bisector to stay d from both edges (at most 4 d at a sharp corner). 2 per point.
std::vector<double> OffsetOutline(const FlattenResult &r, const std::vector<int> &loop, double d);
// The pattern's long axis through its centroid: centre (2) and unit direction (2), and the
// extent along it (mm).
void PatternLongAxis(const FlattenResult &r, double centre[2], double dir[2], double *extent);

// CSV table of the named line lengths of several strips, one row per line plus one row
// "(outline)" per strip: strip,line,on_boundary,pieces,segments,length3d_mm,length2d_mm,
// expansion_pct.
// With compensation result is the compensated pattern (what is cut) and
// uncompensated the design pattern; two more columns then compare them:
// length2d_uncompensated_mm, compensation_pct (without compensation: length2d_mm and 0).
struct PatternTableEntry {
  std::string strip;
  const FlattenResult *result;
  const FlattenResult *uncompensated = nullptr;
};
bool WritePatternLineTable(const std::string &path, const std::vector<PatternTableEntry> &strips,
                           std::string *err);

} // namespace etfe
