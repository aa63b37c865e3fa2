// Triangle-triangle contact (etfe/kernels/tri_intersect.h): the interval test across the line
// where the two planes meet (Moeller 1997) for crossing triangles, and clipping in the plane for
// coplanar ones. Both are written for "interiors cross by more than tol", not for "touch".
#include "etfe/kernels/tri_intersect.h"

#include <algorithm>
#include <cmath>

#include "etfe/kernels/vec3.h"

namespace etfe {
namespace {

double Dot(const double *a, const double *b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

// Unit normal of triangle t; false when it is degenerate.
bool UnitNormal(const double *t, double n[3]) {
  const double u[3] = {t[3] - t[0], t[4] - t[1], t[5] - t[2]};
  const double v[3] = {t[6] - t[0], t[7] - t[1], t[8] - t[2]};
  Cross(u, v, n);
  const double l = std::sqrt(Dot(n, n));
  if (!(l > 0) || !std::isfinite(l)) return false;
  for (int k = 0; k < 3; ++k) n[k] /= l;
  return true;
}

// Signed distances of t's corners to the plane through p with unit normal n.
void Distances(const double *t, const double *p, const double *n, double d[3]) {
  for (int i = 0; i < 3; ++i) {
    const double r[3] = {t[3 * i] - p[0], t[3 * i + 1] - p[1], t[3 * i + 2] - p[2]};
    d[i] = Dot(r, n);
  }
}

// Strictly on both sides of the other's plane (by more than tol): only then can its interior
// reach the other's interior. A triangle on one side with an edge or corner in the plane touches.
bool Straddles(const double d[3], double tol) {
  const double lo = std::min({d[0], d[1], d[2]}), hi = std::max({d[0], d[1], d[2]});
  return lo < -tol && hi > tol;
}

// The segment where t (corners at signed distances d, straddling) meets the other plane:
// its two ends, and their parameters along the direction dir.
void PlaneSegment(const double *t, const double d[3], const double *dir, double end[2][3], double s[2]) {
  int m = 0;
  for (int i = 0; i < 3 && m < 2; ++i) {
    const int j = (i + 1) % 3;
    if ((d[i] < 0) == (d[j] < 0)) continue;  // this edge stays on one side
    const double f = d[i] / (d[i] - d[j]);
    for (int k = 0; k < 3; ++k) end[m][k] = t[3 * i + k] + f * (t[3 * j + k] - t[3 * i + k]);
    ++m;
  }
  for (int q = 0; q < 2; ++q) s[q] = Dot(end[q], dir);
  if (s[0] > s[1]) {
    std::swap(s[0], s[1]);
    for (int k = 0; k < 3; ++k) std::swap(end[0][k], end[1][k]);
  }
}

double Area2(const double p[][2], int n) {
  double a = 0;
  for (int i = 0; i < n; ++i) {
    const int j = (i + 1) % n;
    a += p[i][0] * p[j][1] - p[j][0] * p[i][1];
  }
  return 0.5 * a;
}

// Clips the convex polygon poly (n corners, counterclockwise) by the counterclockwise triangle
// tri: Sutherland-Hodgman, at most 9 corners out.
int Clip(const double tri[3][2], double poly[12][2], int n) {
  for (int e = 0; e < 3 && n > 0; ++e) {
    const double *a = tri[e], *b = tri[(e + 1) % 3];
    double out[12][2];
    int m = 0;
    auto side = [&](const double *p) { return (b[0] - a[0]) * (p[1] - a[1]) - (b[1] - a[1]) * (p[0] - a[0]); };
    for (int i = 0; i < n; ++i) {
      const double *p = poly[i], *q = poly[(i + 1) % n];
      const double sp = side(p), sq = side(q);
      if (sp >= 0 && m < 12) { out[m][0] = p[0]; out[m][1] = p[1]; ++m; }
      if ((sp >= 0) != (sq >= 0) && m < 12) {
        const double f = sp / (sp - sq);
        out[m][0] = p[0] + f * (q[0] - p[0]);
        out[m][1] = p[1] + f * (q[1] - p[1]);
        ++m;
      }
    }
    n = m;
    for (int i = 0; i < n; ++i) { poly[i][0] = out[i][0]; poly[i][1] = out[i][1]; }
  }
  return n;
}

// Coplanar triangles: the area of their common part, in the plane of unit normal n.
TriContact CoplanarContact(const double a[9], const double b[9], const double *n, double tol, double point[3]) {
  int ax = 0;  // drop the normal's largest component: the projection keeps areas up to a factor
  for (int k = 1; k < 3; ++k)
    if (std::fabs(n[k]) > std::fabs(n[ax])) ax = k;
  const int u = (ax + 1) % 3, v = (ax + 2) % 3;
  double pa[3][2], pb[12][2];
  for (int i = 0; i < 3; ++i) {
    pa[i][0] = a[3 * i + u]; pa[i][1] = a[3 * i + v];
    pb[i][0] = b[3 * i + u]; pb[i][1] = b[3 * i + v];
  }
  if (Area2(pa, 3) < 0) std::swap(pa[1], pa[2]);
  if (Area2(pb, 3) < 0) std::swap(pb[1], pb[2]);
  double longest = 0;
  for (int i = 0; i < 3; ++i) {
    const int j = (i + 1) % 3;
    longest = std::max({longest, std::hypot(pa[j][0] - pa[i][0], pa[j][1] - pa[i][1]),
                        std::hypot(pb[j][0] - pb[i][0], pb[j][1] - pb[i][1])});
  }
  const int m = Clip(pa, pb, 3);
  if (m < 3 || !(Area2(pb, m) > tol * longest)) return TriContact::None;
  // A point of the common part (its corners' mean), lifted back onto a's plane.
  double c[2] = {0, 0};
  for (int i = 0; i < m; ++i) { c[0] += pb[i][0] / m; c[1] += pb[i][1] / m; }
  point[u] = c[0];
  point[v] = c[1];
  point[ax] = a[ax] - (n[u] * (c[0] - a[u]) + n[v] * (c[1] - a[v])) / n[ax];
  return TriContact::Coplanar;
}

} // namespace

TriContact TriangleContact(const double a[9], const double b[9], double tol, double point[3]) {
  double na[3], nb[3], da[3], db[3];
  if (!UnitNormal(a, na) || !UnitNormal(b, nb)) return TriContact::None;
  Distances(b, a, na, db);  // b's corners against a's plane
  Distances(a, b, nb, da);
  const bool b_in_a = std::max({std::fabs(db[0]), std::fabs(db[1]), std::fabs(db[2])}) <= tol;
  const bool a_in_b = std::max({std::fabs(da[0]), std::fabs(da[1]), std::fabs(da[2])}) <= tol;
  if (b_in_a || a_in_b) return CoplanarContact(a, b, b_in_a ? na : nb, tol, point);
  if (!Straddles(da, tol) || !Straddles(db, tol)) return TriContact::None;
  double dir[3];
  Cross(na, nb, dir);
  double ea[2][3], eb[2][3], sa[2], sb[2];
  PlaneSegment(a, da, dir, ea, sa);
  PlaneSegment(b, db, dir, eb, sb);
  const double lo = std::max(sa[0], sb[0]), hi = std::min(sa[1], sb[1]);
  const double sin_angle = std::sqrt(Dot(dir, dir));  // dir is not unit: s scales by it
  if (!(hi - lo > tol * sin_angle)) return TriContact::None;
  const double mid = 0.5 * (lo + hi);
  const double f = sa[1] > sa[0] ? (mid - sa[0]) / (sa[1] - sa[0]) : 0.0;
  for (int k = 0; k < 3; ++k) point[k] = ea[0][k] + f * (ea[1][k] - ea[0][k]);
  return TriContact::Cross;
}

} // namespace etfe
