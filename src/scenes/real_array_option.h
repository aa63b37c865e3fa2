// A real-array option whose -help line shows its whole default. PETSc 3.18's PetscOptionsRealArray
// prints only the first value of a default it was not given (-saddle_part_A <0.> for 0,0,400,400),
// so the array is read as a string option, which -help shows in full as <now ... : formerly ...>,
// and parsed value by value as PetscOptionsRealArray parses it. Also the scenes' real options:
// PETSc reads "nan" and "inf" as numbers, which would surface as a NaN divergence (or be taken
// silently) far from the option; both readers refuse them by the option's full name.
#pragma once
#include <petscsys.h>

#include <string>
#include <vector>

namespace etfe {

// Inside PetscOptionsBegin/End. *v holds the default and receives the values given; named (may be
// nullptr) says whether the option was given at all: given without values it leaves *v empty.
// A value that is not a finite number is refused, naming the option and the value's position.
PetscErrorCode OptionsRealArray(PetscOptionItems *PetscOptionsObject, const char *name, const char *help,
                                std::vector<double> *v, PetscBool *named);

// Inside PetscOptionsBegin/End: PetscOptionsReal, refusing a value that is not finite; `unit`
// (e.g. "mm", "" for a pure number) is named in the message with the default (*v on entry, or
// `default_text` when given: "-membrane_thickness").
PetscErrorCode OptionsRealFinite(PetscOptionItems *PetscOptionsObject, const char *name, const char *help,
                                 const char *unit, double *v, PetscBool *set, const char *default_text = nullptr);

// A value as a user types it (%g; PETSc's own %g would print 0 as "0.").
std::string OptionNum(double x);

// "-" + the prefix of the PetscOptionsBegin block + name without its "-": the name a user types.
std::string OptionFullName(const PetscOptionItems *PetscOptionsObject, const char *name);

} // namespace etfe
