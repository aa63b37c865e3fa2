// The -mesh_* options, read in one place for every scene (as DMSetFromOptions reads -dm_refine):
// each key has one help text here; a scene says which keys its mesh takes and sets their defaults
// before the call, so -help shows the scene's own defaults and a key the scene does not take stays
// unread (the app then reports it as not used by this configuration).
#pragma once
#include <petscsys.h>

#include <string>

#include "etfe/mesh/generators.h"

namespace etfe {

// The keys a scene's mesh takes (bits of MeshOptions::keys).
enum MeshOptionKey : unsigned {
  kMeshFile = 1u << 0,       // -mesh_file
  kMeshRefine = 1u << 1,     // -mesh_refine
  kMeshGrid = 1u << 2,       // -mesh_nx, -mesh_ny
  kMeshPerQuarter = 1u << 3, // -mesh_n
  kMeshRings = 1u << 4,      // -mesh_rings
  kMeshSectors = 1u << 5,    // -mesh_sectors
  kMeshTube = 1u << 6,       // -mesh_ntheta, -mesh_nz
  kMeshIrregular = 1u << 7,  // -mesh_perturb, -mesh_pattern
};

struct MeshOptions {
  unsigned keys = 0;  // MeshOptionKey bits: what the scene's mesh takes
  std::string file;   // -mesh_file: a Gmsh mesh instead of the generated one ("": generate)
  PetscInt refine = 0;
  PetscInt nx = 0, ny = 0;          // grid cells along and across
  PetscInt n = 0;                   // cells per 1000 mm (the saddle)
  PetscInt rings = 0, sectors = 0;  // disc and annulus
  PetscInt ntheta = 0, nz = 0;      // tube: around and along the axis
  double perturb = 0.0;
  DiagonalPattern pattern = DiagonalPattern::Alternate;
};

// Reads the keys o->keys names, o's values being the defaults; owner names the scene (or
// analysis) in the -help section title, so every scene's mesh keys are listed.
PetscErrorCode MeshOptionsFromCommandLine(MPI_Comm comm, const char *owner, MeshOptions *o);

// -mesh_cad_size (mm): the target element size when the mesh file `path` is a CAD surface
// (etfe/mesh/cad_reader.h), which Gmsh meshes; 0 (the default) leaves it to the reader (1/50 of
// the model's extent). Read only for a CAD file (and listed by -help), so a .msh leaves it unused.
// Also reads -mesh_check_intersections (any mesh file) into SetMeshIntersectionCheck.
PetscErrorCode MeshCadSizeFromOptions(MPI_Comm comm, const char path[], double *size);

} // namespace etfe
