// -scene annulus: a pretensioned annular film, outer edge held, a rigid hub rotated in its
// plane, as a case of the general scene; with -membrane_wrinkling tension_field a wrinkled zone
// grows around the hub. The check (-structure_check annulus) compares the radius of the wrinkled
// zone and the torque-rotation pair with the closed form of Stein & Hedgepeth (1961) / Mikulas
// (1964) for these boundary conditions (include/etfe/verification/annulus_closed_form.h). The
// same case as options only: options/structure/verify_annulus.opts; this scene keeps its own
// option names (-annulus_*).
//
// Loading: stage 1 stretches both edges radially by eps0 (uniform pretension
// sigma0 = E eps0/(1-nu): -bc_<edge>_gradient eps0,0,0,eps0); stage 2 turns the hub rigidly by
// phi (-bc_hub_rotation: its nodes prescribed on the chord, the end state exact). The hub is
// rigid, so the rotation is the control and the torque the response.
#include <petscsys.h>

#include "etfe/scenes/scene_registry.h"
#include "etfe/verification/annulus_closed_form.h"
#include "structure_inputs.h"

namespace etfe {

namespace {

struct AnnulusInputs {
  double a, b, eps0, phi;
};

// What the annulus options give, as the general scene's inputs.
PetscErrorCode AnnulusPreset(MPI_Comm, StructureInputs *in, void *vctx) {
  const auto *p = (const AnnulusInputs *)vctx;
  PetscFunctionBeginUser;
  in->bcs.push_back(BcInput());
  in->bcs.back().group = "all", in->bcs.back().fix = "z";
  for (const char *edge : {"outer", "hub"}) {
    in->bcs.push_back(BcInput());
    BcInput &bc = in->bcs.back();
    bc.group = edge;
    bc.gradient = {p->eps0, 0.0, 0.0, p->eps0};
    bc.gradient_stages = {"-annulus_pretension_strain", {1.0, 1.0}, 0.0};
  }
  in->bcs.back().rotation = p->phi;
  in->bcs.back().rotation_stages = {"-annulus_rotation", {0.0, 1.0}, 0.0};
  CheckInput &ck = in->check;
  ck.name = "annulus", ck.a = p->a, ck.b = p->b, ck.eps0 = p->eps0, ck.phi = p->phi, ck.given = true;
  PetscFunctionReturn(0);
}

} // namespace

PetscErrorCode SceneBuild_Annulus(MPI_Comm comm, SceneSpec *scene, SceneObserver *observer) {
  PetscReal a = 100.0, b = 500.0, eps0 = 1e-4, phi = 5e-4;
  PetscFunctionBeginUser;
  PetscOptionsBegin(comm, nullptr, "Annulus scene: pretensioned annulus, rigid hub rotated", "Scene");
  PetscCall(PetscOptionsReal("-annulus_inner_radius", "Hub radius a [mm]", "", a, &a, nullptr));
  PetscCall(PetscOptionsReal("-annulus_outer_radius", "Outer radius b [mm]", "", b, &b, nullptr));
  PetscCall(PetscOptionsReal("-annulus_pretension_strain",
                             "Radial strain eps0 of both edges (stage 1): pretension E eps0/(1-nu)", "", eps0,
                             &eps0, nullptr));
  PetscCall(PetscOptionsReal("-annulus_rotation", "Hub rotation phi [rad] (stage 2)", "", phi, &phi, nullptr));
  PetscOptionsEnd();
  PetscCheck(a > 0 && b > a, comm, PETSC_ERR_ARG_OUTOFRANGE,
             "-annulus_inner_radius %g / -annulus_outer_radius %g: need 0 < a < b", a, b);
  PetscCheck(eps0 > 0 && eps0 < 0.05, comm, PETSC_ERR_ARG_OUTOFRANGE,
             "-annulus_pretension_strain %g: the annulus needs a positive pretension (0 < eps0 < 0.05; a film "
             "without it wrinkles under any torque and has no closed form)", eps0);
  PetscCheck(phi >= 0 && phi < 0.5, comm, PETSC_ERR_ARG_OUTOFRANGE,
             "-annulus_rotation %g: give a rotation in [0, 0.5) rad", phi);
  {
    // The closed form's range: past it the radial stress at the hub vanishes and the film around
    // the hub goes slack (no partly wrinkled state). The material belongs to -material_*, read
    // after the scene: the range is checked here with ETFE's nu = 0.43 (E drops out: only
    // phi/eps0, a, b and nu set it) and again with the run's own constants in the report.
    AnnulusTorsion p{a, b, 800.0, 0.43, eps0};
    AnnulusTorsionResult res;
    PetscCheck(AnnulusStateAtRotation(p, phi, &res) == 0, comm, PETSC_ERR_ARG_OUTOFRANGE,
               "-annulus_rotation %g: at this rotation (%.3g times the wrinkling onset) the film around the hub "
               "goes slack and the closed form has no partly wrinkled state; use a smaller rotation", phi,
               phi / AnnulusOnsetRotation(p));
  }
  MeshGenInput gen;
  gen.name = "annulus", gen.radii = {a, b};
  PetscCall(StructureGenerateMesh(comm, "annulus scene", gen, &scene->mesh));
  PetscBool help = PETSC_FALSE;
  PetscCall(PetscOptionsHasHelp(nullptr, &help));
  if (help && scene->name.empty()) PetscFunctionReturn(0);  // -help without a scene: the options are shown
  AnnulusInputs in{a, b, eps0, phi};
  PetscCall(StructureBuild(comm, scene, observer, true, AnnulusPreset, &in));
  PetscFunctionReturn(0);
}

} // namespace etfe
