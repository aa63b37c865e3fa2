// The plausibility checks on a run's inputs (etfe/assembly/input_plausibility.h).
#include "etfe/assembly/input_plausibility.h"

#include "etfe/kernels/plasticity.h"
#include "etfe/material/material.h"

namespace etfe {

PetscErrorCode ReportPlausibility(MPI_Comm comm, const PlausibilityCheck &c) {
  PetscFunctionBeginUser;
  PetscCheck(c.level != Plausibility::Error, comm, PETSC_ERR_ARG_OUTOFRANGE, "%s", c.message.c_str());
  if (c.level == Plausibility::Warning) PetscCall(PetscPrintf(comm, "etfe: warning: %s\n", c.message.c_str()));
  PetscFunctionReturn(0);
}

PetscErrorCode MaterialCheckPlausible(MPI_Comm comm, const Material &material, const char *prefix) {
  double young, nu;
  PetscFunctionBeginUser;
  material.ElasticConstants(&young, &nu);
  PetscCall(ReportPlausibility(comm, CheckYoung(young, prefix ? prefix : "")));
  if (const PlasticMaterial *law = material.PlasticLaw())
    PetscCall(ReportPlausibility(comm, CheckYield(law->yield, law->nseg, young, prefix ? prefix : "")));
  PetscFunctionReturn(0);
}

} // namespace etfe
