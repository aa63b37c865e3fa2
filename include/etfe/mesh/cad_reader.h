// CAD surfaces (STEP, IGES, BREP) meshed into a MeshData by Gmsh's own C++ API: the way a
// designer's model goes in without a hand-made mesh. PETSc-free.
//
// The Gmsh API is optional. When CMake finds it (libgmsh-dev: gmsh.h and libgmsh), the meshing
// is built as a module of its own (src/mesh/cad_gmsh.cpp, libetfe_cad.so) that ReadCadFile loads
// the first time a CAD file is read: libgmsh brings OpenCASCADE (about 90 shared libraries, some
// 0.1 s and 50 MB to load), which a run that reads no CAD file never loads. Without the API every
// other reader works and a CAD file is refused by CadUnavailableMessage.
//
// What comes out (src/mesh/cad_gmsh.cpp does it):
//   * STEP and IGES lengths are converted to mm by OpenCASCADE (Geometry.OCCTargetUnit); a BREP
//     file has no unit and is taken as mm.
//   * Coincident edges and points of different faces are fused (an OCC fragment of everything
//     imported), so faces that meet along an edge give one conforming mesh; a free curve lying on
//     a face becomes a line of nodes in its mesh.
//   * Every face is meshed with 3-node triangles (mesh order 1, recombination off) at a target
//     element size (mm); size <= 0 takes 1/50 of the model's bounding-box diagonal.
//   * Groups: Gmsh 4.8 keeps a STEP file's product names as entity names
//     ("Shapes/<assembly>/<n>/<name>") and makes no physical groups of them. A face carrying a
//     name goes into the element set and node set named by its last path part (characters other
//     than letters, digits, '_', '.', '-' become '_'; faces of one name share the set); a face
//     without a name of its own takes that of its solid (a cushion drawn as a closed body); a
//     face without either goes into "surface_<tag>". So the element sets partition the film (the cutting
//     patterns take them as strips). Every curve tag c and point tag p give the node sets
//     "curve_<c>" and "point_<p>". Tags are Gmsh's after the fusion. Names of STEP faces
//     themselves (ADVANCED_FACE) and of curves are not read by Gmsh 4.8, and IGES and BREP carry
//     none: those are addressed by their tags.
//   * MeshData::notes say the size used, how it was chosen, the groups made and the fusion.
#pragma once
#include <string>

#include "etfe/mesh/mesh_data.h"

namespace etfe {

// Whether the file name ends in .step, .stp, .iges, .igs or .brep (any case).
bool IsCadFile(const std::string &path);

// Whether this build can mesh CAD files (it found the Gmsh API at configure time).
bool CadMeshingBuiltIn();

// The refusal of a CAD file by a build without the Gmsh API: names the file and the way out.
std::string CadUnavailableMessage(const std::string &path);

// Whether `head`, the first bytes of the file `path`, looks like what the name says (.step/.stp:
// "ISO-10303-21;"; .iges/.igs: 80-column records with the section letter in column 73; .brep:
// "DBRep_DrawableShape" or "CASCADE Topology"): "" if so, else a message naming the file, what
// was expected and what was found. ReadCadFile refuses such a file before Gmsh sees it.
std::string CadContentProblem(const std::string &path, const std::string &head);

// Meshes the CAD file at the target element size (mm; <= 0: the default above). Returns false
// with a message naming the file on failure (no Gmsh API in this build, the module not found,
// a file Gmsh cannot read, no surface in it). Gmsh is initialized and finalized within the call
// (the process locale is restored after), so call it on one rank only.
bool ReadCadFile(const std::string &path, double size, MeshData *mesh, std::string *err);

// Reads a mesh file by its name: a CAD file through ReadCadFile at cad_size, anything else
// through ReadGmshFile; then, unless -mesh_check_intersections false, MeshCheckIntersections
// (etfe/mesh/self_intersection.h) refuses a surface that passes through itself.
bool ReadMeshFile(const std::string &path, double cad_size, MeshData *mesh, std::string *err);

} // namespace etfe
