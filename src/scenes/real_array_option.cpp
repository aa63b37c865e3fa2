// Real-array options with their whole default in -help (see real_array_option.h).
#include "real_array_option.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

namespace etfe {

std::string OptionFullName(const PetscOptionItems *PetscOptionsObject, const char *name) {
  const char *prefix = PetscOptionsObject->prefix ? PetscOptionsObject->prefix : "";
  return std::string("-") + prefix + (name[0] == '-' ? name + 1 : name);
}

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
               "%s: value %zu (\"%s\") is not a number; give comma-separated numbers (default %s)",
               OptionFullName(PetscOptionsObject, name).c_str(), v->size() + 1, item,
               shown.empty() ? "none" : shown.c_str());
    PetscCall(PetscOptionsStringToReal(item, &x));
    PetscCheck(std::isfinite(x), PetscOptionsObject->comm, PETSC_ERR_ARG_OUTOFRANGE,
               "%s: value %zu (\"%s\") is not a finite number; give finite numbers (default %s)",
               OptionFullName(PetscOptionsObject, name).c_str(), v->size() + 1, item,
               shown.empty() ? "none" : shown.c_str());
    v->push_back(x);
  }
  PetscCall(PetscTokenDestroy(&token));
  PetscFunctionReturn(0);
}

std::string OptionNum(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", x);
  return buf;
}

PetscErrorCode OptionsRealFinite(PetscOptionItems *PetscOptionsObject, const char *name, const char *help,
                                 const char *unit, double *v, PetscBool *set, const char *default_text) {
  const std::string fallback = default_text ? default_text : OptionNum(*v);
  PetscReal x = *v;
  PetscBool given = PETSC_FALSE;
  PetscFunctionBeginUser;
  PetscCall(PetscOptionsReal(name, help, "", x, &x, &given));
  PetscCheck(std::isfinite(x), PetscOptionsObject->comm, PETSC_ERR_ARG_OUTOFRANGE,
             "%s %s: not a finite number; give the value%s%s, or leave the option out for its default (%s)",
             OptionFullName(PetscOptionsObject, name).c_str(), OptionNum(x).c_str(), unit[0] ? " in " : "", unit,
             fallback.c_str());
  *v = x;
  if (set) *set = given;
  PetscFunctionReturn(0);
}

} // namespace etfe
