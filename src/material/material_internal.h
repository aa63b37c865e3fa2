// Shared by the material files (private to src/material).
#pragma once
#include <petscsys.h>

#include <memory>

#include "etfe/kernels/plasticity.h"
#include "etfe/material/material.h"

namespace etfe {

// -material_young, -material_poisson, -material_yield, -material_hardening into m (thesis
// Table 4.2, case 1, by default), checked.
PetscErrorCode ReadPlasticMaterial(PlasticMaterial *m);
// -material_type viscoelastic_plastic (viscoelastic_plastic.cpp).
PetscErrorCode CreateViscoelasticPlastic(std::unique_ptr<Material> *out);

} // namespace etfe
