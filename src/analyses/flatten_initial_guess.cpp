// Initial plane layouts of a strip: projection onto the best-fit plane and triangle-by-triangle
// unfolding (see flatten.cpp for why both are tried).

#include <algorithm>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <map>
#include <queue>
#include <string>
#include <utility>
#include <vector>

#include "flatten_internal.h"

namespace etfe {
namespace flatten {

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

// Twice the strip's vector area: the sum of its triangles' normals, which orients a plane fitted
// to it the way its triangles face.
static void SummedNormal(const MeshData &m, double N[3]) {
  N[0] = N[1] = N[2] = 0.0;
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
}

// Every node projected onto the plane through c spanned by the first and last eigenvectors of V
// (columns; e3 the normal), e3 turned towards the triangles' summed normal so that consistently
// oriented triangles come out counter-clockwise.
static void ProjectOntoPlane(const MeshData &m, const double c[3], const double V[9], std::vector<double> *xy) {
  double N[3];
  SummedNormal(m, N);
  const double e1[3] = {V[0], V[3], V[6]};
  double e3[3] = {V[2], V[5], V[8]};
  if (e3[0] * N[0] + e3[1] * N[1] + e3[2] * N[2] < 0)
    for (double &v : e3) v = -v;
  const double e2[3] = {e3[1] * e1[2] - e3[2] * e1[1], e3[2] * e1[0] - e3[0] * e1[2],
                        e3[0] * e1[1] - e3[1] * e1[0]};
  const int nn = m.NumNodes();
  xy->assign(2 * (size_t)nn, 0.0);
  for (int i = 0; i < nn; ++i) {
    const double d[3] = {m.coords[3 * (size_t)i] - c[0], m.coords[3 * (size_t)i + 1] - c[1],
                         m.coords[3 * (size_t)i + 2] - c[2]};
    (*xy)[2 * (size_t)i] = d[0] * e1[0] + d[1] * e1[1] + d[2] * e1[2];
    (*xy)[2 * (size_t)i + 1] = d[0] * e2[0] + d[1] * e2[1] + d[2] * e2[2];
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
  ProjectOntoPlane(m, c, V, xy);
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

// The layout for FlattenOptions::hold_planar_outline: every node projected onto the best-fit
// plane of the outline nodes (its normal turned towards the triangles' mean normal, as in
// ProjectionGuess), the outline nodes flagged in *on_outline. False when the outline is not
// planar within rtol (of its largest distance from its centroid), is degenerate, or the
// projection folds (the strip is no graph over that plane): then the free flattening applies.
bool OutlinePlaneLayout(const MeshData &m, const Topology &t, double rtol, std::vector<double> *xy,
                        std::vector<char> *on_outline) {
  const int nn = m.NumNodes();
  on_outline->assign(nn, 0);
  for (int i = 0; i < t.NumLinks(); ++i)
    if (t.Boundary(i)) (*on_outline)[t.links[2 * i]] = (*on_outline)[t.links[2 * i + 1]] = 1;
  int no = 0;
  double c[3] = {0, 0, 0};
  for (int i = 0; i < nn; ++i)
    if ((*on_outline)[i]) {
      ++no;
      for (int k = 0; k < 3; ++k) c[k] += m.coords[3 * (size_t)i + k];
    }
  if (no < 3) return false;
  for (double &v : c) v /= no;
  double C[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0}, reach = 0.0;
  for (int i = 0; i < nn; ++i) {
    if (!(*on_outline)[i]) continue;
    const double d[3] = {m.coords[3 * (size_t)i] - c[0], m.coords[3 * (size_t)i + 1] - c[1],
                         m.coords[3 * (size_t)i + 2] - c[2]};
    reach = std::max(reach, std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]));
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) C[3 * a + b] += d[a] * d[b];
  }
  double vals[3], V[9];
  SymEigen3(C, vals, V);
  if (!(reach > 0) || !(vals[1] > 1e-12 * vals[0])) return false;  // a straight outline spans no plane
  const double e3[3] = {V[2], V[5], V[8]};
  for (int i = 0; i < nn; ++i) {
    if (!(*on_outline)[i]) continue;
    const double *X = &m.coords[3 * (size_t)i];
    if (std::fabs((X[0] - c[0]) * e3[0] + (X[1] - c[1]) * e3[1] + (X[2] - c[2]) * e3[2]) > rtol * reach) return false;
  }
  ProjectOntoPlane(m, c, V, xy);
  // Every triangle on one side (counter-clockwise, seen from e3): no fold, no sliver.
  for (int e = 0; e < m.NumElements(); ++e) {
    const int *v = &m.triangles[3 * (size_t)e];
    if (!(Cross2(&(*xy)[2 * (size_t)v[0]], &(*xy)[2 * (size_t)v[1]], &(*xy)[2 * (size_t)v[2]]) > 0)) return false;
  }
  return true;
}

} // namespace flatten
} // namespace etfe
