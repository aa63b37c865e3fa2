// Least-squares flattening of a cutting strip, docs/theory.md §9 / thesis §2.3.2 (Tabarrok's
// method).
//
// Minimise S(x) = sum_i w_i phi_i(x)^2, phi_i = l_i(x) - L_i (eqs. 2.23-2.25) over the plane node
// positions x = (x_1, y_1, ..., x_n, y_n) (eq. 2.24). Linearising phi_i (eq. 2.26) gives the
// Gauss-Newton system A^T W A dx = -A^T W C (eq. 2.29), i.e. K dx = R (eq. 2.31), assembled from
// the links like truss bars: K_i = w_i A_i^T A_i, R_i = -w_i phi_i A_i^T (eqs. 2.32-2.33; kernel
// src/kernels/flatten_link.cpp). K is singular for the three rigid motions of the plane: one
// node is fixed and the y of the node farthest from it along x, which removes them without
// changing the minimum (S is invariant under rigid motions).
//
// Beyond the thesis, for strips where its plain iteration stalls (see FlattenOptions): the
// boundary links' second-order terms w phi d2l/dx2 join K (w phi is their finite constraint
// force), the boundary weight grows in stages from the interior weight to 1e12, and the line
// search tries a second-order correction at each trial point. All of it changes the path, not
// the minimum: the converged state satisfies the same R = 0.
//
// Two initial layouts are tried and the one with the smaller S (preferring one without folds)
// is iterated: the projection onto the best-fit plane (principal axes of the node covariance)
// and an unfolding that places the triangles one by one from a central one, keeping each
// triangle's 3D shape; the unfolding is exact for developable strips and stays fold-free for
// strongly curved ones where a projection folds.
//
// A strip whose outline lies in one plane (a film cut to a plane frame) keeps that outline
// (FlattenOptions::hold_planar_outline): its nodes are fixed at their places in the plane, the
// layout is the projection onto it, and only the interior links are fitted.
#include <petscksp.h>

#include <algorithm>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <map>
#include <queue>
#include <string>
#include <utility>
#include <vector>

#include "etfe/analyses/flatten_strip.h"
#include "etfe/kernels/flatten_link.h"
#include "etfe/kernels/status.h"

#if defined(PETSC_USE_COMPLEX)
#error "FlattenStrip needs a real PETSc build"
#endif
#include "flatten_internal.h"

namespace etfe {

using namespace flatten;

namespace {

// The strip must be one piece across edges: a strip that falls apart has no single layout.
bool CheckConnected(const MeshData &m, const Topology &t, std::string *err) {
  std::vector<int> order, via;
  TriangleBfs(m, t, 0, &order, &via);
  if ((int)order.size() != m.NumElements()) {
    return Fail(m, err, Format("the strip falls apart: only %d of its %d triangles are "
                               "connected to triangle 0 across edges; flatten each piece on "
                               "its own",
                               (int)order.size(), m.NumElements()));
  }
  return true;
}

// The links' target lengths L (their 3D lengths, or opt.link_target) and weights w; *lmean the
// mean target length. False for a link whose nodes coincide.
bool LinkTargets(const MeshData &m, const Topology &t, const FlattenOptions &opt, Problem *p, double *lmean,
                 std::string *err) {
  const int nl = t.NumLinks();
  p->topo = &t;
  p->L.resize(nl);
  p->w.resize(nl);
  if (!opt.link_target.empty() && (int)opt.link_target.size() != nl)
    return Fail(m, err, Format("%d target link lengths given for %d links", (int)opt.link_target.size(), nl));
  *lmean = 0.0;
  for (int i = 0; i < nl; ++i) {
    const int a = t.links[2 * i], b = t.links[2 * i + 1];
    p->L[i] = opt.link_target.empty() ? Dist3(&m.coords[3 * (size_t)a], &m.coords[3 * (size_t)b])
                                      : opt.link_target[i];
    *lmean += p->L[i] / nl;
    p->w[i] = t.Boundary(i) ? opt.boundary_weight : opt.interior_weight;
  }
  for (int i = 0; i < nl; ++i)
    if (!(p->L[i] > opt.min_link_rel * *lmean)) {
      return Fail(m, err, Format("%s has 3D length %.3g mm (mean link %.3g mm): its nodes "
                                 "coincide, so the strip cannot be flattened; merge them",
                                 LinkName(t, i).c_str(), p->L[i], *lmean));
    }
  p->min_len2d = 1e-12 * *lmean;
  return true;
}

// The initial layout: of the projection and the unfolding, the one with fewer folds, then the
// smaller S.
bool InitialLayout(const MeshData &m, const Topology &t, const Problem &p, std::vector<double> *x, FlattenResult *out,
                   std::string *err) {
  std::vector<double> cand[2];
  ProjectionGuess(m, &cand[0]);
  UnfoldGuess(m, t, &cand[1]);
  const char *names[2] = {"projection", "unfolding"};
  int best = -1, best_folds = 0;
  double best_S = HUGE_VAL;
  for (int c = 0; c < 2; ++c) {
    AlignPrincipal(&cand[c]);
    double S;
    if (Objective(p, cand[c], &S, nullptr) != KERNEL_OK) continue;
    const int folds = CountFolds(t, cand[c], nullptr);
    if (best < 0 || folds < best_folds || (folds == best_folds && S < best_S))
      best = c, best_folds = folds, best_S = S;
  }
  if (best < 0) return Fail(m, err, "no initial plane layout without collapsed links");
  *x = cand[best];
  out->initial_guess = names[best];
  out->S_initial = out->S = best_S;
  return true;
}

// Rigid motion: fix the node with the smallest x and the y of the one with the largest x of
// the (principal-axis aligned) layout, far apart so the rotation is well determined.
void FixRigidMotion(const std::vector<double> &x, int nn, Problem *p) {
  int a = 0, b = 0;
  for (int i = 0; i < nn; ++i) {
    if (x[2 * (size_t)i] < x[2 * (size_t)a]) a = i;
    if (x[2 * (size_t)i] > x[2 * (size_t)b]) b = i;
  }
  p->eq.assign(2 * (size_t)nn, -1);
  for (int k = 0; k < 2 * nn; ++k)
    if (k != 2 * a && k != 2 * a + 1 && k != 2 * b + 1) p->eq[k] = p->nfree++;
}

// FlattenOptions::hold_planar_outline: the outline nodes fixed where the projection onto their
// plane puts them (which fixes the rigid motion too), the rest free.
void HoldOutline(const MeshData &m, const std::vector<char> &on_outline, std::vector<double> *x, Problem *p,
                 FlattenResult *out) {
  AlignPrincipal(x);
  p->eq.assign(2 * (size_t)m.NumNodes(), -1);
  for (int n = 0; n < m.NumNodes(); ++n)
    if (!on_outline[n]) p->eq[2 * (size_t)n] = p->nfree++, p->eq[2 * (size_t)n + 1] = p->nfree++;
  p->outline_held = out->outline_held = true;
  for (int i = 0; i < p->topo->NumLinks(); ++i)  // as Iterate weighs them: a held link is a constant
    if (on_outline[p->topo->links[2 * i]] && on_outline[p->topo->links[2 * i + 1]]) p->w[i] = 0.0;
  out->initial_guess = "outline plane";
  Objective(*p, *x, &out->S_initial, nullptr);
  out->S = out->S_initial;
}

} // namespace

bool FlattenStrip(const MeshData &strip3d, const FlattenOptions &opt, FlattenResult *out,
                  std::string *err) {
  const MeshData &m = strip3d;
  *out = FlattenResult();
  if (!MeshCheck(m, 0.0, err)) return false;
  if (!(opt.boundary_weight > 0) || !(opt.interior_weight > 0) || opt.max_iterations < 1) {
    return Fail(m, err, Format("flatten options: boundary_weight %g and interior_weight %g must "
                               "be positive and max_iterations %d at least 1",
                               opt.boundary_weight, opt.interior_weight, opt.max_iterations));
  }
  PetscBool initialized = PETSC_FALSE;
  PetscInitialized(&initialized);
  if (!initialized) return Fail(m, err, "FlattenStrip needs PETSc to be initialised");

  Topology t;
  if (!BuildTopology(m, &t, err) || !CheckConnected(m, t, err)) return false;
  Problem p;
  double lmean = 0.0;
  if (!LinkTargets(m, t, opt, &p, &lmean, err)) return false;
  std::vector<double> x;
  std::vector<char> on_outline;
  // With target lengths (compensation) the outline's 3D place is no longer its target: free.
  if (opt.hold_planar_outline && opt.link_target.empty() && OutlinePlaneLayout(m, t, opt.outline_plane_rtol, &x, &on_outline)) {
    HoldOutline(m, on_outline, &x, &p, out);
  } else {
    if (!InitialLayout(m, t, p, &x, out, err)) return false;
    FixRigidMotion(x, m.NumNodes(), &p);
  }

  // The second-order step (FlattenOptions::second_order) may lead the iteration into a folded
  // minimum that plain Gauss-Newton from the same layout avoids: a strip of the hypar canopy
  // turned by 45 deg (cut at 444 mm, 2996 nodes) ended folded at its tips with S = 137 mm^2 and
  // link errors of 14 %, and flattened with Gauss-Newton in 24 iterations to S = 0.025 mm^2,
  // link error 1.4e-4. So a strip that fails or folds with it is flattened again without it.
  const std::vector<double> x0 = x;
  const Problem p0 = p;
  const FlattenResult out0 = *out;
  std::string msg;
  int folds = 0, first = -1;
  bool reported = false;
  std::string rep_err;
  for (int attempt = 0; attempt < 2; ++attempt) {
    FlattenOptions o = opt;
    if (attempt == 1) {
      if (opt.second_order == 0) break;
      o.second_order = 0;
      x = x0, p = p0, *out = out0;
      out->gauss_newton_retry = true;
      msg.clear(), rep_err.clear();
    }
    // Every node on the outline (a single triangle, a ring one element wide): nothing to solve.
    const PetscErrorCode ierr = p.nfree ? Iterate(m, o, &p, lmean, &x, out, &msg) : 0;
    if (!p.nfree) out->converged = true;
    Objective(p, x, &out->S, nullptr);
    if (ierr) return Fail(m, err, Format("PETSc error %d while flattening (see the PETSc "
                                         "message above)", (int)ierr));
    // Fill in the report even on failure, for diagnosis.
    reported = Report(m, t, o, p, x, out, &rep_err);
    folds = reported ? CountFolds(t, out->xy, &first) : 0;
    if (msg.empty() && reported && folds == 0) break;
  }
  if (!msg.empty()) return Fail(m, err, msg);
  if (!reported) {
    if (err) *err = rep_err;
    return false;
  }
  if (folds > 0) {
    return Fail(m, err, Format("the flattened strip folds over at %d interior links (first: %s); "
                               "the strip is too strongly curved for one piece: cut it into "
                               "narrower strips",
                               folds, LinkName(t, first).c_str()));
  }
  return true;
}

} // namespace etfe
