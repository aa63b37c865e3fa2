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

// The first words of PETSc's options (the part before the first '_'): its objects' prefixes and
// its program-wide options. Gathered from `etfe -options_file options/hencky.opts -help`, from
// the option strings of PETSc 3.18's library and from the prefixes its solvers give their inner
// solvers (sub_, mg_levels_, fieldsplit_0_, redundant_, esteig_, ...), generously: refusing a
// valid PETSc option costs more than letting a typo through to the end-of-run warning. Words
// starting with "petsc" (petscspace_, petscfe_, ...) are PETSc's too.
const char *const kPetscWords[] = {
    "adapt", "adaptor", "all", "ao", "bag", "bddc", "check", "checkfunctionlist", "checkstack", "citations",
    "compare", "convest", "cuda", "da", "debugger", "default", "deflation", "device", "disable", "display", "dll",
    "dm", "dmcomposite", "dmnetwork", "dmplex", "dmsnes", "dmts", "draw", "error", "esteig", "fas", "fieldsplit",
    "fp", "galerkin", "gamg", "gasm", "geometry", "get", "glvis", "h", "hdf5", "help", "hip", "history", "hmg",
    "hypre", "info", "is", "kokkos", "ksp", "landau", "lg", "library", "log", "lsc", "malloc", "mat", "matconvert",
    "matis", "matload", "matmatmult", "matptap", "matrart", "matstash", "memory", "mg", "mpi", "mpiuni", "noshared",
    "no", "not", "nox", "npc", "objects", "omp", "on", "options", "pc", "pf", "popen", "prefix", "preload",
    "psubcomm", "python", "random", "redistribute", "redundant", "root", "saws", "sf", "shared", "skip", "snes",
    "stag", "start", "stop", "sub", "sycl", "tao", "telescope", "tmp", "ts", "use", "vec", "vecload",
    "vecscatter", "vecstash", "version", "viennacl", "viewer", "x"};
// Prefixes this program gives PETSc objects of its own (their options are PETSc's names after it).
const char *const kOurObjectPrefixes[] = {"flatten", "plan"};

std::string FirstWord(const std::string &name) { return name.substr(0, name.find('_')); }

// A first word this program or PETSc uses: an option that begins with anything else is a typo.
bool KnownFirstWord(const std::string &word) {
  if (word.compare(0, 5, "petsc") == 0) return true;
  for (const char *w : kPetscWords)
    if (word == w) return true;
  for (const char *w : kOurObjectPrefixes)
    if (word == w) return true;
  for (const char *p : kPrefixes)
    if (word == p) return true;
  for (const char *k : kKnown)
    if (word == FirstWord(k + 1)) return true;
  return false;
}

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

// An option whose first word nobody uses: the closest of this program's names, else the name with
// its first word replaced by the closest word in use (-snse_rtol: -snes_rtol).
std::string ClosestForUnknownWord(const std::string &name) {
  const std::string ours = Closest(name);
  if (!ours.empty()) return ours;
  const std::string word = FirstWord(name);
  std::string best;
  size_t d = word.size() >= 4 ? 3 : 2;  // at most 2 edits (a swap of two letters), 1 for a short word
  auto consider = [&](const std::string &w) {
    const size_t e = EditDistance(word, w);
    if (e < d) d = e, best = w;
  };
  for (const char *w : kPetscWords) consider(w);
  for (const char *p : kPrefixes) consider(p);
  return best.empty() ? "" : "-" + best + name.substr(word.size());
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
    if (!IsOurs(name) && !KnownFirstWord(FirstWord(name))) {
      const std::string hint = ClosestForUnknownWord(name);
      const std::string word = FirstWord(name) + (name.find('_') == std::string::npos ? "" : "_");
      typos += " -" + name + " (neither this program nor PETSc has options beginning -" + word +
               (hint.empty() ? "" : "; did you mean " + hint + "?") + ")";
    } else if (!IsOurs(name)) {
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
