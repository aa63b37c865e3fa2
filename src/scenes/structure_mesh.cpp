// The general scene's generated meshes (-structure_mesh_generator): the meshes the built-in scenes
// make (src/mesh/generators.cpp) for a case given as options only, with the same -mesh_* keys and
// checks those scenes had. A generated mesh has the generator's node groups (disc: rim, centre,
// all; annulus: hub, outer, all; rectangle: left, right, bottom, top, corner_ll/lr/ul/ur, all) and
// the surface group all.
#include <petscsys.h>

#include <cmath>
#include <string>
#include <vector>

#include "etfe/mesh/generators.h"
#include "etfe/mesh/mesh_options.h"
#include "etfe/scenes/scene_registry.h"
#include "real_array_option.h"
#include "structure_inputs.h"

namespace etfe {

PetscErrorCode StructureGenerateMesh(MPI_Comm comm, const char *owner, const MeshGenInput &gen, MeshData *mesh) {
  MeshOptions o;
  PetscFunctionBeginUser;
  if (gen.name == "disc") {
    o.keys = kMeshRings | kMeshRefine, o.rings = 16;
    PetscCall(MeshOptionsFromCommandLine(comm, owner, &o));
    PetscCheck(gen.radius > 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "%s: the disc's radius %g must be positive", owner,
               gen.radius);
    PetscCheck(o.rings >= 1 && o.refine >= 0 && o.refine < 12, comm, PETSC_ERR_ARG_OUTOFRANGE,
               "-mesh_rings %" PetscInt_FMT " / -mesh_refine %" PetscInt_FMT ": need rings >= 1 and 0 <= refine < 12",
               o.rings, o.refine);
    PetscCheck(GeneratedTriangles(o.rings, o.rings, 6, o.refine) <= kMaxGeneratedTriangles, comm,
               PETSC_ERR_ARG_OUTOFRANGE,
               "-mesh_rings %" PetscInt_FMT " -mesh_refine %" PetscInt_FMT ": %.3g triangles, more than the %.3g a "
               "generated mesh may have",
               o.rings, o.refine, GeneratedTriangles(o.rings, o.rings, 6, o.refine), kMaxGeneratedTriangles);
    if (SceneHoldsMesh(comm)) *mesh = MakeDiscMesh(gen.radius, (int)(o.rings << o.refine));
    PetscFunctionReturn(0);
  }
  if (gen.name == "annulus") {
    o.keys = kMeshRings | kMeshSectors, o.rings = 16, o.sectors = 96;
    PetscCall(MeshOptionsFromCommandLine(comm, owner, &o));
    PetscCheck(gen.radii.size() == 2 && gen.radii[0] > 0 && gen.radii[1] > gen.radii[0], comm,
               PETSC_ERR_ARG_OUTOFRANGE, "%s: the annulus' radii a,b need 0 < a < b", owner);
    PetscCheck(o.rings >= 1 && o.sectors >= 8 && (double)o.rings * o.sectors * 2 <= 4e6, comm,
               PETSC_ERR_ARG_OUTOFRANGE,
               "-mesh_rings %" PetscInt_FMT " -mesh_sectors %" PetscInt_FMT ": need rings >= 1, sectors >= 8, at most "
               "4e6 triangles",
               o.rings, o.sectors);
    if (SceneHoldsMesh(comm)) *mesh = MakeAnnulusMesh(gen.radii[0], gen.radii[1], (int)o.rings, (int)o.sectors);
    PetscFunctionReturn(0);
  }
  if (gen.name == "capstan") {
    o.keys = kMeshGrid | kMeshRefine, o.nx = 60, o.ny = 4;
    PetscCall(MeshOptionsFromCommandLine(comm, owner, &o));
    PetscCheck(gen.wrap_radius > 0 && gen.wrap_width > 0, comm, PETSC_ERR_ARG_OUTOFRANGE,
               "%s: the pipe's radius and the strip's width must be positive", owner);
    PetscCheck(gen.wrap_angle > 0 && gen.wrap_angle <= 350, comm, PETSC_ERR_ARG_OUTOFRANGE,
               "%s: the wrap angle %g must lie in (0, 350] degrees", owner, gen.wrap_angle);
    PetscCheck(o.nx >= 2 && o.ny >= 1 && o.refine >= 0 && o.refine < 10, comm, PETSC_ERR_ARG_OUTOFRANGE,
               "%s: need -mesh_nx >= 2, -mesh_ny >= 1, 0 <= -mesh_refine < 10", owner);
    PetscCheck(GeneratedTriangles(o.nx, o.ny, 2, o.refine) <= kMaxGeneratedTriangles, comm, PETSC_ERR_ARG_OUTOFRANGE,
               "-mesh_nx %" PetscInt_FMT " -mesh_ny %" PetscInt_FMT " -mesh_refine %" PetscInt_FMT ": %.3g triangles, "
               "more than the %.3g a generated mesh may have",
               o.nx, o.ny, o.refine, GeneratedTriangles(o.nx, o.ny, 2, o.refine), kMaxGeneratedTriangles);
    if (SceneHoldsMesh(comm))
      *mesh = MakeWrappedStripMesh(gen.wrap_radius, gen.wrap_angle * M_PI / 180.0, gen.wrap_width,
                                   (int)(o.nx << o.refine), (int)(o.ny << o.refine));
    PetscFunctionReturn(0);
  }
  if (gen.name == "tube") {
    o.keys = kMeshTube | kMeshRefine, o.ntheta = 48, o.nz = 16;
    PetscCall(MeshOptionsFromCommandLine(comm, owner, &o));
    PetscCheck(gen.radius > 0 && gen.length > 0, comm, PETSC_ERR_ARG_OUTOFRANGE,
               "%s: the tube's radius and length must be positive", owner);
    PetscCheck(o.ntheta >= 6 && o.nz >= 2 && o.nz % 2 == 0 && o.refine >= 0 && o.refine < 8, comm,
               PETSC_ERR_ARG_OUTOFRANGE, "%s: need -mesh_ntheta >= 6, an even -mesh_nz >= 2, 0 <= -mesh_refine < 8",
               owner);
    PetscCheck(GeneratedTriangles(o.ntheta, o.nz, 2, o.refine) <= kMaxGeneratedTriangles, comm,
               PETSC_ERR_ARG_OUTOFRANGE,
               "-mesh_ntheta %" PetscInt_FMT " -mesh_nz %" PetscInt_FMT " -mesh_refine %" PetscInt_FMT ": %.3g "
               "triangles, more than the %.3g a generated mesh may have",
               o.ntheta, o.nz, o.refine, GeneratedTriangles(o.ntheta, o.nz, 2, o.refine), kMaxGeneratedTriangles);
    if (SceneHoldsMesh(comm))
      *mesh = MakeTubeMesh(gen.radius, -0.5 * gen.length, gen.length, (int)(o.ntheta << o.refine),
                           (int)(o.nz << o.refine));
    PetscFunctionReturn(0);
  }
  PetscCheck(gen.name == "rectangle", comm, PETSC_ERR_ARG_UNKNOWN_TYPE,
             "-structure_mesh_generator %s: use disc (-structure_mesh_radius, -mesh_rings), annulus "
             "(-structure_mesh_radii a,b, -mesh_rings, -mesh_sectors), rectangle (-structure_mesh_size lx,ly, "
             "-mesh_nx, -mesh_ny), capstan (-structure_mesh_wrap radius,angle,width) or tube "
             "(-structure_mesh_radius, -structure_mesh_length), or give a mesh file with -mesh_file",
             gen.name.c_str());
  o.keys = kMeshGrid | kMeshRefine | kMeshIrregular, o.nx = 8, o.ny = 4;
  PetscCall(MeshOptionsFromCommandLine(comm, owner, &o));
  PetscCheck(gen.size.size() == 2 && gen.size[0] > 0 && gen.size[1] > 0 && o.nx >= 1 && o.ny >= 1 && o.refine >= 0 &&
                 o.refine < 12,
             comm, PETSC_ERR_ARG_OUTOFRANGE,
             "%s: need a positive size lx,ly, -mesh_nx/-mesh_ny >= 1, 0 <= -mesh_refine < 12", owner);
  PetscCheck(o.perturb >= 0 && o.perturb < 0.5, comm, PETSC_ERR_ARG_OUTOFRANGE,
             "-mesh_perturb %g: must lie in [0, 0.5) or elements may invert", o.perturb);
  const int per_cell = o.pattern == DiagonalPattern::Crossed ? 4 : 2;
  PetscCheck(GeneratedTriangles(o.nx, o.ny, per_cell, o.refine) <= kMaxGeneratedTriangles, comm,
             PETSC_ERR_ARG_OUTOFRANGE,
             "-mesh_nx %" PetscInt_FMT " -mesh_ny %" PetscInt_FMT " -mesh_refine %" PetscInt_FMT ": %.3g triangles, "
             "more than the %.3g a generated mesh may have",
             o.nx, o.ny, o.refine, GeneratedTriangles(o.nx, o.ny, per_cell, o.refine), kMaxGeneratedTriangles);
  if (SceneHoldsMesh(comm))
    *mesh = MakeRectangleMesh(0.0, 0.0, gen.size[0], gen.size[1], (int)(o.nx << o.refine), (int)(o.ny << o.refine),
                              o.pattern, o.perturb, 12345u);
  PetscFunctionReturn(0);
}

PetscErrorCode StructureMeshFromOptions(MPI_Comm comm, StructureInputs *in, SceneSpec *scene, bool *generated) {
  const char *names[] = {"file", "disc", "rectangle", "annulus", "capstan", "tube"};
  PetscInt k = 0;
  MeshGenInput &g = in->generator;
  PetscFunctionBeginUser;
  PetscOptionsBegin(comm, nullptr, "General scene: a generated mesh instead of a mesh file", "Scene");
  PetscCall(PetscOptionsEList("-structure_mesh_generator",
                              "file (-mesh_file), disc (radius -structure_mesh_radius, -mesh_rings; node groups rim, "
                              "centre), rectangle (-structure_mesh_size lx,ly, -mesh_nx, -mesh_ny, -mesh_perturb; "
                              "node groups left, right, bottom, top, corner_*) or annulus (-structure_mesh_radii a,b, "
                              "-mesh_rings, -mesh_sectors; node groups hub, outer) or capstan (a strip laid on a pipe of "
                              "axis y, -structure_mesh_wrap radius,angle,width, -mesh_nx along, -mesh_ny across; node "
                              "groups left and right at its ends) or tube (an open cylinder around z, radius "
                              "-structure_mesh_radius, -structure_mesh_length, -mesh_ntheta, -mesh_nz; node groups bottom, "
                              "top, middle); every generated mesh has the node and surface group all",
                              "", names, 6, names[0], &k, nullptr));
  if (k == 1 || k == 5)
    PetscCall(OptionsRealFinite(PetscOptionsObject, "-structure_mesh_radius", "Radius of the generated disc or tube [mm]", "mm",
                                &g.radius, nullptr));
  if (k == 2)
    PetscCall(OptionsRealArray(PetscOptionsObject, "-structure_mesh_size",
                               "Size lx,ly of the generated rectangle [mm] (corner at the origin)", &g.size, nullptr));
  if (k == 3)
    PetscCall(OptionsRealArray(PetscOptionsObject, "-structure_mesh_radii",
                               "Hub and outer radius a,b of the generated annulus [mm]", &g.radii, nullptr));
  if (k == 5)
    PetscCall(OptionsRealFinite(PetscOptionsObject, "-structure_mesh_length",
                                "Length of the generated tube along z [mm] (centred at z = 0)", "mm", &g.length, nullptr));
  if (k == 4) {
    std::vector<double> wrap = {g.wrap_radius, g.wrap_angle, g.wrap_width};
    PetscCall(OptionsRealArray(PetscOptionsObject, "-structure_mesh_wrap",
                               "The capstan strip: pipe radius [mm], wrap angle [degrees], strip width [mm]", &wrap,
                               nullptr));
    PetscCheck(wrap.size() == 3, comm, PETSC_ERR_ARG_SIZ, "-structure_mesh_wrap: give radius,angle,width");
    g.wrap_radius = wrap[0], g.wrap_angle = wrap[1], g.wrap_width = wrap[2];
  }
  PetscOptionsEnd();
  *generated = k != 0;
  if (!*generated) PetscFunctionReturn(0);
  g.name = names[k];
  PetscCall(StructureGenerateMesh(comm, "general scene", g, &scene->mesh));
  PetscFunctionReturn(0);
}

} // namespace etfe
