// -help without a scene (help_listing.h).
#include "help_listing.h"

#include <petscsnes.h>

#include <memory>

#include "etfe/io/checkpoint.h"
#include "etfe/contact/contact.h"
#include "etfe/analyses/formfind.h"
#include "etfe/solver/linesearch.h"
#include "etfe/solver/load_stepper.h"
#include "etfe/material/material.h"
#include "etfe/io/output.h"
#include "etfe/assembly/problem.h"
#include "etfe/assembly/linear_path.h"

namespace etfe {

PetscErrorCode ListEveryOption(MPI_Comm comm) {
  std::unique_ptr<Material> m;
  Problem throwaway;
  FormFindOptions ffo;
  LoadStepperOptions lso;
  OutputOptions oo;
  CheckpointOptions cko;
  ContactOptions co;
  PetscInt lu_max_dof;
  double young, nu;
  SNES snes;
  SNESLineSearch ls;
  PetscFunctionBeginUser;
  // The viscoelastic-plastic law reads every -material_* option the elastic and plastic ones do,
  // and its own.
  PetscCall(PetscOptionsSetValue(nullptr, "-material_type", "viscoelastic_plastic"));
  PetscCall(FormFindOptionsFromCommandLine(comm, &ffo));
  PetscCall(MaterialCreateFromOptions(comm, &m));
  PetscCall(MembraneOptionsFromCommandLine(comm, &throwaway));
  PetscCall(LoadStepperOptionsFromCommandLine(comm, &lso));
  SceneSpec no_scene;
  PetscCall(StageClockFromOptions(comm, false, &no_scene, &throwaway.clock));
  PetscCall(OutputOptionsFromCommandLine(comm, "scene", &oo));
  PetscCall(CheckpointOptionsFromCommandLine(comm, "results/scene/scene", &cko));
  m->ElasticConstants(&young, &nu);
  PetscCall(ContactOptionsFromCommandLine(comm, 1e3 * young * throwaway.thickness, 1e-6, &co));
  PetscCall(LUNativeMaxDofFromOptions(comm, &lu_max_dof));
  PetscCall(SNESCreate(comm, &snes));
  PetscCall(SNESGetLineSearch(snes, &ls));
  PetscCall(SNESLineSearchSetType(ls, SNESLINESEARCHETFE));
  PetscCall(SNESSetFromOptions(snes));
  PetscCall(SNESDestroy(&snes));
  PetscFunctionReturn(0);
}

} // namespace etfe
