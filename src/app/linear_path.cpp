// The linear solver chosen by size and rank count (linear_path.h).
#include "linear_path.h"

#include <cstring>

#include "memory_check.h"

namespace etfe {

namespace {

struct Setting {
  const char *key, *value;
};

// The scalable path: FGMRES + GAMG on the shifted preconditioning matrix with the rigid-body
// near-null space and GMRES smoothers (options/solvers/gmres_gamg_shifted.opts holds the same
// settings): O(N) memory and work per iteration, and the one AMG set-up measured to keep DD1511's
// answer through sticking arch pairs (BoomerAMG's GMRES broke down there: docs/solvers.md).
// The method keys are set whatever the options said; the others only where the options set none.
const Setting kMethod[] = {{"-ksp_type", "fgmres"}, {"-pc_type", "gamg"}, {"-mat_type", "aij"}};
const Setting kTuning[] = {{"-ksp_pc_side", "right"},        {"-ksp_rtol", "1e-4"},
                           {"-ksp_max_it", "300"},           {"-ksp_gmres_restart", "100"},
                           {"-pc_gamg_threshold", "0.05"},   {"-mg_levels_ksp_type", "gmres"},
                           {"-mg_levels_ksp_max_it", "3"},   {"-membrane_near_null_space", "true"},
                           {"-etfe_pc_shift", "0.1"}};

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

PetscErrorCode ChooseLinearPath(MPI_Comm comm, PetscInt num_nodes) {
  PetscInt choice = kAuto, min_dof = 3000000, min_ranks = 16;
  PetscBool krylov = PETSC_FALSE;
  PetscMPIInt size;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_size(comm, &size));
  PetscOptionsBegin(comm, nullptr, "Linear solver path", "KSP");
  PetscCall(PetscOptionsEList("-etfe_solver",
                              "auto: the options' (direct) solver below the thresholds, the scalable path (FGMRES + "
                              "GAMG) above; direct: the options as given; scalable: always the scalable path",
                              "", kChoiceNames, 3, kChoiceNames[choice], &choice, nullptr));
  PetscCall(PetscOptionsInt("-etfe_scalable_min_dof", "auto: the scalable path from this many DOF", "", min_dof,
                            &min_dof, nullptr));
  PetscCall(PetscOptionsInt("-etfe_scalable_min_ranks", "auto: the scalable path from this many ranks", "", min_ranks,
                            &min_ranks, nullptr));
  PetscOptionsEnd();
  const PetscInt dof = 3 * num_nodes;
  PetscCall(NamesKrylov(&krylov));
  const bool big = dof >= min_dof, many = size >= min_ranks;
  const bool scalable = choice == kScalable || (choice == kAuto && !krylov && (big || many));
  if (scalable) {
    PetscCall(ApplyScalablePath());
    if (choice == kScalable)
      PetscCall(PetscPrintf(comm, "  linear solver: scalable path (FGMRES + GAMG), as -etfe_solver asks\n"));
    else
      PetscCall(PetscPrintf(comm,
                            "  linear solver: scalable path (FGMRES + GAMG) chosen automatically: %" PetscInt_FMT
                            " DOF on %d rank(s), %s -etfe_scalable_min_%s %" PetscInt_FMT
                            " (-etfe_solver direct keeps the direct solver)\n",
                            dof, size, big ? "from" : "ranks from", big ? "dof" : "ranks", big ? min_dof : min_ranks));
  }
  PetscCall(CheckMemoryFits(comm, dof));
  PetscFunctionReturn(0);
}

} // namespace etfe
