// -scene catenoid (a check of form finding) as a case of the general scene: a soap film between
// two coaxial rings of radius R a distance H apart (a generated tube held at its rings, bottom and
// top). Isotropic form finding must give the catenoid r(z) = c cosh(z/c) with R = c cosh(H/(2c))
// (the larger root: the stable one); beyond the Goldschmidt limit (H/R > 1.3255) no catenoid
// exists and the run must end with an error, not a shape. -structure_check catenoid prints
// neck_radius = <value> with the closed form and the relative error. The same case as options
// only: options/structure/verify_catenoid.opts; this scene keeps its own option names.
#include <petscsys.h>

#include "etfe/scenes/scene_registry.h"
#include "structure_inputs.h"

namespace etfe {

namespace {

struct CatenoidInputs {
  PetscReal radius = 1000.0, separation = 1000.0;
};

// The rings held where they are (the start is the cylinder spanning them), the check.
PetscErrorCode CatenoidPreset(MPI_Comm, StructureInputs *in, void *vctx) {
  const auto *c = (const CatenoidInputs *)vctx;
  PetscFunctionBeginUser;
  for (const char *ring : {"bottom", "top"}) {
    in->bcs.push_back(BcInput());
    in->bcs.back().group = ring, in->bcs.back().fix = "xyz";
  }
  CheckInput &ck = in->check;
  ck.name = "catenoid", ck.ring_radius = c->radius, ck.separation = c->separation, ck.given = true;
  PetscFunctionReturn(0);
}

} // namespace

PetscErrorCode SceneBuild_Catenoid(MPI_Comm comm, SceneSpec *scene, SceneObserver *observer) {
  CatenoidInputs c;
  PetscFunctionBeginUser;
  PetscOptionsBegin(comm, nullptr, "Catenoid scene: film between two coaxial rings", "Scene");
  PetscCall(PetscOptionsReal("-catenoid_radius", "Ring radius R [mm]", "", c.radius, &c.radius, nullptr));
  PetscCall(PetscOptionsReal("-catenoid_separation", "Ring separation H [mm]", "", c.separation, &c.separation,
                             nullptr));
  PetscOptionsEnd();
  PetscCheck(c.radius > 0 && c.separation > 0, comm, PETSC_ERR_ARG_OUTOFRANGE,
             "-catenoid_radius and -catenoid_separation must be positive");
  MeshGenInput tube;
  tube.name = "tube", tube.radius = c.radius, tube.length = c.separation;
  PetscCall(StructureGenerateMesh(comm, "catenoid scene", tube, &scene->mesh));
  PetscBool help = PETSC_FALSE;
  PetscCall(PetscOptionsHasHelp(nullptr, &help));
  if (help && scene->name.empty()) PetscFunctionReturn(0);  // -help without a scene: the options are shown
  PetscCall(StructureBuild(comm, scene, observer, true, CatenoidPreset, &c));
  PetscFunctionReturn(0);
}

} // namespace etfe
