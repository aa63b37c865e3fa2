// Solver defaults (solver_defaults.h).
#include "solver_defaults.h"

#include <cstring>

#include "etfe/assembly.h"
#include "etfe/linesearch.h"
#include "etfe/pc_refresh.h"
#include "etfe/pc_shift.h"
#include "etfe/tangent_shift.h"

namespace etfe {

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

// Measured (-log_view, MatLUFactorNum per factorization): PD15a, 2 340 DOF: PETSc's LU 1.25 ms
// against MUMPS's ~4.5 ms (its analysis and distribution overheads dominate a small system);
// Hencky, 5 403 DOF: 15 vs 10 ms; DD1511 on 10^4 triangles, 30 k DOF: 35 vs 23 ms. Whenever MUMPS
// factors, its workspace margin ICNTL(14) defaults to 200 % unless the options set it: the stiff
// contact penalties delay pivots and need more than MUMPS's own 20 %.
PetscErrorCode ChooseLUPackage(Problem *P, PC pc) {
  char pkg[64] = "", pctype[64] = "";
  PetscBool pkg_set = PETSC_FALSE, pc_set = PETSC_FALSE, icntl14 = PETSC_FALSE;
  PetscInt max_dof;
  PetscFunctionBeginUser;
  PetscCall(LUNativeMaxDofFromOptions(P->comm, &max_dof));
  PetscCall(PetscOptionsGetString(nullptr, nullptr, "-pc_factor_mat_solver_type", pkg, sizeof pkg,
                                  &pkg_set));
  PetscCall(PetscOptionsGetString(nullptr, nullptr, "-pc_type", pctype, sizeof pctype, &pc_set));
  const bool native = P->size == 1 && 3 * P->mesh.num_nodes_global <= max_dof;
  if (!pkg_set) {
    PetscCall(PCFactorSetMatSolverType(pc, native ? MATSOLVERPETSC : MATSOLVERMUMPS));
    if (native) PetscCall(PCFactorSetMatOrderingType(pc, MATORDERINGAMD));
  }
  const bool factor = !pc_set || !std::strcmp(pctype, PCLU) || !std::strcmp(pctype, PCCHOLESKY);
  const bool mumps = factor && (pkg_set ? !std::strcmp(pkg, MATSOLVERMUMPS) : !native);
  // Asking reads the option: a -mat_mumps_icntl_14 that does not apply (options/solvers/mumps_lu.opts
  // sets it, then another package or PC is chosen) is not reported as never used at the end.
  PetscCall(PetscOptionsHasName(nullptr, nullptr, "-mat_mumps_icntl_14", &icntl14));
  if (mumps && !icntl14) {
    PetscCall(PetscOptionsSetValue(nullptr, "-mat_mumps_icntl_14", "200"));
    // The program's own default, not the user's: read here, so that a run in which MUMPS never
    // factors (every increment converged without a Newton step) does not call it never used.
    PetscCall(PetscOptionsHasName(nullptr, nullptr, "-mat_mumps_icntl_14", &icntl14));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode CreateSolver(Problem *P, SNES *snes) {
  KSP ksp;
  PC pc;
  SNESLineSearch ls;
  Vec F;
  PetscFunctionBeginUser;
  PetscCall(SNESCreate(P->comm, snes));
  PetscCall(VecDuplicate(P->U, &F));
  PetscCall(SNESSetFunction(*snes, F, FormResidual, P));
  PetscCall(VecDestroy(&F));
  // Sealed gas chambers: Newton's matrix is the sparse tangent plus their rank-one stiffness
  // (chamber.h), solved by GMRES preconditioned with the sparse tangent's factorization.
  const TermSolverNeeds needs = ProblemSolverNeeds(*P);
  const bool lrc = needs.krylov_outer;
  PetscCall(SNESSetJacobian(*snes, needs.outer ? needs.outer : P->J, P->J, FormShiftedJacobian, P));
  PetscCall(SNESSetType(*snes, SNESNEWTONLS));
  PetscCall(SNESSetTolerances(*snes, 1e-9, 1e-10, 1e-14, 30, 10000));
  PetscCall(SNESGetKSP(*snes, &ksp));
  PetscCall(KSPSetType(ksp, lrc ? KSPGMRES : KSPPREONLY));
  if (lrc) PetscCall(KSPSetTolerances(ksp, 1e-12, 1e-50, PETSC_DEFAULT, 50));
  PetscCall(KSPGetPC(ksp, &pc));
  PetscCall(PCSetType(pc, PCLU));
  PetscCall(ChooseLUPackage(P, pc));
  PetscCall(SNESGetLineSearch(*snes, &ls));
  PetscCall(SNESLineSearchSetType(ls, SNESLINESEARCHETFE));
  PetscCall(SNESSetFromOptions(*snes));
  if (lrc) {
    // A direct solve alone (-ksp_type preonly, as the solver files set) would drop the sealed gas's
    // rank-one stiffness and cost Newton its quadratic rate: GMRES adds it back, preconditioned by
    // that same factorization (chambers + 1 iterations).
    KSPType type;
    PetscCall(KSPGetType(ksp, &type));
    if (!std::strcmp(type, KSPPREONLY)) {
      PetscCall(KSPSetType(ksp, KSPGMRES));
      PetscCall(KSPSetTolerances(ksp, 1e-12, 1e-50, PETSC_DEFAULT, 50));
      PetscCall(PetscInfo(ksp, "sealed gas chambers: KSP preonly replaced by GMRES on the rank-one-updated tangent\n"));
    }
  }
  PetscCall(PcShiftSetUp(P, *snes));
  PetscCall(PcRefreshSetUp(P, *snes));
  PetscCall(SNESGetLineSearch(*snes, &ls));
  PetscCall(SNESLineSearchEtfeSetProblem(ls, P));
  PetscFunctionReturn(0);
}

} // namespace etfe
