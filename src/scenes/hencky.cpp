// -scene hencky: Hencky's problem (docs/theory.md §13) as a case of the general scene. A flat disc
// (generated, -mesh_rings) clamped at its rim (-bc_rim_fix xyz) under a uniform follower pressure
// on the whole film, started from a paraboloid bulge, checked against the closed form
// (-structure_check hencky: centre deflection and centre stress). The same case as options only:
// options/structure/verify_hencky.opts; this scene keeps its own option names (-hencky_*).
//
// A flat membrane has no out-of-plane stiffness at zero load, so Newton cannot start from the
// flat state: the paraboloid (-hencky_initial_bulge, default a/10) changes only the initial
// guess, not the converged answer.
#include <petscsys.h>

#include "etfe/assembly/input_plausibility.h"
#include "etfe/scenes/scene_registry.h"
#include "structure_inputs.h"

namespace etfe {

namespace {

struct HenckyInputs {
  PetscReal radius = 500.0, pressure = 2e-4, bulge = -1.0;
};

// What the hencky options give, as the general scene's inputs.
PetscErrorCode HenckyPreset(MPI_Comm, StructureInputs *in, void *vctx) {
  const auto *h = (const HenckyInputs *)vctx;
  PetscFunctionBeginUser;
  BcInput rim;
  rim.group = "rim", rim.fix = "xyz";
  in->bcs.push_back(rim);
  for (FilmInput &f : in->films)
    if (f.group == "all") f.pressure = {"-hencky_pressure", {1.0}, h->pressure};
  in->initial_bulge = h->bulge, in->bulge_radius = h->radius, in->bulge_centre = {0.0, 0.0};
  in->generator.name = "disc", in->generator.radius = h->radius;
  in->check.name = "hencky", in->check.radius = h->radius, in->check.pressure = h->pressure, in->check.given = true;
  PetscFunctionReturn(0);
}

} // namespace

PetscErrorCode SceneBuild_Hencky(MPI_Comm comm, SceneSpec *scene, SceneObserver *observer) {
  HenckyInputs h;
  MeshGenInput disc;
  PetscFunctionBeginUser;
  PetscOptionsBegin(comm, nullptr, "Hencky scene: clamped circular membrane under pressure", "Scene");
  PetscCall(PetscOptionsReal("-hencky_radius", "Radius a [mm]", "", h.radius, &h.radius, nullptr));
  PetscCall(PetscOptionsReal("-hencky_pressure", "Pressure p [MPa]", "", h.pressure, &h.pressure, nullptr));
  PetscCall(PetscOptionsReal("-hencky_initial_bulge",
                             "Centre height of the paraboloid initial guess [mm] (default a/10)", "", h.bulge, &h.bulge,
                             nullptr));
  PetscOptionsEnd();
  PetscCheck(h.radius > 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "-hencky_radius %g must be positive", h.radius);
  if (h.bulge < 0) h.bulge = 0.1 * h.radius;
  disc.name = "disc", disc.radius = h.radius;
  PetscCall(StructureGenerateMesh(comm, "hencky scene", disc, &scene->mesh));
  PetscBool help = PETSC_FALSE;
  PetscCall(PetscOptionsHasHelp(nullptr, &help));
  if (help && scene->name.empty()) PetscFunctionReturn(0);  // -help without a scene: the options are shown
  PetscCall(StructureBuild(comm, scene, observer, true, HenckyPreset, &h));
  // The pressure is this scene's option, in MPa: the registry checks its scale by that name.
  scene->loads_checked = false;
  PetscFunctionReturn(0);
}

} // namespace etfe
