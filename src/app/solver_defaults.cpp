// Solver defaults (solver_defaults.h).
#include "solver_defaults.h"

#include <cstring>

#include "etfe/assembly/assembly.h"
#include "etfe/solver/linesearch.h"
#include "etfe/solver/pc_refresh.h"
#include "etfe/solver/pc_shift.h"
#include "etfe/solver/tangent_shift.h"

namespace etfe {

// The package the linear path chose (linear_path.h) where the options name none.
PetscErrorCode ChooseLUPackage(Problem *P, PC pc) {
  PetscFunctionBeginUser;
  const LinearPath &path = P->linear_path;
  if (path.lu_native) {
    PetscCall(PCFactorSetMatSolverType(pc, MATSOLVERPETSC));
    PetscCall(PCFactorSetMatOrderingType(pc, MATORDERINGAMD));
  } else if (!path.lu_package_named) {
    PetscCall(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS));
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
  LinearPathTakeNeeds(&P->linear_path, ProblemSolverNeeds(*P));
  const bool lrc = P->linear_path.needs.krylov_outer;
  PetscCall(SNESSetJacobian(*snes, lrc && P->linear_path.needs.outer ? P->linear_path.needs.outer : P->J, P->J,
                            FormShiftedJacobian, P));
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
