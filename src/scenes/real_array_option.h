// A real-array option whose -help line shows its whole default. PETSc 3.18's PetscOptionsRealArray
// prints only the first value of a default it was not given (-saddle_part_A <0.> for 0,0,400,400),
// so the array is read as a string option, which -help shows in full as <now ... : formerly ...>,
// and parsed value by value as PetscOptionsRealArray parses it.
#pragma once
#include <petscsys.h>

#include <vector>

namespace etfe {

// Inside PetscOptionsBegin/End. *v holds the default and receives the values given; named (may be
// nullptr) says whether the option was given at all: given without values it leaves *v empty.
PetscErrorCode OptionsRealArray(PetscOptionItems *PetscOptionsObject, const char *name, const char *help,
                                std::vector<double> *v, PetscBool *named);

} // namespace etfe
