// Least-squares flattening of a cutting strip, SPEC §7 / thesis §2.3.2 (Tabarrok's method).
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

#include "etfe/flatten_strip.h"
#include "etfe/kernels/flatten_link.h"
#include "etfe/kernels/status.h"

#if defined(PETSC_USE_COMPLEX)
#error "FlattenStrip needs a real PETSc build"
#endif

namespace etfe {
namespace {

std::string Format(const char *fmt, ...) __attribute__((format(printf, 1, 2)));
std::string Format(const char *fmt, ...) {
  char buf[1024];
  va_list ap;
  va_start(ap, fmt);
  std::vsnprintf(buf, sizeof buf, fmt, ap);
  va_end(ap);
  return buf;
}

bool Fail(const MeshData &m, std::string *err, const std::string &msg) {
  if (err) *err = (m.source.empty() ? std::string("strip") : m.source) + ": " + msg;
  return false;
}

// Links (unique mesh edges) with their one or two triangles and the nodes opposite them.
struct Topology {
  std::vector<int> links;  // 2 per link, smaller id first
  std::vector<int> tri;    // 2 per link: adjacent triangles, -1 for none
  std::vector<int> opp;    // 2 per link: the third node of those triangles
  std::vector<int> tri_links;  // 3 per triangle
  int NumLinks() const { return (int)(links.size() / 2); }
  bool Boundary(int i) const { return tri[2 * i + 1] < 0; }
};

bool BuildTopology(const MeshData &m, Topology *t, std::string *err) {
  std::map<std::pair<int, int>, int> id;
  const int ne = m.NumElements();
  t->tri_links.assign(3 * (size_t)ne, -1);
  for (int e = 0; e < ne; ++e) {
    const int *v = &m.triangles[3 * (size_t)e];
    for (int k = 0; k < 3; ++k) {
      const int a = std::min(v[k], v[(k + 1) % 3]), b = std::max(v[k], v[(k + 1) % 3]);
      const int c = v[(k + 2) % 3];
      auto ins = id.emplace(std::make_pair(a, b), t->NumLinks());
      const int i = ins.first->second;
      if (ins.second) {
        t->links.insert(t->links.end(), {a, b});
        t->tri.insert(t->tri.end(), {e, -1});
        t->opp.insert(t->opp.end(), {c, -1});
      } else if (t->tri[2 * i + 1] < 0) {
        t->tri[2 * i + 1] = e;
        t->opp[2 * i + 1] = c;
      } else {
        return Fail(m, err, Format("the edge between nodes %d and %d belongs to three or more "
                                   "triangles (%d, %d, %d): a cutting strip must be a manifold "
                                   "surface; split the mesh into strips along that line",
                                   a, b, t->tri[2 * i], t->tri[2 * i + 1], e));
      }
      t->tri_links[3 * (size_t)e + k] = i;
    }
  }
  return true;
}

double Dist3(const double *a, const double *b) {
  return std::sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
                   (a[2] - b[2]) * (a[2] - b[2]));
}

double Cross2(const double *o, const double *a, const double *b) {
  return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]);
}

// Triangles reached from triangle `start` across shared links (breadth first), in visit order,
// with the link each one was reached through (-1 for the start).
void TriangleBfs(const MeshData &m, const Topology &t, int start, std::vector<int> *order,
                 std::vector<int> *via) {
  const int ne = m.NumElements();
  std::vector<char> seen(ne, 0);
  order->clear();
  via->assign(ne, -1);
  std::queue<int> q;
  q.push(start);
  seen[start] = 1;
  while (!q.empty()) {
    const int e = q.front();
    q.pop();
    order->push_back(e);
    for (int k = 0; k < 3; ++k) {
      const int i = t.tri_links[3 * (size_t)e + k];
      const int f = t.tri[2 * i] == e ? t.tri[2 * i + 1] : t.tri[2 * i];
      if (f < 0 || seen[f]) continue;
      seen[f] = 1;
      (*via)[f] = i;
      q.push(f);
    }
  }
}

// Eigen-decomposition of a symmetric 3x3 matrix by cyclic Jacobi rotations; vecs holds the
// eigenvectors as columns (vecs[3*row + col]), values sorted in descending order.
void SymEigen3(const double Ain[9], double vals[3], double vecs[9]) {
  double A[9], V[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  std::copy(Ain, Ain + 9, A);
  for (int sweep = 0; sweep < 50; ++sweep) {
    const double off = A[1] * A[1] + A[2] * A[2] + A[5] * A[5];
    const double diag = A[0] * A[0] + A[4] * A[4] + A[8] * A[8];
    if (off <= 1e-30 * diag || off == 0.0) break;
    for (int p = 0; p < 2; ++p)
      for (int q = p + 1; q < 3; ++q) {
        const double apq = A[3 * p + q];
        if (apq == 0.0) continue;
        const double theta = (A[3 * q + q] - A[3 * p + p]) / (2.0 * apq);
        const double tn = (theta >= 0 ? 1.0 : -1.0) / (std::fabs(theta) + std::hypot(theta, 1.0));
        const double c = 1.0 / std::hypot(tn, 1.0), s = tn * c;
        for (int k = 0; k < 3; ++k) {  // A <- A J
          const double akp = A[3 * k + p], akq = A[3 * k + q];
          A[3 * k + p] = c * akp - s * akq;
          A[3 * k + q] = s * akp + c * akq;
        }
        for (int k = 0; k < 3; ++k) {  // A <- J^T A
          const double apk = A[3 * p + k], aqk = A[3 * q + k];
          A[3 * p + k] = c * apk - s * aqk;
          A[3 * q + k] = s * apk + c * aqk;
        }
        for (int k = 0; k < 3; ++k) {
          const double vkp = V[3 * k + p], vkq = V[3 * k + q];
          V[3 * k + p] = c * vkp - s * vkq;
          V[3 * k + q] = s * vkp + c * vkq;
        }
      }
  }
  int idx[3] = {0, 1, 2};
  std::sort(idx, idx + 3, [&](int a, int b) { return A[4 * a] > A[4 * b]; });
  for (int j = 0; j < 3; ++j) {
    vals[j] = A[4 * idx[j]];
    for (int k = 0; k < 3; ++k) vecs[3 * k + j] = V[3 * k + idx[j]];
  }
}

// Rotates a plane layout so its principal (long) axis is x and translates its bounding box to
// start at (0, 0). A rotation, never a reflection, so the side the pattern is seen from stays.
void AlignPrincipal(std::vector<double> *xy) {
  const size_t n = xy->size() / 2;
  double c[2] = {0, 0};
  for (size_t i = 0; i < n; ++i) {
    c[0] += (*xy)[2 * i] / n;
    c[1] += (*xy)[2 * i + 1] / n;
  }
  double sxx = 0, syy = 0, sxy = 0;
  for (size_t i = 0; i < n; ++i) {
    const double dx = (*xy)[2 * i] - c[0], dy = (*xy)[2 * i + 1] - c[1];
    sxx += dx * dx;
    syy += dy * dy;
    sxy += dx * dy;
  }
  const double phi = 0.5 * std::atan2(2.0 * sxy, sxx - syy);  // angle of the major axis
  const double cs = std::cos(phi), sn = std::sin(phi);
  double lo[2] = {HUGE_VAL, HUGE_VAL};
  for (size_t i = 0; i < n; ++i) {
    const double dx = (*xy)[2 * i] - c[0], dy = (*xy)[2 * i + 1] - c[1];
    (*xy)[2 * i] = cs * dx + sn * dy;
    (*xy)[2 * i + 1] = -sn * dx + cs * dy;
    lo[0] = std::min(lo[0], (*xy)[2 * i]);
    lo[1] = std::min(lo[1], (*xy)[2 * i + 1]);
  }
  for (size_t i = 0; i < n; ++i) {
    (*xy)[2 * i] -= lo[0];
    (*xy)[2 * i + 1] -= lo[1];
  }
}

// Projection onto the best-fit plane, its normal turned towards the area-weighted mean normal
// of the triangles (by node order) so consistently oriented triangles come out counter-clockwise.
void ProjectionGuess(const MeshData &m, std::vector<double> *xy) {
  const int nn = m.NumNodes();
  double c[3] = {0, 0, 0};
  for (int i = 0; i < nn; ++i)
    for (int k = 0; k < 3; ++k) c[k] += m.coords[3 * (size_t)i + k] / nn;
  double C[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0};
  for (int i = 0; i < nn; ++i) {
    const double d[3] = {m.coords[3 * (size_t)i] - c[0], m.coords[3 * (size_t)i + 1] - c[1],
                         m.coords[3 * (size_t)i + 2] - c[2]};
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) C[3 * a + b] += d[a] * d[b];
  }
  double vals[3], V[9];
  SymEigen3(C, vals, V);
  double N[3] = {0, 0, 0};
  for (int e = 0; e < m.NumElements(); ++e) {
    const double *a = &m.coords[3 * (size_t)m.triangles[3 * (size_t)e]];
    const double *b = &m.coords[3 * (size_t)m.triangles[3 * (size_t)e + 1]];
    const double *d = &m.coords[3 * (size_t)m.triangles[3 * (size_t)e + 2]];
    const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    const double v[3] = {d[0] - a[0], d[1] - a[1], d[2] - a[2]};
    N[0] += u[1] * v[2] - u[2] * v[1];
    N[1] += u[2] * v[0] - u[0] * v[2];
    N[2] += u[0] * v[1] - u[1] * v[0];
  }
  double e1[3] = {V[0], V[3], V[6]}, e3[3] = {V[2], V[5], V[8]};
  if (e3[0] * N[0] + e3[1] * N[1] + e3[2] * N[2] < 0)
    for (double &v : e3) v = -v;
  const double e2[3] = {e3[1] * e1[2] - e3[2] * e1[1], e3[2] * e1[0] - e3[0] * e1[2],
                        e3[0] * e1[1] - e3[1] * e1[0]};
  xy->assign(2 * (size_t)nn, 0.0);
  for (int i = 0; i < nn; ++i) {
    const double d[3] = {m.coords[3 * (size_t)i] - c[0], m.coords[3 * (size_t)i + 1] - c[1],
                         m.coords[3 * (size_t)i + 2] - c[2]};
    (*xy)[2 * (size_t)i] = d[0] * e1[0] + d[1] * e1[1] + d[2] * e1[2];
    (*xy)[2 * (size_t)i + 1] = d[0] * e2[0] + d[1] * e2[1] + d[2] * e2[2];
  }
}

// Triangle-by-triangle unfolding from the triangle nearest the centroid: the new node w of a
// triangle reached across the placed edge (a, b) keeps its 3D position relative to that edge
// (fraction along it and height over it, scaled by the plane edge length) on the side opposite
// the triangle it came from. Exact for a developable strip up to round-off; on a doubly curved
// one the error collects where the fronts of the search meet.
void UnfoldGuess(const MeshData &m, const Topology &t, std::vector<double> *xy) {
  const int nn = m.NumNodes(), ne = m.NumElements();
  double c[3] = {0, 0, 0};
  for (int i = 0; i < nn; ++i)
    for (int k = 0; k < 3; ++k) c[k] += m.coords[3 * (size_t)i + k] / nn;
  int start = 0;
  double best = HUGE_VAL;
  for (int e = 0; e < ne; ++e) {
    double g[3] = {0, 0, 0};
    for (int k = 0; k < 3; ++k)
      for (int d = 0; d < 3; ++d) g[d] += m.coords[3 * (size_t)m.triangles[3 * e + k] + d] / 3;
    const double dist = Dist3(g, c);
    if (dist < best) best = dist, start = e;
  }
  std::vector<int> order, via;
  TriangleBfs(m, t, start, &order, &via);
  std::vector<char> placed(nn, 0);
  xy->assign(2 * (size_t)nn, 0.0);
  // Places w relative to the placed edge a->b; side = +1 puts it on the left of a->b.
  auto place = [&](int a, int b, int w, double side) {
    const double *A = &m.coords[3 * (size_t)a], *B = &m.coords[3 * (size_t)b];
    const double *W = &m.coords[3 * (size_t)w];
    const double ab[3] = {B[0] - A[0], B[1] - A[1], B[2] - A[2]};
    const double aw[3] = {W[0] - A[0], W[1] - A[1], W[2] - A[2]};
    const double l2 = ab[0] * ab[0] + ab[1] * ab[1] + ab[2] * ab[2];
    const double cr[3] = {ab[1] * aw[2] - ab[2] * aw[1], ab[2] * aw[0] - ab[0] * aw[2],
                          ab[0] * aw[1] - ab[1] * aw[0]};
    const double s = (ab[0] * aw[0] + ab[1] * aw[1] + ab[2] * aw[2]) / l2;
    const double h = std::sqrt(cr[0] * cr[0] + cr[1] * cr[1] + cr[2] * cr[2]) / l2;
    const double *pa = &(*xy)[2 * (size_t)a], *pb = &(*xy)[2 * (size_t)b];
    const double d[2] = {pb[0] - pa[0], pb[1] - pa[1]};
    (*xy)[2 * (size_t)w] = pa[0] + s * d[0] - side * h * d[1];
    (*xy)[2 * (size_t)w + 1] = pa[1] + s * d[1] + side * h * d[0];
    placed[w] = 1;
  };
  const int *v0 = &m.triangles[3 * (size_t)start];
  (*xy)[2 * (size_t)v0[1]] = Dist3(&m.coords[3 * (size_t)v0[0]], &m.coords[3 * (size_t)v0[1]]);
  placed[v0[0]] = placed[v0[1]] = 1;
  place(v0[0], v0[1], v0[2], 1.0);
  for (size_t k = 1; k < order.size(); ++k) {
    const int e = order[k], i = via[e];
    const int a = t.links[2 * i], b = t.links[2 * i + 1];
    const int from = t.tri[2 * i] == e ? t.opp[2 * i + 1] : t.opp[2 * i];
    const int w = t.tri[2 * i] == e ? t.opp[2 * i] : t.opp[2 * i + 1];
    if (placed[w]) continue;
    const double side = Cross2(&(*xy)[2 * (size_t)a], &(*xy)[2 * (size_t)b],
                               &(*xy)[2 * (size_t)from]) > 0 ? -1.0 : 1.0;
    place(a, b, w, side);
  }
}

// The flattening problem: links, their 3D lengths and weights, and the free equations.
struct Problem {
  const Topology *topo;
  std::vector<double> L, w;
  std::vector<PetscInt> eq;  // 2 per node: equation number or -1 for a fixed coordinate
  PetscInt nfree = 0;
  double min_len2d = 0.0;  // plane links at or below this length count as collapsed
};

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

// Interior links whose two triangles lie on the same side of them in the plane (a fold).
int CountFolds(const Topology &t, const std::vector<double> &x, int *first) {
  int n = 0;
  for (int i = 0; i < t.NumLinks(); ++i) {
    if (t.Boundary(i)) continue;
    const double *a = &x[2 * (size_t)t.links[2 * i]], *b = &x[2 * (size_t)t.links[2 * i + 1]];
    const double s1 = Cross2(a, b, &x[2 * (size_t)t.opp[2 * i]]);
    const double s2 = Cross2(a, b, &x[2 * (size_t)t.opp[2 * i + 1]]);
    if (!(s1 * s2 < 0)) {
      if (n++ == 0 && first) *first = i;
    }
  }
  return n;
}

struct LinearSystem {
  Mat K = nullptr;
  Vec r = nullptr, dx = nullptr;
  KSP ksp = nullptr;
};

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
  // LU rather than Cholesky: PETSc's native Cholesky on AIJ needs a natural ordering, while LU
  // with nested dissection keeps the fill small; K is SPD so no pivoting is needed.
  PetscCall(PCSetType(pc, PCLU));
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

// Assembles K at x: the Gauss-Newton matrix A^T W A (eqs. 2.31-2.33) plus the second-order
// terms w_i phi_i d2l_i/dx2 of the boundary links (order 1) or of all links (order 2, Newton).
// *status: KERNEL_OK or a link kernel status (*bad = link).
PetscErrorCode AssembleK(const Problem &p, LinearSystem *ls, const std::vector<double> &x,
                         int order, int *status, int *bad) {
  PetscFunctionBeginUser;
  *status = KERNEL_OK;
  PetscCall(MatZeroEntries(ls->K));
  for (int i = 0; i < p.topo->NumLinks(); ++i) {
    const int a = p.topo->links[2 * i], b = p.topo->links[2 * i + 1];
    double c, g[4], Ke[16], Re[4];
    const int st = FlattenLink(&x[2 * (size_t)a], &x[2 * (size_t)b], p.L[i], p.min_len2d, &c, g);
    if (st != KERNEL_OK) {
      *status = st;
      *bad = i;
      PetscFunctionReturn(0);
    }
    const bool second = order == 2 || (order == 1 && p.topo->Boundary(i));
    FlattenLinkSystem(p.w[i], c, g, second ? c + p.L[i] : 0.0, Ke, Re);
    // Fixed coordinates carry equation -1, which MatSetValues skips.
    const PetscInt idx[4] = {p.eq[2 * (size_t)a], p.eq[2 * (size_t)a + 1], p.eq[2 * (size_t)b],
                             p.eq[2 * (size_t)b + 1]};
    PetscCall(MatSetValues(ls->K, 4, idx, 4, idx, Ke, ADD_VALUES));
  }
  PetscCall(MatAssemblyBegin(ls->K, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(ls->K, MAT_FINAL_ASSEMBLY));
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
  std::vector<double> R, R1, dx, dc, xt(nd), xc(nd), step(nd);
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
      double a = 1.0;
      for (int k = 0; k < 40 && !accepted; ++k, a *= 0.5) {
        for (size_t j = 0; j < nd; ++j) xt[j] = (*x)[j] + a * dx[j];
        double Sp = HUGE_VAL, Sc = HUGE_VAL;
        if (Objective(p, xt, &Sp, nullptr) != KERNEL_OK) Sp = HUGE_VAL;
        bool soc = Residual(p, xt, &R1, &bad) == KERNEL_OK;
        if (soc) PetscCall(SolveK(p, ls, R1, &dc, &soc));
        if (soc) {
          for (size_t j = 0; j < nd; ++j) xc[j] = xt[j] + dc[j];
          if (Objective(p, xc, &Sc, nullptr) != KERNEL_OK) Sc = HUGE_VAL;
        }
        const bool use_c = Sc < Sp;
        St = use_c ? Sc : Sp;
        if (St <= S || St <= opt.s_atol * sw) {
          accepted = true;
          if (use_c) xt.swap(xc);
          for (size_t j = 0; j < nd; ++j) step[j] = xt[j] - (*x)[j];
        }
      }
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
  if (opt.weight_growth > 1.0)
    for (double wb = opt.interior_weight; wb < opt.boundary_weight; wb *= opt.weight_growth)
      weights.push_back(wb);
  weights.push_back(opt.boundary_weight);
  PetscCall(CreateSystem(m, *p, &ls));
  for (size_t k = 0; k < weights.size() && msg->empty(); ++k) {
    const bool last = k + 1 == weights.size();
    double sw = 0.0;
    for (int i = 0; i < p->topo->NumLinks(); ++i) {
      p->w[i] = p->topo->Boundary(i) ? weights[k] : opt.interior_weight;
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

// Boundary loops with the interior on their left, the outer (largest) loop first.
void OutlineLoops(const Topology &t, const std::vector<double> &x, int nn,
                  std::vector<std::vector<int>> *loops) {
  std::vector<std::vector<std::pair<int, int>>> out_edges(nn);  // (to, link)
  for (int i = 0; i < t.NumLinks(); ++i) {
    if (!t.Boundary(i)) continue;
    int a = t.links[2 * i], b = t.links[2 * i + 1];
    if (Cross2(&x[2 * (size_t)a], &x[2 * (size_t)b], &x[2 * (size_t)t.opp[2 * i]]) < 0)
      std::swap(a, b);
    out_edges[a].push_back({b, i});
  }
  std::vector<char> used(t.NumLinks(), 0);
  std::vector<std::pair<double, std::vector<int>>> found;
  for (int s = 0; s < nn; ++s)
    for (const auto &e0 : out_edges[s]) {
      if (used[e0.second]) continue;
      std::vector<int> loop{s};
      used[e0.second] = 1;
      int cur = e0.first;
      while (cur != s) {
        loop.push_back(cur);
        int next = -1;
        for (const auto &e : out_edges[cur])
          if (!used[e.second]) {
            used[e.second] = 1;
            next = e.first;
            break;
          }
        if (next < 0) break;  // cannot happen on a manifold mesh: every boundary node closes
        cur = next;
      }
      double area = 0.0;
      for (size_t k = 0; k < loop.size(); ++k) {
        const double *p = &x[2 * (size_t)loop[k]], *q = &x[2 * (size_t)loop[(k + 1) % loop.size()]];
        area += 0.5 * (p[0] * q[1] - p[1] * q[0]);
      }
      found.push_back({area, loop});
    }
  std::stable_sort(found.begin(), found.end(), [](const auto &a, const auto &b) {
    return std::fabs(a.first) > std::fabs(b.first);
  });
  loops->clear();
  for (auto &f : found) loops->push_back(std::move(f.second));
}

// The polyline of a node set (see PatternLine); false with a message when the set's edges do
// not form simple lines.
bool MeasureLine(const MeshData &m, const Topology &t, const std::vector<double> &x,
                 const std::string &name, const std::vector<int> &set, PatternLine *line,
                 std::string *err) {
  const int nn = m.NumNodes();
  std::vector<char> in(nn, 0);
  for (int v : set) in[v] = 1;
  std::vector<int> edges;
  for (int pass = 0; pass < 2 && edges.empty(); ++pass)
    for (int i = 0; i < t.NumLinks(); ++i)
      if (in[t.links[2 * i]] && in[t.links[2 * i + 1]] && (pass == 1 || t.Boundary(i)))
        edges.push_back(i);
  line->name = name;
  line->on_boundary = !edges.empty() && t.Boundary(edges[0]);
  if (edges.empty()) {
    return Fail(m, err, "node set '" + name + "' has no two nodes joined by a mesh edge, so it "
                        "is not a line: list the nodes of a boundary or cutting line");
  }
  std::vector<std::vector<std::pair<int, int>>> adj(nn);
  for (int i : edges) {
    adj[t.links[2 * i]].push_back({t.links[2 * i + 1], i});
    adj[t.links[2 * i + 1]].push_back({t.links[2 * i], i});
  }
  for (int v = 0; v < nn; ++v)
    if (adj[v].size() > 2) {
      return Fail(m, err, Format("node set '%s': node %d joins %d of the set's %s edges, so the "
                                 "set is not a simple line; split it into separate lines",
                                 name.c_str(), v, (int)adj[v].size(),
                                 line->on_boundary ? "boundary" : "mesh"));
    }
  std::vector<char> used(t.NumLinks(), 0);
  // Open pieces start at their end points (one edge), then the closed pieces.
  for (int pass = 0; pass < 2; ++pass)
    for (int s = 0; s < nn; ++s) {
      if (adj[s].empty() || (pass == 0 && adj[s].size() != 1)) continue;
      if (used[adj[s][0].second] && (adj[s].size() == 1 || used[adj[s][1].second])) continue;
      std::vector<int> path{s};
      int cur = s;
      for (;;) {
        int next = -1;
        for (const auto &e : adj[cur])
          if (!used[e.second]) {
            used[e.second] = 1;
            next = e.first;
            ++line->segments;
            line->length3d += Dist3(&m.coords[3 * (size_t)cur], &m.coords[3 * (size_t)e.first]);
            line->length2d += std::hypot(x[2 * (size_t)e.first] - x[2 * (size_t)cur],
                                         x[2 * (size_t)e.first + 1] - x[2 * (size_t)cur + 1]);
            break;
          }
        if (next < 0) break;
        path.push_back(next);
        cur = next;
        if (cur == s) break;
      }
      line->paths.push_back(std::move(path));
    }
  line->expansion_pct = (line->length2d - line->length3d) / line->length3d * 100.0;
  return true;
}

// Final mirror, rotation and translation; link errors; outline; lines.
bool Report(const MeshData &m, const Topology &t, const FlattenOptions &opt, const Problem &p,
            std::vector<double> x, FlattenResult *out, std::string *err) {
  const int nn = m.NumNodes();
  // S is invariant under reflection, so the solution may be the mirror image of the strip seen
  // from triangle 0's normal side; a fabricator needs the film's face, so undo that.
  const int *v0 = &m.triangles[0];
  if (Cross2(&x[2 * (size_t)v0[0]], &x[2 * (size_t)v0[1]], &x[2 * (size_t)v0[2]]) < 0)
    for (int i = 0; i < nn; ++i) x[2 * (size_t)i] = -x[2 * (size_t)i];
  AlignPrincipal(&x);
  out->xy = x;
  const int nl = t.NumLinks();
  out->links = t.links;
  out->link_on_boundary.assign(nl, 0);
  out->link_length3d = p.L;
  out->link_error.assign(nl, 0.0);
  double sum2 = 0.0, sum2i = 0.0;
  int ni = 0;
  out->num_boundary_links = 0;
  out->max_rel_error = out->max_rel_error_boundary = out->max_rel_error_interior = 0.0;
  for (int i = 0; i < nl; ++i) {
    const int a = t.links[2 * i], b = t.links[2 * i + 1];
    const double l = std::hypot(x[2 * (size_t)b] - x[2 * (size_t)a],
                                x[2 * (size_t)b + 1] - x[2 * (size_t)a + 1]);
    const double e = (l - p.L[i]) / p.L[i];
    out->link_error[i] = e;
    out->max_rel_error = std::max(out->max_rel_error, std::fabs(e));
    sum2 += e * e;
    if (t.Boundary(i)) {
      out->link_on_boundary[i] = 1;
      ++out->num_boundary_links;
      out->max_rel_error_boundary = std::max(out->max_rel_error_boundary, std::fabs(e));
    } else {
      ++ni;
      sum2i += e * e;
      out->max_rel_error_interior = std::max(out->max_rel_error_interior, std::fabs(e));
    }
  }
  out->rms_rel_error = std::sqrt(sum2 / nl);
  out->rms_rel_error_interior = ni ? std::sqrt(sum2i / ni) : 0.0;
  OutlineLoops(t, x, nn, &out->outline);
  out->outline_length3d = out->outline_length2d = 0.0;
  for (const auto &loop : out->outline)
    for (size_t k = 0; k < loop.size(); ++k) {
      const int a = loop[k], b = loop[(k + 1) % loop.size()];
      out->outline_length3d += Dist3(&m.coords[3 * (size_t)a], &m.coords[3 * (size_t)b]);
      out->outline_length2d += std::hypot(x[2 * (size_t)b] - x[2 * (size_t)a],
                                          x[2 * (size_t)b + 1] - x[2 * (size_t)a + 1]);
    }
  std::vector<std::string> names = opt.line_sets;
  for (const auto &s : m.node_sets)
    for (const auto &pre : opt.line_prefixes)
      if (s.first.compare(0, pre.size(), pre) == 0 &&
          std::find(names.begin(), names.end(), s.first) == names.end())
        names.push_back(s.first);
  out->lines.clear();
  for (const auto &name : names) {
    auto it = m.node_sets.find(name);
    if (it == m.node_sets.end()) {
      return Fail(m, err, "line set '" + name + "' is not a node set of the strip (it has " +
                              std::to_string(m.node_sets.size()) + " node sets)");
    }
    PatternLine line;
    if (!MeasureLine(m, t, x, name, it->second, &line, err)) return false;
    out->lines.push_back(std::move(line));
  }
  return true;
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
  if (!BuildTopology(m, &t, err)) return false;
  const int nn = m.NumNodes(), nl = t.NumLinks();
  {
    std::vector<int> order, via;
    TriangleBfs(m, t, 0, &order, &via);
    if ((int)order.size() != m.NumElements()) {
      return Fail(m, err, Format("the strip falls apart: only %d of its %d triangles are "
                                 "connected to triangle 0 across edges; flatten each piece on "
                                 "its own",
                                 (int)order.size(), m.NumElements()));
    }
  }
  Problem p;
  p.topo = &t;
  p.L.resize(nl);
  p.w.resize(nl);
  double lmean = 0.0;
  for (int i = 0; i < nl; ++i) {
    const int a = t.links[2 * i], b = t.links[2 * i + 1];
    p.L[i] = Dist3(&m.coords[3 * (size_t)a], &m.coords[3 * (size_t)b]);
    lmean += p.L[i] / nl;
    p.w[i] = t.Boundary(i) ? opt.boundary_weight : opt.interior_weight;
  }
  for (int i = 0; i < nl; ++i)
    if (!(p.L[i] > opt.min_link_rel * lmean)) {
      return Fail(m, err, Format("%s has 3D length %.3g mm (mean link %.3g mm): its nodes "
                                 "coincide, so the strip cannot be flattened; merge them",
                                 LinkName(t, i).c_str(), p.L[i], lmean));
    }
  p.min_len2d = 1e-12 * lmean;

  // Initial layouts: fold-free first, then the smaller S.
  std::vector<double> x;
  {
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
    x = cand[best];
    out->initial_guess = names[best];
    out->S_initial = out->S = best_S;
  }

  // Rigid motion: fix the node with the smallest x and the y of the one with the largest x of
  // the (principal-axis aligned) layout, far apart so the rotation is well determined.
  int a = 0, b = 0;
  for (int i = 0; i < nn; ++i) {
    if (x[2 * (size_t)i] < x[2 * (size_t)a]) a = i;
    if (x[2 * (size_t)i] > x[2 * (size_t)b]) b = i;
  }
  p.eq.assign(2 * (size_t)nn, -1);
  for (int k = 0; k < 2 * nn; ++k)
    if (k != 2 * a && k != 2 * a + 1 && k != 2 * b + 1) p.eq[k] = p.nfree++;

  std::string msg;
  const PetscErrorCode ierr = Iterate(m, opt, &p, lmean, &x, out, &msg);
  Objective(p, x, &out->S, nullptr);
  if (ierr) return Fail(m, err, Format("PETSc error %d while flattening (see the PETSc "
                                       "message above)", (int)ierr));
  // Fill in the report even on failure, for diagnosis.
  std::string rep_err;
  const bool reported = Report(m, t, opt, p, x, out, &rep_err);
  if (!msg.empty()) return Fail(m, err, msg);
  if (!reported) {
    if (err) *err = rep_err;
    return false;
  }
  int first = -1;
  const int folds = CountFolds(t, out->xy, &first);
  if (folds > 0) {
    return Fail(m, err, Format("the flattened strip folds over at %d interior links (first: %s); "
                               "the strip is too strongly curved for one piece: cut it into "
                               "narrower strips",
                               folds, LinkName(t, first).c_str()));
  }
  return true;
}

} // namespace etfe
