// Gauss-Newton iteration of the strip flattening (thesis eqs. 2.23-2.33): objective, residual,
// the matrix K with its own serial KSP (LU), the backtracking line search with second-order
// correction, and the stages of the boundary weight (see flatten.cpp for the formulation).

#include <algorithm>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <map>
#include <queue>
#include <string>
#include <utility>
#include <vector>

#include "etfe/kernels/flatten_link.h"
#include "etfe/kernels/status.h"
#include "flatten_internal.h"

namespace etfe {
namespace flatten {

// The flattening problem: links, their 3D lengths and weights, and the free equations.

// S(x) (eq. 2.23); KERNEL_OK or the status of the first link whose gradient is undefined.
int Objective(const Problem &p, const std::vector<double> &x, double *S, int *bad) {
  double s = 0.0;
  for (int i = 0; i < p.topo->NumLinks(); ++i) {
    const int a = p.topo->links[2 * i], b = p.topo->links[2 * i + 1];
    double c;
    const int st = FlattenLink(&x[2 * (size_t)a], &x[2 * (size_t)b], p.L[i], p.min_len2d, &c,
                               nullptr);
    if (st != KERNEL_OK) {
      if (bad) *bad = i;
      return st;
    }
    s += p.w[i] * c * c;
  }
  *S = s;
  return KERNEL_OK;
}

PetscErrorCode CreateSystem(const MeshData &m, const Problem &p, LinearSystem *ls) {
  PC pc;
  PetscFunctionBeginUser;
  // Exact preallocation: a free row couples to its own node and to every linked node.
  std::vector<PetscInt> nnz((size_t)p.nfree, 0);
  std::vector<int> degree(m.NumNodes(), 0);
  for (int i = 0; i < p.topo->NumLinks(); ++i) {
    ++degree[p.topo->links[2 * i]];
    ++degree[p.topo->links[2 * i + 1]];
  }
  for (int n = 0; n < m.NumNodes(); ++n)
    for (int d = 0; d < 2; ++d)
      if (p.eq[2 * (size_t)n + d] >= 0) nnz[(size_t)p.eq[2 * (size_t)n + d]] = 2 * (1 + degree[n]);
  PetscCall(MatCreateSeqAIJ(PETSC_COMM_SELF, p.nfree, p.nfree, 0, nnz.data(), &ls->K));
  PetscCall(MatSetOption(ls->K, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_TRUE));
  PetscCall(MatSetOption(ls->K, MAT_SYMMETRIC, PETSC_TRUE));
  PetscCall(MatCreateVecs(ls->K, &ls->dx, &ls->r));
  PetscCall(KSPCreate(PETSC_COMM_SELF, &ls->ksp));
  PetscCall(KSPSetOptionsPrefix(ls->ksp, "flatten_"));
  PetscCall(KSPSetType(ls->ksp, KSPPREONLY));
  PetscCall(KSPGetPC(ls->ksp, &pc));
  // LU rather than Cholesky: PETSc's native Cholesky on AIJ needs a natural ordering, and the
  // step with second-order terms (FlattenOptions::second_order) may be indefinite, which a
  // Cholesky factorisation (CHOLMOD) refuses with an error, not a reason the step can fall back
  // on. The ordering is approximate minimum degree: on the strips of a 10^5-triangle canopy
  // (7649 nodes each) the whole run took 5.7 s of CPU with AMD against 11.5 s with PETSc's default
  // nested dissection, 7.5 s with QMD and 11.4 s with RCM (-flatten_pc_factor_mat_ordering_type).
  PetscCall(PCSetType(pc, PCLU));
  PetscCall(PCFactorSetMatOrderingType(pc, MATORDERINGAMD));
  PetscCall(KSPSetFromOptions(ls->ksp));
  PetscFunctionReturn(0);
}

PetscErrorCode DestroySystem(LinearSystem *ls) {
  PetscFunctionBeginUser;
  PetscCall(KSPDestroy(&ls->ksp));
  PetscCall(VecDestroy(&ls->r));
  PetscCall(VecDestroy(&ls->dx));
  PetscCall(MatDestroy(&ls->K));
  PetscFunctionReturn(0);
}

// R = -A^T W C at x on the free equations (eqs. 2.31, 2.32b); KERNEL_OK or a link status.
int Residual(const Problem &p, const std::vector<double> &x, std::vector<double> *R, int *bad) {
  R->assign((size_t)p.nfree, 0.0);
  for (int i = 0; i < p.topo->NumLinks(); ++i) {
    const int a = p.topo->links[2 * i], b = p.topo->links[2 * i + 1];
    double c, g[4];
    const int st = FlattenLink(&x[2 * (size_t)a], &x[2 * (size_t)b], p.L[i], p.min_len2d, &c, g);
    if (st != KERNEL_OK) {
      *bad = i;
      return st;
    }
    const PetscInt idx[4] = {p.eq[2 * (size_t)a], p.eq[2 * (size_t)a + 1], p.eq[2 * (size_t)b],
                             p.eq[2 * (size_t)b + 1]};
    for (int k = 0; k < 4; ++k)
      if (idx[k] >= 0) (*R)[(size_t)idx[k]] -= p.w[i] * c * g[k];
  }
  return KERNEL_OK;
}

// Where each link's 4x4 block lies in K's value array (LinearSystem::slot), from K's structure.
static PetscErrorCode FindSlots(const Problem &p, LinearSystem *ls) {
  PetscInt n;
  const PetscInt *ia, *ja;
  PetscBool done;
  PetscFunctionBeginUser;
  PetscCall(MatGetRowIJ(ls->K, 0, PETSC_FALSE, PETSC_FALSE, &n, &ia, &ja, &done));
  PetscCheck(done, PETSC_COMM_SELF, PETSC_ERR_PLIB, "flattening: the structure of K is not available");
  ls->nnz = ia[n];
  ls->slot.assign(16 * (size_t)p.topo->NumLinks(), -1);
  for (int i = 0; i < p.topo->NumLinks(); ++i) {
    const int a = p.topo->links[2 * i], b = p.topo->links[2 * i + 1];
    const PetscInt idx[4] = {p.eq[2 * (size_t)a], p.eq[2 * (size_t)a + 1], p.eq[2 * (size_t)b],
                             p.eq[2 * (size_t)b + 1]};
    for (int r = 0; r < 4; ++r)
      for (int c = 0; c < 4; ++c) {
        if (idx[r] < 0 || idx[c] < 0) continue;
        const PetscInt *at = std::lower_bound(ja + ia[idx[r]], ja + ia[idx[r] + 1], idx[c]);
        PetscCheck(at != ja + ia[idx[r] + 1] && *at == idx[c], PETSC_COMM_SELF, PETSC_ERR_PLIB,
                   "flattening: an entry of link %d is missing from K's structure", i);
        ls->slot[16 * (size_t)i + 4 * r + c] = (PetscInt)(at - ja);
      }
  }
  PetscCall(MatRestoreRowIJ(ls->K, 0, PETSC_FALSE, PETSC_FALSE, &n, &ia, &ja, &done));
  PetscFunctionReturn(0);
}

// Assembles K at x: the Gauss-Newton matrix A^T W A (eqs. 2.31-2.33) plus the second-order
// terms w_i phi_i d2l_i/dx2 of the boundary links (order 1) or of all links (order 2, Newton).
// *status: KERNEL_OK or a link kernel status (*bad = link). The first assembly goes through
// MatSetValues; later ones add each link's block at its place in K's value array
// (LinearSystem::slot): K's structure never changes, and MatSetValues' search of each row was
// 17 % of a roll fit's instructions.
PetscErrorCode AssembleK(const Problem &p, LinearSystem *ls, const std::vector<double> &x,
                         int order, int *status, int *bad) {
  PetscScalar *val = nullptr;
  PetscFunctionBeginUser;
  *status = KERNEL_OK;
  const bool direct = !ls->slot.empty();
  if (direct) {
    PetscCall(MatSeqAIJGetArray(ls->K, &val));
    std::fill(val, val + ls->nnz, 0.0);
  } else {
    PetscCall(MatZeroEntries(ls->K));
  }
  for (int i = 0; i < p.topo->NumLinks(); ++i) {
    const int a = p.topo->links[2 * i], b = p.topo->links[2 * i + 1];
    double c, g[4], Ke[16], Re[4];
    const int st = FlattenLink(&x[2 * (size_t)a], &x[2 * (size_t)b], p.L[i], p.min_len2d, &c, g);
    if (st != KERNEL_OK) {
      *status = st;
      *bad = i;
      break;
    }
    const bool second = order == 2 || (order == 1 && p.topo->Boundary(i));
    FlattenLinkSystem(p.w[i], c, g, second ? c + p.L[i] : 0.0, Ke, Re);
    if (direct) {
      const PetscInt *s = &ls->slot[16 * (size_t)i];
      for (int k = 0; k < 16; ++k)
        if (s[k] >= 0) val[s[k]] += Ke[k];
      continue;
    }
    // Fixed coordinates carry equation -1, which MatSetValues skips.
    const PetscInt idx[4] = {p.eq[2 * (size_t)a], p.eq[2 * (size_t)a + 1], p.eq[2 * (size_t)b],
                             p.eq[2 * (size_t)b + 1]};
    PetscCall(MatSetValues(ls->K, 4, idx, 4, idx, Ke, ADD_VALUES));
  }
  if (direct) {
    PetscCall(MatSeqAIJRestoreArray(ls->K, &val));  // marks K changed: the next solve refactors it
  } else {
    PetscCall(MatAssemblyBegin(ls->K, MAT_FINAL_ASSEMBLY));
    PetscCall(MatAssemblyEnd(ls->K, MAT_FINAL_ASSEMBLY));
    if (*status == KERNEL_OK) PetscCall(FindSlots(p, ls));
  }
  if (*status != KERNEL_OK) PetscFunctionReturn(0);
  PetscCall(KSPSetOperators(ls->ksp, ls->K, ls->K));
  PetscFunctionReturn(0);
}

// Solves K d = R with the K last assembled (factored once, reused for further right-hand
// sides); d per node coordinate (0 for fixed ones). *ok = false when the factorisation failed.
PetscErrorCode SolveK(const Problem &p, LinearSystem *ls, const std::vector<double> &R,
                      std::vector<double> *d, bool *ok) {
  KSPConvergedReason reason;
  PetscScalar *r;
  const PetscScalar *v;
  PetscFunctionBeginUser;
  // VecSetValues on a sequential vector does not skip negative indices, hence the plain copy.
  PetscCall(VecGetArrayWrite(ls->r, &r));
  std::copy(R.begin(), R.end(), r);
  PetscCall(VecRestoreArrayWrite(ls->r, &r));
  PetscCall(KSPSolve(ls->ksp, ls->r, ls->dx));
  PetscCall(KSPGetConvergedReason(ls->ksp, &reason));
  *ok = reason >= 0;
  d->assign(p.eq.size(), 0.0);
  if (!*ok) PetscFunctionReturn(0);
  PetscCall(VecGetArrayRead(ls->dx, &v));
  for (size_t k = 0; k < p.eq.size(); ++k)
    if (p.eq[k] >= 0) (*d)[k] = v[p.eq[k]];
  PetscCall(VecRestoreArrayRead(ls->dx, &v));
  for (double e : *d) *ok = *ok && std::isfinite(e);
  PetscFunctionReturn(0);
}

std::string LinkName(const Topology &t, int i) {
  return Format("link %d-%d", t.links[2 * i], t.links[2 * i + 1]);
}

namespace {

// Backtracking along dx from x, halving the step up to 40 times, until S does not grow (or is at
// its floor s_atol sw); at every trial point xt = x + a dx the second-order correction
// dc = K^-1 R(xt), with K's current factorisation, is tried too and the better point kept.
// On *accepted: *xt the new point, *St its S and *step = *xt - x (*xc is scratch).
PetscErrorCode SearchAlongStep(const FlattenOptions &opt, const Problem &p, LinearSystem *ls,
                               const std::vector<double> &x, const std::vector<double> &dx, double S, double sw,
                               std::vector<double> *xt, std::vector<double> *xc, double *St,
                               std::vector<double> *step, bool *accepted) {
  const size_t nd = x.size();
  std::vector<double> R1, dc;
  int bad = -1;
  PetscFunctionBeginUser;
  double a = 1.0;
  for (int k = 0; k < 40 && !*accepted; ++k, a *= 0.5) {
    for (size_t j = 0; j < nd; ++j) (*xt)[j] = x[j] + a * dx[j];
    double Sp = HUGE_VAL, Sc = HUGE_VAL;
    if (Objective(p, *xt, &Sp, nullptr) != KERNEL_OK) Sp = HUGE_VAL;
    bool soc = Residual(p, *xt, &R1, &bad) == KERNEL_OK;
    if (soc) PetscCall(SolveK(p, ls, R1, &dc, &soc));
    if (soc) {
      for (size_t j = 0; j < nd; ++j) (*xc)[j] = (*xt)[j] + dc[j];
      if (Objective(p, *xc, &Sc, nullptr) != KERNEL_OK) Sc = HUGE_VAL;
    }
    const bool use_c = Sc < Sp;
    *St = use_c ? Sc : Sp;
    if (*St <= S || *St <= opt.s_atol * sw) {
      *accepted = true;
      if (use_c) xt->swap(*xc);
      for (size_t j = 0; j < nd; ++j) (*step)[j] = (*xt)[j] - x[j];
    }
  }
  PetscFunctionReturn(0);
}

} // namespace

// One stage of the iteration, at the weights in p. Each step dx = K^-1 R is searched by
// backtracking until S does not grow; at every trial point x + a dx the second-order
// correction dc = K^-1 R(x + a dx), with the same factorisation, is tried too and the better
// point kept. Why: with a large weight the boundary links act as length constraints, a step
// along them lengthens them to second order (|dx|^2 / 2l), and the weight turns that into a
// large increase of S, so the line search would cut the steps to a crawl (the Maratos
// effect); dc restores the boundary lengths. A step of opt.second_order that cannot be
// factored or does not descend (K indefinite) falls back to Gauss-Newton, whose K is positive
// definite. Converged: largest step <= step_tol and S settled (see FlattenOptions).
// Returns a PETSc error code; a numerical failure sets *msg instead.
PetscErrorCode IterateStage(const FlattenOptions &opt, const Problem &p, LinearSystem *ls,
                            double sw, double step_tol, int max_it, std::vector<double> *x,
                            FlattenResult *out, bool *converged, std::string *msg) {
  const size_t nd = x->size();
  std::vector<double> R, dx, xt(nd), xc(nd), step(nd);
  PetscFunctionBeginUser;
  *converged = false;
  double S;
  int bad = -1;
  if (Objective(p, *x, &S, &bad) != KERNEL_OK) {
    *msg = Format("%s collapsed in the plane layout", LinkName(*p.topo, bad).c_str());
    PetscFunctionReturn(0);
  }
  const int first_order = std::max(0, std::min(2, opt.second_order));
  for (int it = 1; it <= max_it; ++it) {
    double St = HUGE_VAL, smax = 0.0, dmax = 0.0;
    bool accepted = false;
    const int st = Residual(p, *x, &R, &bad);
    if (st != KERNEL_OK) {
      *msg = Format("%s: %s in the plane layout at iteration %d",
                    LinkName(*p.topo, bad).c_str(), KernelStatusName(st), out->iterations + 1);
      break;
    }
    for (int order = first_order; order >= 0 && !accepted; order = order ? 0 : -1) {
      int status;
      bool ok = false;
      PetscCall(AssembleK(p, ls, *x, order, &status, &bad));
      if (status == KERNEL_OK) PetscCall(SolveK(p, ls, R, &dx, &ok));
      double slope = 0.0;
      for (size_t k = 0; ok && k < nd; ++k)
        if (p.eq[k] >= 0) slope += R[(size_t)p.eq[k]] * dx[k];
      // A Gauss-Newton K is positive definite, so its slope is >= 0 but for round-off when R
      // vanishes (an exact development); the line search then finds the floor.
      if (order > 0 && !(ok && slope > 0)) continue;
      if (!ok) {
        *msg = "the Gauss-Newton matrix K = A^T W A could not be factored (singular: a "
               "triangle collapsed to a line in the plane); check the strip for slivers";
        break;
      }
      dmax = 0.0;
      for (double v : dx) dmax = std::max(dmax, std::fabs(v));
      // At the round-off floor of an exact development no trial decreases S; that counts as
      // converged below.
      PetscCall(SearchAlongStep(opt, p, ls, *x, dx, S, sw, &xt, &xc, &St, &step, &accepted));
      if (accepted && order > 0) ++out->second_order_steps;
    }
    if (!msg->empty()) break;
    ++out->iterations;
    if (!accepted) {
      if (dmax <= step_tol) {  // already at the minimum within round-off
        *converged = true;
        break;
      }
      *msg = Format("the line search found no decrease of S = %.6e along the step (max %.3e mm) "
                    "at iteration %d; the strip may be too strongly curved for one piece: cut "
                    "it into narrower strips",
                    S, dmax, out->iterations);
      break;
    }
    for (double v : step) smax = std::max(smax, std::fabs(v));
    const double Sprev = S;
    S = St;
    x->swap(xt);
    out->S_history.push_back(S);
    const bool s_ok = std::fabs(Sprev - S) <= opt.s_rtol * Sprev || S <= opt.s_atol * sw;
    if (s_ok && smax <= step_tol) {
      *converged = true;
      break;
    }
  }
  PetscFunctionReturn(0);
}

// The stages of the boundary weight: interior_weight * growth^k up to boundary_weight, each
// started from the previous solution; only the last one must meet the tolerances.
PetscErrorCode Iterate(const MeshData &m, const FlattenOptions &opt, Problem *p, double lmean,
                       std::vector<double> *x, FlattenResult *out, std::string *msg) {
  LinearSystem ls;
  std::vector<double> weights;
  PetscFunctionBeginUser;
  // A held outline leaves the boundary links nothing to do: one stage.
  if (opt.weight_growth > 1.0 && !p->outline_held)
    for (double wb = opt.interior_weight; wb < opt.boundary_weight; wb *= opt.weight_growth)
      weights.push_back(wb);
  weights.push_back(opt.boundary_weight);
  PetscCall(CreateSystem(m, *p, &ls));
  for (size_t k = 0; k < weights.size() && msg->empty(); ++k) {
    const bool last = k + 1 == weights.size();
    double sw = 0.0;
    for (int i = 0; i < p->topo->NumLinks(); ++i) {
      // A link between two held nodes (FlattenOptions::hold_planar_outline) is a constant of S:
      // weight 0, so that S, its settling test and the line search see the free links only.
      const int a = p->topo->links[2 * i], b = p->topo->links[2 * i + 1];
      const bool fixed = p->eq[2 * (size_t)a] < 0 && p->eq[2 * (size_t)a + 1] < 0 && p->eq[2 * (size_t)b] < 0 &&
                         p->eq[2 * (size_t)b + 1] < 0;
      p->w[i] = fixed ? 0.0 : p->topo->Boundary(i) ? weights[k] : opt.interior_weight;
      sw += p->w[i] * p->L[i] * p->L[i];
    }
    bool converged = false;
    const int budget = opt.max_iterations - out->iterations;
    PetscCall(IterateStage(opt, *p, &ls, sw, (last ? opt.step_rtol : opt.stage_step_rtol) * lmean,
                           budget, x, out, &converged, msg));
    ++out->stages;
    if (last) out->converged = converged && msg->empty();
    if (msg->empty() && !converged && last) {
      *msg = Format("no convergence in %d iterations (S = %.6e, last change %.3e); raise "
                    "max_iterations or loosen the tolerances, or cut the strip narrower",
                    opt.max_iterations, out->S_history.empty() ? 0.0 : out->S_history.back(),
                    out->S_history.size() > 1
                        ? out->S_history[out->S_history.size() - 2] - out->S_history.back()
                        : 0.0);
    }
  }
  PetscCall(DestroySystem(&ls));
  PetscFunctionReturn(0);
}

} // namespace flatten
} // namespace etfe
