// The linear solver chosen by size and rank count (linear_path.h).
#include "linear_path.h"

#include <cstring>

namespace etfe {

namespace {

struct Setting {
  const char *key, *value;
};

// The scalable path: GMRES preconditioned by a MUMPS factorization with block low-rank
// compression, kept over Newton iterations and increments and rebuilt once a solve needs more
// than 20 iterations (options/solvers/gmres_mumps_blr_lagged.opts holds the same settings). The
// method keys are set whatever the options said; the others only where the options set none.
const Setting kMethod[] = {{"-ksp_type", "gmres"}, {"-pc_type", "lu"}, {"-pc_factor_mat_solver_type", "mumps"}};
const Setting kTuning[] = {{"-ksp_pc_side", "right"},      {"-ksp_rtol", "1e-4"},          {"-ksp_max_it", "100"},
                           {"-ksp_gmres_restart", "100"},  {"-mat_mumps_icntl_35", "2"},   {"-mat_mumps_cntl_7", "1e-4"},
                           {"-etfe_pc_refresh_its", "20"}};

enum Choice { kAuto, kDirect, kScalable };
const char *const kChoiceNames[] = {"auto", "direct", "scalable"};

PetscErrorCode ApplyScalablePath() {
  PetscBool set;
  PetscFunctionBeginUser;
  for (const Setting &s : kMethod) PetscCall(PetscOptionsSetValue(nullptr, s.key, s.value));
  for (const Setting &s : kTuning) {
    PetscCall(PetscOptionsHasName(nullptr, nullptr, s.key, &set));
    if (!set) PetscCall(PetscOptionsSetValue(nullptr, s.key, s.value));
  }
  PetscFunctionReturn(0);
}

// A Krylov method the options name (anything but preonly), which auto leaves alone.
PetscErrorCode NamesKrylov(PetscBool *krylov) {
  char ksp[64] = "";
  PetscBool set;
  PetscFunctionBeginUser;
  PetscCall(PetscOptionsGetString(nullptr, nullptr, "-ksp_type", ksp, sizeof ksp, &set));
  *krylov = set && std::strcmp(ksp, "preonly") ? PETSC_TRUE : PETSC_FALSE;
  PetscFunctionReturn(0);
}

} // namespace

PetscErrorCode ChooseLinearPath(Problem *P) {
  PetscInt choice = kAuto, min_dof = 3000000, min_ranks = 16;
  PetscBool krylov;
  PetscFunctionBeginUser;
  PetscOptionsBegin(P->comm, nullptr, "Linear solver path", "KSP");
  PetscCall(PetscOptionsEList("-etfe_solver",
                              "auto: the options' (direct) solver below the thresholds, the scalable path (GMRES + "
                              "lagged MUMPS BLR) above; direct: the options as given; scalable: always the scalable path",
                              "", kChoiceNames, 3, kChoiceNames[choice], &choice, nullptr));
  PetscCall(PetscOptionsInt("-etfe_scalable_min_dof", "auto: the scalable path from this many DOF", "", min_dof,
                            &min_dof, nullptr));
  PetscCall(PetscOptionsInt("-etfe_scalable_min_ranks", "auto: the scalable path from this many ranks", "", min_ranks,
                            &min_ranks, nullptr));
  PetscOptionsEnd();
  const PetscInt dof = 3 * P->mesh.num_nodes_global;
  PetscCall(NamesKrylov(&krylov));
  const bool big = dof >= min_dof, many = P->size >= min_ranks;
  if (choice == kDirect || (choice == kAuto && (krylov || !(big || many)))) PetscFunctionReturn(0);
  PetscCall(ApplyScalablePath());
  if (choice == kScalable)
    PetscCall(PetscPrintf(P->comm, "  linear solver: scalable path (GMRES + lagged MUMPS BLR), as -etfe_solver asks\n"));
  else
    PetscCall(PetscPrintf(P->comm,
                          "  linear solver: scalable path (GMRES + lagged MUMPS BLR) chosen automatically: %" PetscInt_FMT
                          " DOF on %d rank(s), %s -etfe_scalable_min_%s %" PetscInt_FMT
                          " (-etfe_solver direct keeps the direct solver)\n",
                          dof, P->size, big ? "from" : "ranks from", big ? "dof" : "ranks", big ? min_dof : min_ranks));
  PetscFunctionReturn(0);
}

} // namespace etfe
