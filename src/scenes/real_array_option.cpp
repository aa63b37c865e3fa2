// Real-array options with their whole default in -help (see real_array_option.h).
#include "real_array_option.h"

#include <cstdio>
#include <cstdlib>
#include <string>

namespace etfe {

PetscErrorCode OptionsRealArray(PetscOptionItems *PetscOptionsObject, const char *name, const char *help,
                                std::vector<double> *v, PetscBool *named) {
  char value[PETSC_MAX_PATH_LEN];
  PetscBool set = PETSC_FALSE;
  PetscToken token;
  char *item = nullptr;
  PetscFunctionBeginUser;
  std::string shown;  // the default as the user would type it (PETSc's %g would add "." to integers)
  for (double x : *v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.15g", x);
    shown += (shown.empty() ? "" : ",") + std::string(buf);
  }
  // The default apart from the buffer read into: -help shows both ("now" and "formerly").
  PetscCall(PetscStrncpy(value, shown.c_str(), sizeof value));
  PetscCall(PetscOptionsString(name, help, "", shown.c_str(), value, sizeof value, &set));
  if (named) *named = set;
  if (!set) PetscFunctionReturn(0);
  v->clear();
  PetscCall(PetscTokenCreate(value, ',', &token));
  while (true) {
    PetscReal x;
    PetscCall(PetscTokenFind(token, &item));
    if (!item) break;
    // PETSc's own message ("Input string abc has no numeric value") names neither option nor place.
    char *end = nullptr;
    std::strtod(item, &end);
    PetscCheck(end != item && *end == '\0', PetscOptionsObject->comm, PETSC_ERR_ARG_WRONG,
               "%s: value %zu (\"%s\") is not a number; give comma-separated numbers (default %s)", name,
               v->size() + 1, item, shown.empty() ? "none" : shown.c_str());
    PetscCall(PetscOptionsStringToReal(item, &x));
    v->push_back(x);
  }
  PetscCall(PetscTokenDestroy(&token));
  PetscFunctionReturn(0);
}

} // namespace etfe
