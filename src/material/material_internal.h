// Shared by the material files (private to src/material).
#pragma once
#include <petscsys.h>

#include <memory>

#include "etfe/kernels/plasticity.h"
#include "etfe/material/material.h"

namespace etfe {

// Where a law's options are read (`pre`): nullptr, the film's -material_*; "film_<group>_", a
// surface group's own law, -film_<group>_material_*, each option falling back to the film's.
// An options block is read once per pass: the film's options, then the group's over them (a
// group's option left out keeps the film's value).
inline int MaterialPasses(const char *pre) { return pre ? 2 : 1; }
inline const char *MaterialPassPrefix(const char *pre, int pass) { return pass ? pre : nullptr; }
// The prefix in a message: "-%smaterial_young" names the option the value came from.
inline const char *MaterialPre(const char *pre) { return pre ? pre : ""; }

// Inside a pass's PetscOptionsBegin/End: a real array of at most N values into values[0..N) and
// its count *n. A pass that does not give the array leaves the one before it: PETSc zeroes the
// count of an array it does not find, so the pass reads into a copy and keeps it only if given.
template <int N>
PetscErrorCode MaterialPassRealArray(PetscOptionItems *PetscOptionsObject, const char *name, const char *help,
                                     PetscReal (&values)[N], PetscInt *n) {
  PetscReal v[N];
  PetscInt nv = N;
  PetscBool set = PETSC_FALSE;
  PetscFunctionBeginUser;
  for (int k = 0; k < N; ++k) v[k] = values[k];
  PetscCall(PetscOptionsRealArray(name, help, "", v, &nv, &set));
  if (set) {
    for (int k = 0; k < N; ++k) values[k] = v[k];
    *n = nv;
  }
  PetscFunctionReturn(0);
}

// -material_young, -material_poisson, -material_yield, -material_hardening into m (thesis
// Table 4.2, case 1, by default), checked.
PetscErrorCode ReadPlasticMaterial(const char *pre, PlasticMaterial *m);
// -material_type viscoelastic_plastic (viscoelastic_plastic.cpp).
PetscErrorCode CreateViscoelasticPlastic(const char *pre, std::unique_ptr<Material> *out);

} // namespace etfe
