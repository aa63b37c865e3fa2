// Unused options (see options_check.h).
#include "options_check.h"

#include <algorithm>
#include <cstring>
#include <string>
#include <vector>

namespace etfe {

namespace {

const char *const kKnown[] = {
#include "option_names.inc"
};

// The project's option prefixes: a name equal to one, or starting with it and '_'.
const char *const kPrefixes[] = {"scene", "analysis", "mesh", "material", "membrane", "contact", "load", "plan",
                                 "output", "checkpoint", "restart", "formfind", "cutpattern", "saddle",
                                 "hencky", "patch", "capstan", "catenoid", "etfe", "snes_linesearch_etfe",
                                 "structure", "bc", "film", "rigid", "region", "chamber"};

bool IsOurs(const std::string &name) {
  // The planner's TAO reads PETSc's own options under our prefix (-plan_tao_type, ...), late.
  if (name.compare(0, 9, "plan_tao_") == 0) return false;
  for (const char *p : kPrefixes) {
    const size_t n = std::strlen(p);
    if (name.compare(0, n, p) == 0 && (name.size() == n || name[n] == '_')) return true;
  }
  return false;
}

bool IsKnown(const std::string &name) {
  for (const char *k : kKnown)
    if (name == k + 1) return true;  // k is "-name"
  return false;
}

size_t EditDistance(const std::string &a, const std::string &b) {
  std::vector<size_t> row(b.size() + 1);
  for (size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (size_t i = 1; i <= a.size(); ++i) {
    size_t diag = row[0];
    row[0] = i;
    for (size_t j = 1; j <= b.size(); ++j) {
      const size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diag + (a[i - 1] != b[j - 1])});
      diag = up;
    }
  }
  return row[b.size()];
}

std::string Closest(const std::string &name) {
  std::string best;
  size_t d = name.size();
  for (const char *k : kKnown) {
    const size_t e = EditDistance(name, k + 1);
    if (e < d) d = e, best = k;
  }
  return d <= std::max<size_t>(2, name.size() / 4) ? best : "";
}

PetscBool allow = PETSC_FALSE;

} // namespace

void CheckUnusedOptionsAllow(PetscBool allow_unused) { allow = allow_unused; }

PetscErrorCode CheckUnusedOptions(MPI_Comm comm, PetscBool before_run) {
  PetscInt n;
  char **names, **values;
  PetscFunctionBeginUser;
  PetscCall(PetscOptionsLeftGet(nullptr, &n, &names, &values));
  std::string typos, unused, petsc;
  for (PetscInt i = 0; i < n; ++i) {
    const std::string name = names[i];
    if (!IsOurs(name)) {
      petsc += " -" + name;
    } else if (!IsKnown(name)) {
      const std::string hint = Closest(name);
      typos += " -" + name + (hint.empty() ? "" : " (did you mean " + hint + "?)");
    } else {
      unused += " -" + name;
    }
  }
  PetscCall(PetscOptionsLeftRestore(nullptr, &n, &names, &values));
  if (before_run) {
    PetscCheck(typos.empty() || allow, comm, PETSC_ERR_USER_INPUT,
               "unknown option(s):%s. Check the spelling against -help (-options_allow_unused accepts them)",
               typos.c_str());
    if (!unused.empty())
      PetscCall(PetscPrintf(comm, "etfe: warning: option(s) not used by this configuration:%s\n", unused.c_str()));
  } else if (!petsc.empty() && !allow) {
    // Read lazily (a solver, a viewer at the end) or misspelt: PETSc never read them.
    PetscCall(PetscPrintf(comm, "etfe: warning: option(s) never used:%s\n", petsc.c_str()));
  }
  PetscFunctionReturn(0);
}

} // namespace etfe
