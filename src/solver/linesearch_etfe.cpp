// The "etfe" line search. Newton on membranes fails in recognisable ways: a full step folds an
// element through itself (a slack region), the linear solve is inaccurate (stiff penalties,
// near-singular tangents), or the residual grows far from the solution. This line search
//   1. checks the true residual |J y - F| / |F| of the Newton direction (warns, fails when large;
//      with an inexact Newton method, -snes_ksp_ew, against what the Krylov solve was asked for);
//   2. caps the largest nodal update at -snes_linesearch_etfe_max_update (mm);
//   3. halves the step while the trial collapses or flips an element or gives a non-finite
//      residual (the "domain" of the membrane);
//   4. backtracks on |F| (sufficient decrease, Armijo with c = 1e-4); if no step decreases it
//      within max_it halvings the best decreasing one is taken, else the search fails and the
//      load stepper cuts the increment back.
// Registered like PETSc's own types (see linesearchbt.c): one file, a create function, options
// under -snes_linesearch_etfe_.
#include <petsc/private/linesearchimpl.h>
#include <petsc/private/snesimpl.h>

#include <cmath>

#include "etfe/assembly/assembly.h"
#include "etfe/kernels/status.h"
#include "etfe/solver/linesearch.h"

namespace etfe {

namespace {

struct EtfeLineSearch {
  Problem *problem = nullptr;
  PetscReal max_update = 0.0;  // mm; 0 = no cap
  PetscReal max_strain_update = 0.0;  // largest |Y_a - Y_b| / |X_a - X_b| over edges; 0 = no cap
  PetscReal linear_warn = 1e-6, linear_fail = 1e-2;
  PetscBool check_linear = PETSC_TRUE;
  PetscReal armijo = 1e-4;
  // Inexact Newton (-snes_ksp_ew): the Krylov solve is asked for |J y - F| <= eta_k |F| only, eta_k
  // up to 0.9 far from the answer; the check then fails a direction only past inexact_factor
  // eta_k, and never accepts one past inexact_max (nearer 1, y is hardly a descent direction).
  PetscReal inexact_factor = 10.0, inexact_max = 0.9;
};

// The forcing term eta_k the Krylov solve was asked for (its relative tolerance, which
// Eisenstat-Walker sets before each solve), or 0 when Newton's directions are meant to be exact.
PetscErrorCode ForcingTerm(SNES snes, PetscReal *eta) {
  PetscBool ew;
  KSP ksp;
  PetscFunctionBeginUser;
  *eta = 0.0;
  PetscCall(SNESKSPGetUseEW(snes, &ew));
  if (!ew) PetscFunctionReturn(0);
  PetscCall(SNESGetKSP(snes, &ksp));
  PetscCall(KSPGetTolerances(ksp, eta, nullptr, nullptr, nullptr));
  PetscFunctionReturn(0);
}

// r is scratch (the line search's trial residual, overwritten by the trials that follow). eta:
// the forcing term (ForcingTerm); *rel: |J y - F| / |F| (eta when the check is off).
PetscErrorCode CheckLinearResidual(SNESLineSearch ls, EtfeLineSearch *d, Vec F, Vec Y, Vec r,
                                   PetscReal fnorm, PetscReal eta, PetscReal *rel, PetscBool *ok) {
  SNES snes;
  Mat J;
  PetscReal rnorm;
  PetscFunctionBeginUser;
  *ok = PETSC_TRUE;
  *rel = eta;
  PetscCall(SNESLineSearchGetSNES(ls, &snes));
  PetscCall(SNESGetJacobian(snes, &J, nullptr, nullptr, nullptr));
  if (!d->check_linear || !J || fnorm == 0.0) PetscFunctionReturn(0);
  PetscCall(MatMult(J, Y, r));
  PetscCall(VecAXPY(r, -1.0, F));
  PetscCall(VecNorm(r, NORM_2, &rnorm));
  *rel = rnorm / fnorm;
  const PetscReal bound = PetscMax(d->linear_fail, PetscMin(d->inexact_max, d->inexact_factor * eta));
  if (!(*rel <= bound)) {
    if (eta > 0)
      PetscCall(PetscPrintf(PetscObjectComm((PetscObject)ls),
                            "  line search: linear solve inaccurate, |J y - F|/|F| = %.3e > %.1e (inexact Newton: "
                            "asked for %.1e; the preconditioner does not carry this tangent: -ksp_max_it, "
                            "-snes_ksp_ew_rtolmax)\n",
                            (double)*rel, (double)bound, (double)eta));
    else
      PetscCall(PetscPrintf(PetscObjectComm((PetscObject)ls),
                            "  line search: linear solve inaccurate, |J y - F|/|F| = %.3e > %.1e "
                            "(singular or ill-conditioned tangent: check supports, penalties, "
                            "-pc_factor_mat_solver_type)\n",
                            (double)*rel, (double)bound));
    *ok = PETSC_FALSE;
  } else if (*rel > d->linear_warn) {
    PetscCall(PetscInfo(ls, "linear solve residual |J y - F|/|F| = %g (forcing term %g)\n", (double)*rel, (double)eta));
  }
  PetscFunctionReturn(0);
}

// The first step length: 1, capped so that no node moves more than max_update (mm) and no edge
// changes its length by more than max_strain_update.
PetscErrorCode InitialStepLength(SNESLineSearch ls, EtfeLineSearch *d, Vec Y, PetscReal *lambda) {
  Problem *P = d->problem;
  PetscFunctionBeginUser;
  *lambda = 1.0;
  if (d->max_update > 0.0) {
    PetscReal ymax;
    PetscCall(VecMaxNodalNorm(Y, &ymax));
    if (ymax > d->max_update) {
      *lambda = d->max_update / ymax;
      PetscCall(PetscInfo(ls, "step capped: largest nodal update %g > %g\n", (double)ymax,
                          (double)d->max_update));
    }
  }
  if (d->max_strain_update > 0.0 && P) {
    PetscReal g;
    PetscCall(LargestUpdateGradient(P, Y, &g));
    if (*lambda * g > d->max_strain_update) {
      PetscCall(PetscInfo(ls, "step capped: largest edge strain update %g > %g\n", (double)(*lambda * g),
                          (double)d->max_strain_update));
      *lambda = d->max_strain_update / g;
    }
  }
  PetscFunctionReturn(0);
}

// What backtracking found: the accepted step (lambda, |F| there) or, when none passed the
// Armijo test, the trial with the smallest finite |F|.
struct Backtracking {
  PetscBool accepted = PETSC_FALSE;
  PetscReal lambda = 1.0, gnorm = 0.0;
  PetscReal best_lambda = -1.0, best_norm = PETSC_MAX_REAL;
};

// Halves the step from b->lambda while the trial W = X - lambda Y collapses or flips an element,
// makes the residual G non-finite, or does not decrease |F| sufficiently: Armijo, |G| <= (1 - c
// lambda (1 - eta)) |F| with eta the direction's linear residual |J y - F|/|F| under inexact Newton
// (Eisenstat and Walker's globalization: the linear model itself promises only that much
// decrease), 0 otherwise.
PetscErrorCode Backtrack(SNESLineSearch ls, EtfeLineSearch *d, Vec X, Vec Y, Vec W, Vec G, PetscReal fnorm,
                         PetscReal eta, Backtracking *b) {
  Problem *P = d->problem;
  SNES snes;
  PetscBool ok;
  PetscFunctionBeginUser;
  PetscCall(SNESLineSearchGetSNES(ls, &snes));
  for (PetscInt it = 0; it <= ls->max_its && !b->accepted; ++it, b->lambda *= 0.5) {
    PetscCall(VecWAXPY(W, -b->lambda, Y, X));
    if (P) {
      PetscCall(CheckStep(P, X, W, &ok));
      if (!ok) {
        PetscCall(PetscInfo(ls, "lambda %g refused: element %" PetscInt_FMT " would collapse or flip\n",
                            (double)b->lambda, P->diagnostics.bad_element));
        continue;
      }
      P->diagnostics.in_linesearch = PETSC_TRUE;
    }
    PetscCall((*ls->ops->snesfunc)(snes, W, G));
    if (P) {
      P->diagnostics.in_linesearch = PETSC_FALSE;
      if (P->diagnostics.bad_status != KERNEL_OK) continue;
    }
    PetscCall(VecNorm(G, NORM_2, &b->gnorm));
    PetscViewer monitor;
    PetscCall(SNESLineSearchGetDefaultMonitor(ls, &monitor));
    if (monitor)
      PetscCall(PetscViewerASCIIPrintf(monitor, "    Line search etfe: lambda %g |F| %.6e -> %.6e\n",
                                       (double)b->lambda, (double)fnorm, (double)b->gnorm));
    if (PetscIsInfOrNanReal(b->gnorm)) continue;
    if (b->gnorm <= (1.0 - d->armijo * b->lambda * (1.0 - eta)) * fnorm) {
      b->accepted = PETSC_TRUE;
      break;
    }
    if (b->gnorm < b->best_norm) b->best_norm = b->gnorm, b->best_lambda = b->lambda;
  }
  PetscFunctionReturn(0);
}

PetscErrorCode Apply(SNESLineSearch ls) {
  EtfeLineSearch *d = (EtfeLineSearch *)ls->data;
  Problem *P = d->problem;
  SNES snes;
  Vec X, F, Y, W, G;
  PetscReal fnorm, xnorm, ynorm;
  PetscBool ok;
  Backtracking b;
  PetscFunctionBeginUser;
  PetscCall(SNESLineSearchGetSNES(ls, &snes));
  PetscCall(SNESLineSearchGetVecs(ls, &X, &F, &Y, &W, &G));
  PetscCall(SNESLineSearchGetNorms(ls, &xnorm, &fnorm, &ynorm));
  PetscCall(SNESLineSearchSetReason(ls, SNES_LINESEARCH_SUCCEEDED));
  if (ls->norms) PetscCall(VecNorm(F, NORM_2, &fnorm));

  PetscReal eta, rel;
  PetscCall(ForcingTerm(snes, &eta));
  PetscCall(CheckLinearResidual(ls, d, F, Y, G, fnorm, eta, &rel, &ok));
  if (!ok) {
    PetscCall(SNESLineSearchSetReason(ls, SNES_LINESEARCH_FAILED_USER));
    PetscFunctionReturn(0);
  }
  PetscCall(InitialStepLength(ls, d, Y, &b.lambda));
  PetscCall(Backtrack(ls, d, X, Y, W, G, fnorm, eta > 0 ? PetscMin(rel, d->inexact_max) : 0.0, &b));
  if (!b.accepted) {
    if (b.best_lambda > 0.0 && b.best_norm < fnorm) {
      b.lambda = b.best_lambda;
      PetscCall(VecWAXPY(W, -b.lambda, Y, X));
      PetscCall((*ls->ops->snesfunc)(snes, W, G));
      PetscCall(VecNorm(G, NORM_2, &b.gnorm));
    } else {
      PetscCall(SNESLineSearchSetReason(ls, (P && P->diagnostics.bad_status != KERNEL_OK)
                                                ? SNES_LINESEARCH_FAILED_DOMAIN
                                                : SNES_LINESEARCH_FAILED_REDUCT));
      PetscFunctionReturn(0);
    }
  }
  PetscCall(VecCopy(W, X));
  PetscCall(VecCopy(G, F));
  PetscCall(SNESLineSearchSetLambda(ls, b.lambda));
  PetscCall(VecNorm(X, NORM_2, &xnorm));
  PetscCall(VecNorm(Y, NORM_2, &ynorm));
  PetscCall(SNESLineSearchSetNorms(ls, xnorm, b.gnorm, b.lambda * ynorm));
  PetscFunctionReturn(0);
}

PetscErrorCode SetFromOptions(SNESLineSearch ls, PetscOptionItems *PetscOptionsObject) {
  EtfeLineSearch *d = (EtfeLineSearch *)ls->data;
  PetscFunctionBeginUser;
  PetscOptionsHeadBegin(PetscOptionsObject, "SNES line search etfe");
  PetscCall(PetscOptionsReal("-snes_linesearch_etfe_max_update",
                             "Largest nodal displacement update per Newton iteration [mm] (0: none)",
                             "", d->max_update, &d->max_update, nullptr));
  PetscCall(PetscOptionsReal("-snes_linesearch_etfe_max_strain_update",
                             "Largest relative change of an element edge per Newton iteration, |dU_a - dU_b|/|X_a - X_b| "
                             "(a cap that means the same on every mesh density; 0: none)",
                             "", d->max_strain_update, &d->max_strain_update, nullptr));
  PetscCall(PetscOptionsBool("-snes_linesearch_etfe_check_linear",
                             "Check the true residual of the linear solve", "", d->check_linear,
                             &d->check_linear, nullptr));
  PetscCall(PetscOptionsReal("-snes_linesearch_etfe_linear_fail",
                             "Fail the step when |J y - F|/|F| exceeds this", "", d->linear_fail,
                             &d->linear_fail, nullptr));
  PetscCall(PetscOptionsReal("-snes_linesearch_etfe_inexact_factor",
                             "Inexact Newton (-snes_ksp_ew): fail the step when |J y - F|/|F| exceeds this many times "
                             "the forcing term the Krylov solve was asked for (and -snes_linesearch_etfe_linear_fail)",
                             "", d->inexact_factor, &d->inexact_factor, nullptr));
  PetscCall(PetscOptionsReal("-snes_linesearch_etfe_inexact_max",
                             "Inexact Newton (-snes_ksp_ew): never accept a direction with |J y - F|/|F| above this "
                             "(< 1: a descent direction for |F|)",
                             "", d->inexact_max, &d->inexact_max, nullptr));
  PetscCheck(d->inexact_factor >= 1 && d->inexact_max > 0 && d->inexact_max < 1, PetscObjectComm((PetscObject)ls),
             PETSC_ERR_ARG_OUTOFRANGE,
             "-snes_linesearch_etfe_inexact_factor %g, -snes_linesearch_etfe_inexact_max %g: give a factor >= 1 and "
             "a bound in (0, 1)",
             (double)d->inexact_factor, (double)d->inexact_max);
  PetscOptionsHeadEnd();
  PetscFunctionReturn(0);
}

PetscErrorCode View(SNESLineSearch ls, PetscViewer viewer) {
  EtfeLineSearch *d = (EtfeLineSearch *)ls->data;
  PetscBool ascii;
  PetscFunctionBeginUser;
  PetscCall(PetscObjectTypeCompare((PetscObject)viewer, PETSCVIEWERASCII, &ascii));
  if (ascii)
    PetscCall(PetscViewerASCIIPrintf(viewer, "  max nodal update %g mm, max edge strain update %g, linear check %s\n",
                                     (double)d->max_update, (double)d->max_strain_update,
                                     d->check_linear ? "on" : "off"));
  PetscFunctionReturn(0);
}

PetscErrorCode Destroy(SNESLineSearch ls) {
  PetscFunctionBeginUser;
  delete (EtfeLineSearch *)ls->data;
  ls->data = nullptr;
  PetscFunctionReturn(0);
}

PetscErrorCode Create(SNESLineSearch ls) {
  PetscFunctionBeginUser;
  ls->ops->apply = Apply;
  ls->ops->destroy = Destroy;
  ls->ops->setfromoptions = SetFromOptions;
  ls->ops->view = View;
  ls->ops->reset = nullptr;
  ls->data = new EtfeLineSearch();
  ls->max_its = 25;  // halvings down to lambda ~ 3e-8: stiff penalties need small first steps
  PetscFunctionReturn(0);
}

} // namespace

PetscErrorCode SNESLineSearchRegisterEtfe(void) {
  static bool done = false;
  PetscFunctionBeginUser;
  if (done) PetscFunctionReturn(0);
  done = true;
  PetscCall(SNESLineSearchRegister(SNESLINESEARCHETFE, Create));
  PetscFunctionReturn(0);
}

PetscErrorCode SNESLineSearchEtfeSetProblem(SNESLineSearch ls, Problem *problem) {
  PetscBool match;
  PetscFunctionBeginUser;
  PetscCall(PetscObjectTypeCompare((PetscObject)ls, SNESLINESEARCHETFE, &match));
  if (match) ((EtfeLineSearch *)ls->data)->problem = problem;
  PetscFunctionReturn(0);
}

} // namespace etfe
