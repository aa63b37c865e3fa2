// The -mesh_* options of every scene (see mesh_options.h).
#include "etfe/mesh/mesh_options.h"

#include <cmath>
#include <string>

#include "etfe/mesh/cad_reader.h"
#include "etfe/mesh/self_intersection.h"

namespace etfe {

namespace {

const char *const kPatternNames[] = {"right", "left", "alternate", "crossed"};
const DiagonalPattern kPatterns[] = {DiagonalPattern::Right, DiagonalPattern::Left, DiagonalPattern::Alternate,
                                     DiagonalPattern::Crossed};

} // namespace

PetscErrorCode MeshOptionsFromCommandLine(MPI_Comm comm, const char *owner, MeshOptions *o) {
  char file[PETSC_MAX_PATH_LEN], pattern[32] = "";
  const char *default_pattern = "";  // the defaults apart from the buffers read into: -help shows both
  PetscFunctionBeginUser;
  PetscCall(PetscStrncpy(file, o->file.c_str(), sizeof file));
  for (int k = 0; k < 4; ++k)
    if (kPatterns[k] == o->pattern) default_pattern = kPatternNames[k];
  PetscCall(PetscStrncpy(pattern, default_pattern, sizeof pattern));
  const std::string title = std::string("Mesh of the ") + owner;
  PetscOptionsBegin(comm, nullptr, title.c_str(), "Mesh");
  if (o->keys & kMeshFile)
    PetscCall(PetscOptionsString("-mesh_file",
                                 "Gmsh mesh (.msh) instead of the generated one: patch, a flat rectangle with node "
                                 "sets left, right, bottom, top; saddle, a surface such as a form-found .msh; "
                                 "-analysis cutpattern, the strips as physical surfaces (OBJ groups / STL solids: "
                                 "convert with scripts/surface2msh); a CAD surface (.step, .stp, .iges, .igs, .brep) "
                                 "is meshed by Gmsh at -mesh_cad_size",
                                 "", o->file.c_str(), file, sizeof file, nullptr));
  if (o->keys & kMeshGrid) {
    PetscCall(PetscOptionsInt("-mesh_nx", "Grid cells along the length (patch: in X; capstan: along the wrap)", "",
                              o->nx, &o->nx, nullptr));
    PetscCall(PetscOptionsInt("-mesh_ny", "Grid cells across (patch: in Y; capstan: across the strip)", "", o->ny,
                              &o->ny, nullptr));
  }
  if (o->keys & kMeshPerQuarter)
    PetscCall(PetscOptionsInt("-mesh_n", "Cells per 1000 mm (saddle quarter: 2n x n cells)", "", o->n, &o->n,
                              nullptr));
  if (o->keys & kMeshRings)
    PetscCall(PetscOptionsInt("-mesh_rings",
                              "Element rings from the centre or hub to the outer edge (hencky disc: 6 rings^2 "
                              "triangles)",
                              "", o->rings, &o->rings, nullptr));
  if (o->keys & kMeshSectors)
    PetscCall(PetscOptionsInt("-mesh_sectors", "Elements around (two triangles each per ring)", "", o->sectors,
                              &o->sectors, nullptr));
  if (o->keys & kMeshTube) {
    PetscCall(PetscOptionsInt("-mesh_ntheta", "Cells around the axis", "", o->ntheta, &o->ntheta, nullptr));
    PetscCall(PetscOptionsInt("-mesh_nz", "Cells along the axis (even)", "", o->nz, &o->nz, nullptr));
  }
  if (o->keys & kMeshRefine)
    PetscCall(PetscOptionsInt("-mesh_refine", "Double the generated mesh's density this many times", "", o->refine,
                              &o->refine, nullptr));
  if (o->keys & kMeshIrregular) {
    PetscCall(PetscOptionsReal("-mesh_perturb", "Random interior node shift, fraction of a cell", "", o->perturb,
                               &o->perturb, nullptr));
    PetscCall(PetscOptionsString("-mesh_pattern", "Diagonals: right, left, alternate, crossed", "", default_pattern,
                                 pattern, sizeof pattern, nullptr));
  }
  PetscOptionsEnd();
  o->file = file;
  if (o->keys & kMeshIrregular) {
    int k = 0;
    while (k < 4 && std::string(pattern) != kPatternNames[k]) ++k;
    PetscCheck(k < 4, comm, PETSC_ERR_ARG_UNKNOWN_TYPE, "-mesh_pattern %s: use right, left, alternate or crossed",
               pattern);
    o->pattern = kPatterns[k];
  }
  PetscFunctionReturn(0);
}

PetscErrorCode MeshCadSizeFromOptions(MPI_Comm comm, const char path[], double *size) {
  PetscBool help = PETSC_FALSE;
  PetscBool check = MeshIntersectionCheck() ? PETSC_TRUE : PETSC_FALSE;
  PetscFunctionBeginUser;
  *size = 0.0;
  PetscOptionsBegin(comm, nullptr, "Mesh file checks", "Mesh");
  PetscCall(PetscOptionsBool("-mesh_check_intersections",
                             "Refuse a mesh file whose surface passes through itself (two triangles without a "
                             "common node crossing); false skips the check (it takes about a second per 10^6 "
                             "triangles)",
                             "", check, &check, nullptr));
  PetscOptionsEnd();
  SetMeshIntersectionCheck(check == PETSC_TRUE);
  PetscCall(PetscOptionsHasHelp(nullptr, &help));
  if (!IsCadFile(path) && !help) PetscFunctionReturn(0);
  PetscOptionsBegin(comm, nullptr, "CAD surface of -mesh_file, meshed by Gmsh", "Mesh");
  PetscCall(PetscOptionsReal("-mesh_cad_size",
                             "Target element size [mm] when -mesh_file is a CAD surface (STEP, IGES, BREP); 0: 1/50 "
                             "of the model's bounding-box diagonal",
                             "", *size, size, nullptr));
  PetscOptionsEnd();
  PetscCheck(*size >= 0 && std::isfinite(*size), comm, PETSC_ERR_ARG_OUTOFRANGE,
             "-mesh_cad_size %g: give the target element size in mm (> 0), or 0 for 1/50 of the model's extent",
             *size);
  PetscFunctionReturn(0);
}

} // namespace etfe
