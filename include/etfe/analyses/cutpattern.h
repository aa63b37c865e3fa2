// Cutting patterns of a surface (docs/theory.md §9): the surface is split into strips (element
// sets: the saddle's "middle" and "corner" parts, split at the cutting line X = 0 and the weld
// line over the arch), each strip is flattened by least squares of its link lengths
// (flatten_strip.h) and written as DXF, SVG and a Gmsh .msh (the 2D mesh for a stretch
// analysis), with a table of its named lines (cut_*, weld_*, and -cutpattern_lines) in 3D and 2D.
#pragma once
#include <petscsys.h>

#include <map>
#include <string>
#include <vector>

#include "etfe/analyses/flatten_strip.h"
#include "etfe/analyses/geodesic_cut.h"
#include "etfe/mesh/mesh_data.h"

namespace etfe {

// Compensation (etfe/kernels/compensation.h): the pattern is cut smaller so that the
// film drawn back to the design shape carries the design prestress. MD is the pattern's long
// axis (x of the DXF), TD across it.
enum class Compensation { None, Uniform, Stress };

struct CutPatternOptions {
  PetscBool enabled = PETSC_FALSE;
  std::vector<std::string> strips;  // element sets to flatten (empty: every set but "all")
  FlattenOptions flatten;
  Compensation compensation = Compensation::None;
  double comp_md = 0.0, comp_td = 0.0;  // uniform: engineering strains the film is drawn by
  double prestress[3] = {0.0, 0.0, 0.0};  // stress: S_MD, S_TD, S_MD-TD (PK2, MPa)
  bool prestress_given = false;           // -cutpattern_prestress was given (it then wins)
  double young = 0.0, nu = 0.0;           // stress: the material's elastic constants
  // Stress compensation from a computed stress (form finding) when no -cutpattern_prestress is
  // given: per element of the surface S_MD, S_TD, S_MD-TD in the element's own frame (md_axis
  // projected on it). element_stress says the caller provides it (filled on rank 0 only).
  bool element_stress = false;
  std::vector<double> element_prestress;
  double md_axis[3] = {1.0, 0.0, 0.0};
  // The drawings (DXF, SVG): a weld/seam allowance outline and the MD (roll) direction mark.
  double seam_allowance = 0.0;  // mm
  PetscBool md_mark = PETSC_TRUE;
  // Roll nesting (-cutpattern_roll_width, 0: none): every strip on a roll this wide, gap apart.
  double roll_width = 0.0, roll_gap = 10.0;  // mm
  // The first-yield strain S_y1 / E of the film (0: none known), above which a fabrication error
  // is warned about, and where it came from.
  double first_yield_strain = 0.0;
  std::string first_yield_source;
};

PetscErrorCode CutPatternOptionsFromCommandLine(MPI_Comm comm, CutPatternOptions *o);
// The sub-mesh of one element set (a strip), nodes renumbered in order of first use, with every
// node set restricted to it.
MeshData ExtractStrip(const MeshData &m, const std::vector<int> &elements, const std::string &name);
// The name of a compensation kind as the option spells it ("none", "uniform", "stress").
const char *CompensationName(Compensation c);
// Flattens the element set `name` of shape into *r (*strip: the strip as a mesh of its own), or
// takes its flattening from *flattened when that has it (a roll fit's last try; may be null);
// with compensation, the design pattern first (its axes define MD/TD) into *design, then the
// pattern of the compensated link lengths. Stress compensation needs o.prestress_given or
// o.element_prestress. Serial (rank 0 of a scene). False with a message.
bool FlattenNamedStrip(const MeshData &shape, const std::string &name, const CutPatternOptions &o,
                       const std::map<std::string, FlattenResult> *flattened, MeshData *strip, FlattenResult *r,
                       FlattenResult *design, std::string *err);
// shape: the 3D surface (valid on rank 0). Writes <dir>/<stem>_<strip>.{dxf,svg,msh},
// <dir>/<stem>_lines.csv, <dir>/<stem>_errors.csv (pattern_errors.h) and, with a roll width,
// <dir>/<stem>_nesting.{dxf,svg}; prints one line per named line and edge, warns of errors above
// the first-yield strain and prints the roll length and waste. flattened (rank 0, may be null):
// strips already flattened with o.flatten (uncompensated), by name, used instead of flattening
// them again (the roll fit's last try). Collective.
PetscErrorCode CutPatternRun(MPI_Comm comm, const MeshData &shape, const CutPatternOptions &o,
                             const std::string &dir, const std::string &stem,
                             const std::map<std::string, FlattenResult> *flattened = nullptr);

// -analysis cutpattern (cutpattern_surface.cpp): the strips of any surface mesh.
struct CutPatternSurfaceOptions {
  std::string mesh_file;     // -mesh_file: Gmsh surface, physical surfaces = strips
  double cad_size = 0.0;     // -mesh_cad_size: element size when mesh_file is a CAD surface (mm)
  std::string results_path;  // -output_file: the pattern files go beside it, named by its stem
  CutPatternOptions cutpattern;
  GeodesicCutOptions geodesic;  // -cutpattern_strip_width/_direction/_layout: strips cut by seams
  // -cutpattern_strip_fit_roll: the strip width chosen so that every flattened strip, with the
  // seam allowance on both sides, fits -cutpattern_roll_width.
  PetscBool fit_roll = PETSC_FALSE;
  bool width_given = false;  // -cutpattern_strip_width given (the fit then starts from it)
};
// The least width of a set of plane points (x, y pairs): across the narrowest caliper of their
// convex hull (mm).
double PatternLeastWidth(const std::vector<double> &xy);
PetscErrorCode CutPatternSurfaceOptionsFromCommandLine(MPI_Comm comm, CutPatternSurfaceOptions *o);
// Reads and checks the mesh on rank 0, then CutPatternRun. Collective.
PetscErrorCode CutPatternSurfaceRun(MPI_Comm comm, const CutPatternSurfaceOptions &o);
// The strips of a surface (PETSc-free): every element set (or only those named in `only`, when
// given) must be a disc (connected, manifold, one boundary loop) and the sets must not overlap;
// adds a node set cut_<a>_<b> for the edges strips a and b share (unless the file names one
// so). Notes say what was added.
bool CutPatternPrepareSurface(MeshData *mesh, const std::vector<std::string> &only,
                              std::vector<std::string> *notes, std::string *err);

} // namespace etfe
