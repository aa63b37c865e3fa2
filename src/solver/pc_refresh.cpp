// The preconditioner refreshed when the Krylov solve struggles (pc_refresh.h).
#include "etfe/solver/pc_refresh.h"

#include <petsc/private/snesimpl.h>

#include "etfe/base/owned_context.h"

namespace etfe {

namespace {

struct PcRefresh {
  SNES snes;  // not referenced (the hook lives on the SNES's own KSP): read for its inexact Newton state
  PetscInt max_its;
  PetscInt refreshes = 0;
};

PetscErrorCode AfterKrylovSolve(KSP ksp, Vec b, Vec x, void *ctx) {
  auto *c = (PcRefresh *)ctx;
  KSPConvergedReason reason;
  PetscInt its;
  PetscBool ew;
  PetscFunctionBeginUser;
  // The KSP has one post-solve hook, and inexact Newton's (-snes_ksp_ew) is where Eisenstat-Walker
  // records the last solve's tolerance and residual for the next forcing term: without it the
  // forcing term stays at its loose first value and Newton crawls (Hencky, BoomerAMG: the first
  // increment not converged in 30 iterations, against 17 without the lagged preconditioner).
  PetscCall(SNESKSPGetUseEW(c->snes, &ew));
  if (ew) PetscCall(KSPPostSolve_SNESEW(ksp, b, x, c->snes));
  PetscCall(KSPGetConvergedReason(ksp, &reason));
  PetscCall(KSPGetIterationNumber(ksp, &its));
  if (reason < 0 || its > c->max_its) {
    // -2: rebuilt at the next Jacobian evaluation, then "never" again until the next struggle.
    PetscCall(SNESSetLagPreconditioner(c->snes, -2));
    ++c->refreshes;
    PetscCall(PetscInfo(ksp, "Krylov solve took %" PetscInt_FMT " iterations (%s): preconditioner rebuilt next (%" PetscInt_FMT " so far)\n",
                        its, KSPConvergedReasons[reason], c->refreshes));
  }
  PetscFunctionReturn(0);
}

} // namespace

PetscErrorCode KrylovSolveFailed(SNES snes, PetscBool *failed) {
  SNESConvergedReason reason;
  KSPConvergedReason kreason;
  KSP ksp;
  PetscBool preonly;
  PetscFunctionBeginUser;
  PetscCall(SNESGetConvergedReason(snes, &reason));
  PetscCall(SNESGetKSP(snes, &ksp));
  PetscCall(PetscObjectTypeCompare((PetscObject)ksp, KSPPREONLY, &preonly));
  PetscCall(KSPGetConvergedReason(ksp, &kreason));
  *failed = reason == SNES_DIVERGED_LINEAR_SOLVE && !preonly && kreason != KSP_DIVERGED_PC_FAILED ? PETSC_TRUE
                                                                                                    : PETSC_FALSE;
  PetscFunctionReturn(0);
}

PetscErrorCode PcRefreshSetUp(Problem *P, SNES snes) {
  PetscInt n = 0;
  KSP ksp;
  PetscFunctionBeginUser;
  PetscOptionsBegin(P->comm, nullptr, "Preconditioner reuse (Krylov paths)", "PC");
  PetscCall(PetscOptionsInt("-etfe_pc_refresh_its",
                            "Keep the preconditioner over Newton iterations and increments; rebuild it once a Krylov "
                            "solve needs more than this many iterations or fails. 0: as -snes_lag_preconditioner says",
                            "", n, &n, nullptr));
  PetscOptionsEnd();
  PetscCheck(n >= 0, P->comm, PETSC_ERR_ARG_OUTOFRANGE,
             "-etfe_pc_refresh_its %" PetscInt_FMT ": an iteration count, >= 0 (0: off)", n);
  if (n == 0) PetscFunctionReturn(0);
  auto *c = new PcRefresh{snes, n};
  PetscCall(ComposeOwnedContext((PetscObject)snes, "etfe_pc_refresh", c));
  PetscCall(SNESSetLagPreconditioner(snes, -2));  // built at the first Jacobian, then kept
  PetscCall(SNESSetLagPreconditionerPersists(snes, PETSC_TRUE));
  // A solve that runs out of iterations with stale factors still gives a direction: the Newton
  // iteration goes on with it (the etfe line search refuses it when |J y - F|/|F| > 1e-2) and the
  // next one has fresh factors, instead of the whole increment being cut back.
  PetscCall(SNESSetMaxLinearSolveFailures(snes, PETSC_MAX_INT));
  PetscCall(SNESGetKSP(snes, &ksp));
  PetscCall(KSPSetPostSolve(ksp, AfterKrylovSolve, c));
  PetscFunctionReturn(0);
}

} // namespace etfe
