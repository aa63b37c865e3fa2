// Cutting patterns of a surface (SPEC §7, issue 5): the surface is split into strips (element
// sets: the saddle's "middle" and "corner" parts, split at the cutting line X = 0 and the weld
// line over the arch), each strip is flattened by least squares of its link lengths
// (flatten_strip.h) and written as DXF, SVG and a Gmsh .msh (the 2D mesh for a stretch
// analysis), with a table of its named lines (cut_*, weld_*, and -cutpattern_lines) in 3D and 2D.
#pragma once
#include <petscsys.h>

#include <string>
#include <vector>

#include "etfe/flatten_strip.h"
#include "etfe/mesh/mesh_data.h"

namespace etfe {

struct CutPatternOptions {
  PetscBool enabled = PETSC_FALSE;
  std::vector<std::string> strips;  // element sets to flatten (empty: every set but "all")
  FlattenOptions flatten;
};

PetscErrorCode CutPatternOptionsFromCommandLine(MPI_Comm comm, CutPatternOptions *o);
// shape: the 3D surface (valid on rank 0). Writes <dir>/<stem>_<strip>.{dxf,svg,msh} and
// <dir>/<stem>_lines.csv; prints one line per named line. Collective.
PetscErrorCode CutPatternRun(MPI_Comm comm, const MeshData &shape, const CutPatternOptions &o,
                             const std::string &dir, const std::string &stem);

} // namespace etfe
