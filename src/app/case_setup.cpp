// A case built from the options (case_setup.h).
#include "case_setup.h"

#include <cstring>
#include <memory>

#include "etfe/io/checkpoint.h"
#include "etfe/assembly/input_plausibility.h"
#include "etfe/material/material.h"
#include "etfe/assembly/linear_path.h"
#include "memory_check.h"
#include "solver_defaults.h"

namespace etfe {

PetscErrorCode CreateCase(MPI_Comm comm, bool formfind, SceneSpec &&scene,
                          const SceneObserver &observer, Case *c) {
  std::unique_ptr<Material> material;
  PetscFunctionBeginUser;
  c->formfind = formfind;
  if (formfind) {
    PetscCall(FormFindOptionsFromCommandLine(comm, &c->ffo));
    material = MaterialCreatePrescribedStress(c->ffo.ratio * c->ffo.stress, c->ffo.stress);
  } else {
    PetscCall(MaterialCreateFromOptions(comm, &material));
    PetscCall(MaterialCheckPlausible(comm, *material));
  }
  // The linear path first: it may name the matrix type and the near-null space the problem reads,
  // and whether it fits the nodes' memory is known before anything large is made.
  LinearPath path;
  {
    PetscInt nodes = (PetscInt)scene.mesh.coords.size() / 3;
    PetscCallMPI(MPI_Bcast(&nodes, 1, MPIU_INT, 0, comm));  // rank 0 alone holds the mesh
    PetscCall(DecideLinearPath(comm, 3 * nodes, &path));
    PetscCall(CheckMemoryFits(comm, path));
  }
  auto *P = new Problem();
  c->P = P;
  P->linear_path = std::move(path);
  P->thickness = scene.thickness;
  PetscCall(MembraneOptionsFromCommandLine(comm, P));
  PetscCall(ReportPlausibility(comm, CheckThickness(P->thickness)));
  PetscCheck(
      !(formfind && P->wrinkling), comm, PETSC_ERR_ARG_INCOMP,
      "-membrane_wrinkling tension_field needs a material law (-analysis stretch); form finding "
      "prescribes the stress: drop the option for -analysis formfind");
  PetscCheck(!(P->wrinkling && std::strcmp(material->Name(), "viscoelastic_plastic") == 0), comm, PETSC_ERR_ARG_INCOMP,
             "-membrane_wrinkling tension_field with -material_type viscoelastic_plastic: the wrinkled return map "
             "has no relaxation; use -material_type plastic or drop the wrinkling model");
  if (P->wrinkling) material = MaterialWrapTensionField(std::move(material));
  // The surface groups' own laws (-film_<group>_material_*), each over the film's options.
  PetscCheck(!formfind || scene.material_prefixes.empty(), comm, PETSC_ERR_ARG_INCOMP,
             "-%smaterial_*: form finding prescribes the stress and uses no material law; drop the surface group's "
             "material options for -analysis formfind",
             scene.material_prefixes.empty() ? "" : scene.material_prefixes[0].c_str());
  for (const std::string &prefix : scene.material_prefixes) {
    std::unique_ptr<Material> law;
    PetscCall(MaterialCreateFromOptions(comm, &law, prefix.c_str()));
    PetscCall(MaterialCheckPlausible(comm, *law, prefix.c_str()));
    PetscCheck(!(P->wrinkling && std::strcmp(law->Name(), "viscoelastic_plastic") == 0), comm, PETSC_ERR_ARG_INCOMP,
               "-membrane_wrinkling tension_field with -%smaterial_type viscoelastic_plastic: the wrinkled return "
               "map has no relaxation; use the plastic law there or drop the wrinkling model",
               prefix.c_str());
    if (P->wrinkling) law = MaterialWrapTensionField(std::move(law));
    P->part_materials.push_back(std::move(law));
  }
  PetscCall(StageClockFromOptions(comm, formfind, &scene, &P->clock));
  PetscCall(CheckpointFingerprintScene(comm, scene, P));
  // A load history keeps only each rank's part (form finding keeps the global description on
  // rank 0, which writes the found shape with the scene's topology).
  PetscCall(ProblemCreate(comm, std::move(scene), std::move(material), formfind, P));
  P->observer = observer;
  if (P->observer.setup) PetscCall(P->observer.setup(P, P->observer.ctx));
  PetscCall(CreateSolver(P, &c->snes));
  PetscCall(LoadStepperOptionsFromCommandLine(comm, &c->lso));
  PetscCall(LoadStepperSetConvergenceTest(P, c->snes, c->lso));
  PetscFunctionReturn(0);
}

PetscErrorCode CaseDestroy(Case *c) {
  PetscFunctionBeginUser;
  PetscCall(SNESDestroy(&c->snes));
  if (c->P) PetscCall(ProblemDestroy(c->P));
  delete c->P;
  c->P = nullptr;
  PetscFunctionReturn(0);
}

} // namespace etfe
