// The linear solver path, decided once (etfe/assembly/linear_path.h).
#include "etfe/assembly/linear_path.h"

#include <petscksp.h>

#include <algorithm>
#include <cstdio>
#include <cstring>

#include "etfe/solver/linear_crossover.h"

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

// The options file of the scalable path (the crossover data's name for it), and the size from
// which the direct path no longer fits a node's memory (docs/solvers.md, "The largest run here").
const char *const kScalableFile = "gmres_gamg_shifted";
const PetscInt kMemoryMinDof = 3000000;

enum Choice { kAuto, kDirectChoice, kScalable };
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

// Peak memory per DOF of a whole run (all ranks of a node together), measured with this code on
// the clamped membrane and DD1511 (docs/solvers.md, "The largest run here"). Lower ends of what
// was measured, so that a refusal means the run cannot fit, not that it might not.
struct PathMemory {
  const char *name;
  double kb_per_dof;
};
const PathMemory kDirect = {"a sparse direct factorization", 2.5};  // MUMPS, 1.5e6 DOF: 3.8 GB, grows as N log N
const PathMemory kGamg = {"FGMRES + GAMG", 2.1};                    // 1.5e6 DOF, one rank: 3.2 GB
const PathMemory kLean = {"a Krylov method", 1.1};                  // GMRES(20) + BoomerAMG on J, 1.5e7 DOF: 16.3 GB

PetscErrorCode IsFactor(PC pc, PetscBool *factor) {
  PetscFunctionBeginUser;
  PetscCall(PetscObjectTypeCompareAny((PetscObject)pc, factor, PCLU, PCCHOLESKY, ""));
  PetscFunctionReturn(0);
}

// The kind and memory of a PC that is not a composite one. A factorization's memory is what
// matters wherever the factor PC sits.
PetscErrorCode KindOfPC(PC pc, LinearPath::Kind *kind, PathMemory *memory) {
  PetscBool factor, bddc, gamg, amg;
  PetscFunctionBeginUser;
  PetscCall(IsFactor(pc, &factor));
  PetscCall(PetscObjectTypeCompare((PetscObject)pc, PCBDDC, &bddc));
  PetscCall(PetscObjectTypeCompare((PetscObject)pc, PCGAMG, &gamg));
  PetscCall(PetscObjectTypeCompareAny((PetscObject)pc, &amg, PCHYPRE, PCML, ""));
  *kind = factor ? LinearPath::Kind::direct_lu
          : bddc ? LinearPath::Kind::unassembled
          : gamg || amg ? LinearPath::Kind::krylov_amg
                        : LinearPath::Kind::krylov_other;
  *memory = factor ? kDirect : bddc ? PathMemory{"BDDC (direct subdomain factorizations)", kDirect.kb_per_dof}
          : gamg ? kGamg : kLean;
  PetscFunctionReturn(0);
}

// Block Jacobi and additive Schwarz make their blocks' solvers only at set-up with a matrix: an
// identity of 64 rows per rank (room for several blocks a rank; nothing is factored before a
// solve) gives them, configured from the options as the real ones will be. A set-up the probe
// cannot make (more blocks asked for than it has rows) counts as a Krylov method: the memory
// check never refuses a run for its own sake.
PetscErrorCode MemoryOfBlocks(PC pc, PetscBool asm_pc, PathMemory *memory) {
  const PetscInt rows = 64;
  MPI_Comm comm;
  Mat A;
  KSP *sub = nullptr;
  PetscInt nlocal = 0, first = 0, row0;
  PetscFunctionBeginUser;
  PetscCall(PetscObjectGetComm((PetscObject)pc, &comm));
  PetscCall(MatCreateAIJ(comm, rows, rows, PETSC_DETERMINE, PETSC_DETERMINE, 1, nullptr, 0, nullptr, &A));
  PetscCall(MatGetOwnershipRange(A, &row0, nullptr));
  for (PetscInt i = row0; i < row0 + rows; ++i) PetscCall(MatSetValue(A, i, i, 1.0, INSERT_VALUES));
  PetscCall(MatAssemblyBegin(A, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(A, MAT_FINAL_ASSEMBLY));
  PetscCall(PCSetOperators(pc, A, A));
  PetscCall(PetscPushErrorHandler(PetscReturnErrorHandler, nullptr));
  PetscErrorCode ierr = PCSetUp(pc);
  if (!ierr) ierr = asm_pc ? PCASMGetSubKSP(pc, &nlocal, &first, &sub) : PCBJacobiGetSubKSP(pc, &nlocal, &first, &sub);
  PetscCall(PetscPopErrorHandler());
  *memory = kLean;
  PetscBool factor = PETSC_FALSE;
  if (!ierr && nlocal > 0) {
    PC subpc;
    PetscCall(KSPSetFromOptions(sub[0]));
    PetscCall(KSPGetPC(sub[0], &subpc));
    PetscCall(IsFactor(subpc, &factor));
  }
  PetscInt any = factor ? 1 : 0;  // every rank's blocks decide alike
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &any, 1, MPIU_INT, MPI_MAX, comm));
  if (any) *memory = {asm_pc ? "additive Schwarz with factored blocks" : "block Jacobi with factored blocks",
                      kDirect.kb_per_dof};
  PetscCall(MatDestroy(&A));
  PetscFunctionReturn(0);
}

// The path as PETSc builds it from the options: a KSP configured as the solver's is (CreateSolver:
// preonly + LU, then the options), classified by its types. PC redundant holds the whole system
// once per rank group and is a direct solve when its inner PC factors.
PetscErrorCode Classify(MPI_Comm comm, LinearPath *path) {
  KSP ksp;
  PC pc;
  PetscBool redundant, bjacobi, asm_pc, preonly;
  PathMemory memory = kLean;
  PetscBool help = PETSC_FALSE;
  PetscFunctionBeginUser;
  PetscCall(KSPCreate(comm, &ksp));
  PetscCall(KSPSetType(ksp, KSPPREONLY));
  PetscCall(KSPGetPC(ksp, &pc));
  PetscCall(PCSetType(pc, PCLU));
  // -help lists a section of options once, the first time an object reads it: the solver's own
  // KSP and PC are to list theirs (with the defaults the solver sets), so with -help the probe
  // takes the two types the options name and reads nothing else (nothing is solved, and the memory
  // check, which needs the inner solvers, does not run).
  PetscCall(PetscOptionsHasName(nullptr, nullptr, "-help", &help));
  if (help) {
    char type[64];
    PetscBool set;
    PetscCall(PetscOptionsGetString(nullptr, nullptr, "-ksp_type", type, sizeof type, &set));
    if (set) PetscCall(KSPSetType(ksp, type));
    PetscCall(PetscOptionsGetString(nullptr, nullptr, "-pc_type", type, sizeof type, &set));
    if (set) PetscCall(PCSetType(pc, type));
  } else {
    PetscCall(KSPSetFromOptions(ksp));
  }
  PetscCall(PetscObjectTypeCompare((PetscObject)ksp, KSPPREONLY, &preonly));
  PetscCall(PetscObjectTypeCompare((PetscObject)pc, PCREDUNDANT, &redundant));
  PetscCall(PetscObjectTypeCompare((PetscObject)pc, PCBJACOBI, &bjacobi));
  PetscCall(PetscObjectTypeCompare((PetscObject)pc, PCASM, &asm_pc));
  PetscBool factor;
  PetscCall(IsFactor(pc, &factor));
  path->factor = factor;
  path->krylov_named = !preonly;
  path->copies = 1.0;
  if (help) {
    PetscCall(KindOfPC(pc, &path->kind, &memory));
  } else if (redundant) {
    KSP inner;
    PC inner_pc;
    PetscMPIInt size, inner_size;
    PetscCall(PCRedundantGetKSP(pc, &inner));
    PetscCall(KSPSetFromOptions(inner));
    PetscCall(KSPGetPC(inner, &inner_pc));
    PetscCall(KindOfPC(inner_pc, &path->kind, &memory));
    if (path->kind != LinearPath::Kind::direct_lu) path->kind = LinearPath::Kind::krylov_other;
    PetscCallMPI(MPI_Comm_size(comm, &size));
    PetscCallMPI(MPI_Comm_size(PetscObjectComm((PetscObject)inner), &inner_size));
    path->copies = (double)size / inner_size;
    static char name[160];  // the path's name for the memory check's message, made once per run
    std::snprintf(name, sizeof name, "%s of the whole system on each of %d rank group(s) (PC redundant)",
                  memory.name, (int)path->copies);
    memory.name = name;
  } else if (bjacobi || asm_pc) {
    PetscCall(MemoryOfBlocks(pc, asm_pc, &memory));
    path->kind = LinearPath::Kind::krylov_other;
  } else {
    PetscCall(KindOfPC(pc, &path->kind, &memory));
  }
  path->memory_name = memory.name;
  path->kb_per_dof = memory.kb_per_dof;
  PetscCall(KSPDestroy(&ksp));
  PetscFunctionReturn(0);
}

// Measured (-log_view, MatLUFactorNum per factorization): PD15a, 2 340 DOF: PETSc's LU 1.25 ms
// against MUMPS's ~4.5 ms (its analysis and distribution overheads dominate a small system);
// Hencky, 5 403 DOF: 15 vs 10 ms; DD1511 on 10^4 triangles, 30 k DOF: 35 vs 23 ms. Whenever MUMPS
// factors, its workspace margin ICNTL(14) defaults to 200 % unless the options set it: the stiff
// contact penalties delay pivots and need more than MUMPS's own 20 %.
PetscErrorCode ChooseLUPackage(MPI_Comm comm, LinearPath *path) {
  char pkg[64] = "";
  PetscBool pkg_set = PETSC_FALSE, icntl14 = PETSC_FALSE;
  PetscInt max_dof;
  PetscFunctionBeginUser;
  PetscCall(LUNativeMaxDofFromOptions(comm, &max_dof));
  PetscCall(PetscOptionsGetString(nullptr, nullptr, "-pc_factor_mat_solver_type", pkg, sizeof pkg, &pkg_set));
  // Where the options name no package: the solver set-up puts this one on its PC.
  path->lu_package_named = pkg_set;
  path->lu_native = !pkg_set && path->ranks == 1 && path->dof <= max_dof;
  path->mumps = path->factor && (pkg_set ? !std::strcmp(pkg, MATSOLVERMUMPS) : !path->lu_native);
  // Asking reads the option: a -mat_mumps_icntl_14 that does not apply (options/solvers/mumps_lu.opts
  // sets it, then another package or PC is chosen) is not reported as never used at the end.
  PetscCall(PetscOptionsHasName(nullptr, nullptr, "-mat_mumps_icntl_14", &icntl14));
  if (path->mumps && !icntl14) {
    PetscCall(PetscOptionsSetValue(nullptr, "-mat_mumps_icntl_14", "200"));
    // The program's own default, not the user's: read here, so that a run in which MUMPS never
    // factors (every increment converged without a Newton step) does not call it never used.
    PetscCall(PetscOptionsHasName(nullptr, nullptr, "-mat_mumps_icntl_14", &icntl14));
  }
  PetscFunctionReturn(0);
}

} // namespace

const char *LinearPathKindName(LinearPath::Kind kind) {
  switch (kind) {
  case LinearPath::Kind::direct_lu: return "direct LU";
  case LinearPath::Kind::krylov_amg: return "Krylov + AMG";
  case LinearPath::Kind::krylov_other: return "Krylov";
  case LinearPath::Kind::unassembled: return "unassembled (BDDC)";
  }
  return "?";
}

PetscErrorCode LUNativeMaxDofFromOptions(MPI_Comm comm, PetscInt *max_dof) {
  PetscFunctionBeginUser;
  *max_dof = 0;
  PetscOptionsBegin(comm, nullptr, "Linear solver", "PC");
  PetscCall(PetscOptionsInt(
      "-etfe_lu_native_max_dof",
      "On one rank, systems up to this many DOF are factored with PETSc's own LU (AMD ordering) "
      "unless -pc_factor_mat_solver_type names a package; 0: always MUMPS",
      "", *max_dof, max_dof, nullptr));
  PetscOptionsEnd();
  PetscFunctionReturn(0);
}

PetscErrorCode DecideLinearPath(MPI_Comm comm, PetscInt dof, LinearPath *path) {
  PetscInt choice = kAuto, min_dof = kMemoryMinDof, min_ranks = 16;
  PetscBool krylov = PETSC_FALSE, mat_set = PETSC_FALSE, min_dof_set = PETSC_FALSE;
  PetscFunctionBeginUser;
  *path = LinearPath();
  path->dof = dof;
  PetscCallMPI(MPI_Comm_size(comm, &path->ranks));
  // Where the measurements on this rank count show the scalable path faster at every larger size
  // measured, it is taken from there; elsewhere from where the direct path stops fitting.
  const Crossover crossover = MeasuredCrossover(path->ranks, kScalableFile);
  if (crossover.dof > 0) min_dof = std::min(min_dof, crossover.dof);
  PetscOptionsBegin(comm, nullptr, "Linear solver path", "KSP");
  PetscCall(PetscOptionsEList("-etfe_solver",
                              "auto: the options' (direct) solver below the thresholds, the scalable path (FGMRES + "
                              "GAMG) above; direct: the options as given; scalable: always the scalable path",
                              "", kChoiceNames, 3, kChoiceNames[choice], &choice, nullptr));
  PetscCall(PetscOptionsInt("-etfe_scalable_min_dof",
                            "auto: the scalable path from this many DOF (default: the crossover measured on this rank "
                            "count where there is one, else 3000000, where MUMPS stops fitting a node)",
                            "", min_dof, &min_dof, &min_dof_set));
  PetscCall(PetscOptionsInt("-etfe_scalable_min_ranks", "auto: the scalable path from this many ranks", "", min_ranks,
                            &min_ranks, nullptr));
  PetscOptionsEnd();
  PetscCall(NamesKrylov(&krylov));
  const bool big = dof >= min_dof, many = path->ranks >= min_ranks;
  path->scalable = choice == kScalable || (choice == kAuto && !krylov && (big || many));
  path->automatic = path->scalable && choice == kAuto;
  char why[320];
  if (path->scalable) {
    PetscCall(ApplyScalablePath());
    if (choice == kScalable)
      std::snprintf(why, sizeof why, "scalable path (FGMRES + GAMG), as -etfe_solver asks");
    else if (big && !min_dof_set && crossover.dof > 0 && min_dof == crossover.dof)
      std::snprintf(why, sizeof why,
                    "scalable path (FGMRES + GAMG) chosen automatically: %" PetscInt_FMT
                    " DOF on %d rank(s), from the crossover measured here at %" PetscInt_FMT
                    " DOF (docs/solvers.md; -etfe_solver direct keeps the direct solver)",
                    dof, path->ranks, crossover.dof);
    else
      std::snprintf(why, sizeof why,
                    "scalable path (FGMRES + GAMG) chosen automatically: %" PetscInt_FMT
                    " DOF on %d rank(s), %s -etfe_scalable_min_%s %" PetscInt_FMT
                    " (-etfe_solver direct keeps the direct solver)",
                    dof, path->ranks, big ? "from" : "ranks from", big ? "dof" : "ranks", big ? min_dof : min_ranks);
    PetscCall(PetscPrintf(comm, "  linear solver: %s\n", why));
  } else if (choice == kDirectChoice || krylov) {
    std::snprintf(why, sizeof why, "the options' solver (%s)",
                  choice == kDirectChoice ? "-etfe_solver direct" : "-etfe_solver auto: they name a Krylov method");
  } else if (crossover.rows > 0) {
    std::snprintf(why, sizeof why,
                  "the options' solver: %" PetscInt_FMT " DOF below -etfe_scalable_min_dof %" PetscInt_FMT
                  "; measured on %d rank(s) up to %" PetscInt_FMT " DOF, the scalable path %s",
                  dof, min_dof, path->ranks, crossover.measured_max,
                  crossover.dof > 0 ? "faster from the crossover" : "slower at every size");
  } else {
    std::snprintf(why, sizeof why,
                  "the options' solver: %" PetscInt_FMT " DOF below -etfe_scalable_min_dof %" PetscInt_FMT
                  "; no crossover measured on %d rank(s)",
                  dof, min_dof, path->ranks);
  }
  path->why = why;
  PetscCall(PetscInfo(nullptr, "linear path: %s\n", why));
  PetscCall(Classify(comm, path));
  path->outer_krylov = path->krylov_named;
  PetscCall(PetscOptionsHasName(nullptr, nullptr, "-mat_type", &mat_set));
  path->mat_type_named = mat_set;
  PetscCall(ChooseLUPackage(comm, path));
  PetscFunctionReturn(0);
}

void LinearPathTakeNeeds(LinearPath *path, const TermSolverNeeds &needs) {
  path->needs = needs;
  path->outer_krylov = path->krylov_named || needs.krylov_outer;
}

} // namespace etfe
