// Geometry of the thesis's saddle (docs/theory.md §13), shared by its form-finding and stretch
// set-ups.
#pragma once
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <petscsys.h>

#include "etfe/scenes/scene_registry.h"

namespace etfe {

struct SaddleGeometry {
  double half_length = 2000.0;  // X extent of the quarter (frame at X = 2000)
  double arch_x = 1000.0;       // arch plane
  double half_span = 1000.0;    // Y extent (frame at Y = 1000), arch span L = 2 half_span
  double rise = 300.0;          // H
  double ArchRadius() const { return (half_span * half_span + rise * rise) / (2.0 * rise); }
  double ArchHeight(double y) const {
    const double r = ArchRadius();
    return rise - r + std::sqrt(std::max(0.0, r * r - y * y));
  }
  // PD initial shape: arch extruded in the middle, ruled down to the frame in the corner.
  double InitialHeight(double x, double y) const {
    const double za = ArchHeight(y);
    return x <= arch_x ? za : za * (half_length - x) / (half_length - arch_x);
  }
};

// Where the saddle's shape is measured (thesis L1866, Fig. 5.22, whose drawing is lost; heights
// above the frame plane z = 0): h1 at the middle part's centre (X = 0, Y = 0), h2 at the corner
// part's centre (X midway between the arch and the frame, Y = 0), the middle cutting line X = 0
// (node set sym_x, by Y). Shared by the form-finding and the stretch reports.
struct SaddleShapeNodes {
  PetscInt centre = -1, corner = -1;
  std::vector<PetscInt> cut_line;
  double h1_start = 0.0, h2_start = 0.0;  // the initial surface's heights there (the mesh's Z)
};
// Finds them on the distributed problem (collective; an observer's setup).
PetscErrorCode SaddleShapeNodesFind(Problem *P, const SaddleGeometry &g, SaddleShapeNodes *n);
// Prints h1, h2, the middle sag (rise H - h1) and curvature, and the middle cutting line at the
// current displacement (collective). start: also h1, h2 of the initial surface and the change.
PetscErrorCode SaddleShapeReport(Problem *P, const SaddleGeometry &g, const SaddleShapeNodes &n, bool start);

// The stretch report's probes (structure_check_saddle.cpp), by default the thesis's: parts A
// (the middle part's centre) and B (the corner part's), plan boxes x0, y0, x1, y1 whose elements'
// mean strains and Mises are reported; elements I and II (nearest to plan points); the arch
// slide points I-V (Y on the arch).
struct SaddlePlanBox {
  double x0, y0, x1, y1;
  bool Contains(double x, double y) const { return x >= x0 && x <= x1 && y >= y0 && y <= y1; }
};
struct SaddleStretchProbes {
  SaddleGeometry g;
  SaddlePlanBox part_a{0, 0, 400, 400}, part_b{1300, 0, 1700, 400};
  double elem_i_at[2] = {200, 200}, elem_ii_at[2] = {500, 700};  // probe positions (plan)
  std::vector<double> slide_at = {0, 250, 500, 750, 950};        // Y of the slide points I..V on the arch
  std::string history;                 // its CSV ("": beside the results)
  // Found at set-up on the distributed mesh:
  PetscInt elem_i = -1, elem_ii = -1;  // scene element ids
  std::vector<PetscInt> slide_nodes;   // arch nodes I..V
  std::vector<double> slide_y;         // their Y on the initial surface
  std::vector<char> in_a, in_b;        // per local element
  SaddleShapeNodes shape;              // heights h1, h2 and the middle cutting line (saddle.cpp)
};

// Stretch fabrication (-analysis stretch, saddle_stretch.cpp): the -saddle_* options as the general
// scene's drawing of the frame at a, b, c, d, symmetry, arch contact, optional pressure cycle and
// -structure_check saddle_stretch. The mesh (PD initial shape or a form-found DD shape) and its
// node sets are already in scene.

PetscErrorCode SaddleStretchSetup(MPI_Comm comm, const SaddleGeometry &g, SceneSpec *scene, SceneObserver *observer);

} // namespace etfe
