// Straightest geodesics on a triangle mesh: tracing (see etfe/kernels/geodesic.h for the rules).
// Directions are kept as unit 3D vectors in the plane of the current triangle; crossing an edge
// turns the direction about that edge into the next triangle's plane (the unfolding), so the
// component along the edge and the one across it are kept exactly.
#include "etfe/kernels/geodesic.h"
#include "etfe/kernels/vec3.h"

#include <cmath>
#include <limits>

namespace etfe {

namespace {

void Sub(const double *a, const double *b, double *c) {
  for (int i = 0; i < 3; ++i) c[i] = a[i] - b[i];
}
double Dot(const double *a, const double *b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
double Normalize(double *a) {
  const double n = std::sqrt(Dot(a, a));
  if (n > 0)
    for (int i = 0; i < 3; ++i) a[i] /= n;
  return n;
}
const double *X(const TriSurface &s, int n) { return &s.coords[3 * (size_t)n]; }

// Unit normal of triangle t (by its node order); false when degenerate.
bool Normal(const TriSurface &s, int t, double n[3]) {
  SurfaceTriangleNormal(s, t, n);
  return Normalize(n) > 0;
}

int IndexIn(const TriSurface &s, int t, int v) {
  for (int k = 0; k < 3; ++k)
    if (s.tris[3 * t + k] == v) return k;
  return -1;
}

// Corner frame of triangle t at its vertex v: e1 along the edge to the next node, e2 = n x e1 (so
// angles grow counter-clockwise, towards the previous node); returns the corner angle.
double CornerFrame(const TriSurface &s, int t, int v, double e1[3], double e2[3]) {
  const int j = IndexIn(s, t, v);
  double n[3], f[3];
  Normal(s, t, n);
  Sub(X(s, s.tris[3 * t + (j + 1) % 3]), X(s, v), e1);
  Normalize(e1);
  Cross(n, e1, e2);
  Sub(X(s, s.tris[3 * t + (j + 2) % 3]), X(s, v), f);
  return std::atan2(Dot(f, e2), Dot(f, e1));
}

// The triangles around v, counter-clockwise; at a boundary vertex from the first one after the
// boundary. *boundary says which.
void VertexFan(const TriSurface &s, int v, std::vector<int> *fan, bool *boundary) {
  fan->clear();
  *boundary = false;
  const int start = s.vtri[v];
  int t = start;
  // Clockwise to the boundary (or all the way round).
  for (int guard = 0; guard < 10000; ++guard) {
    const int j = IndexIn(s, t, v);
    const int prev = s.nbr[3 * t + j];  // across edge (v, next): clockwise
    if (prev < 0) {
      *boundary = true;
      break;
    }
    if (prev == start) break;
    t = prev;
  }
  const int first = *boundary ? t : start;
  t = first;
  for (int guard = 0; guard < 10000; ++guard) {
    fan->push_back(t);
    const int j = IndexIn(s, t, v);
    const int next = s.nbr[3 * t + (j + 2) % 3];  // across edge (previous, v): counter-clockwise
    if (next < 0 || next == first) break;
    t = next;
  }
}

// The edge k (from node k to node k+1) through which the ray P + s u leaves triangle T (unit
// normal n), the distance smin to it and the edge's outward unit normal m_exit in T's plane; -1
// when the ray leaves at once. P closer than on_edge_tol to an edge (relative to the longest
// edge) is on it and never leaves through it.
int ExitEdge(const TriSurface &s, int T, const double n[3], const double P[3], const double u[3], double *smin,
             double m_exit[3]) {
  const double on_edge_tol = 1e-13;
  const int *v = &s.tris[3 * T];
  double h = 0;
  for (int k = 0; k < 3; ++k) {
    double e[3];
    Sub(X(s, v[(k + 1) % 3]), X(s, v[k]), e);
    h = std::max(h, std::sqrt(Dot(e, e)));
  }
  *smin = std::numeric_limits<double>::infinity();
  int kexit = -1;
  m_exit[0] = m_exit[1] = m_exit[2] = 0;
  for (int k = 0; k < 3; ++k) {
    double e[3], m[3], w[3];
    Sub(X(s, v[(k + 1) % 3]), X(s, v[k]), e);
    Cross(e, n, m);  // outward normal of edge k in the triangle's plane
    Normalize(m);
    Sub(X(s, v[k]), P, w);
    const double dist = Dot(w, m), rate = Dot(u, m);
    if (dist <= on_edge_tol * h || rate <= 1e-15) continue;
    if (dist / rate < *smin) *smin = dist / rate, kexit = k, m_exit[0] = m[0], m_exit[1] = m[1], m_exit[2] = m[2];
  }
  return kexit;
}

// Unfolds the direction u across the edge e (leaving with outward normal m_exit) into triangle N:
// the components along the edge and across it are kept, the latter now in N's plane. e is
// normalised. False when N is degenerate.
bool UnfoldInto(const TriSurface &s, int N, double e[3], const double m_exit[3], double u[3]) {
  double nN[3], into[3];
  if (!Normal(s, N, nN)) return false;
  Normalize(e);
  Cross(e, nN, into);
  const double along = Dot(u, e), across = Dot(u, m_exit);
  for (int i = 0; i < 3; ++i) u[i] = along * e[i] + across * into[i];
  Normalize(u);
  return true;
}

} // namespace

void SurfaceTriangleNormal(const TriSurface &s, int t, double n[3]) {
  double e1[3], e2[3];
  Sub(X(s, s.tris[3 * t + 1]), X(s, s.tris[3 * t]), e1);
  Sub(X(s, s.tris[3 * t + 2]), X(s, s.tris[3 * t]), e2);
  Cross(e1, e2, n);
}

bool SurfaceVertexOnBoundary(const TriSurface &s, int v) {
  std::vector<int> fan;
  bool b;
  VertexFan(s, v, &fan, &b);
  return b;
}

double SurfaceVertexAngle(const TriSurface &s, int v) {
  std::vector<int> fan;
  bool b;
  VertexFan(s, v, &fan, &b);
  double theta = 0, e1[3], e2[3];
  for (int t : fan) theta += CornerFrame(s, t, v, e1, e2);
  return theta;
}

bool GeodesicStartAtVertex(const TriSurface &s, int v, const double d[3], int *tri, double dir[3]) {
  std::vector<int> fan;
  bool b;
  VertexFan(s, v, &fan, &b);
  double best = std::numeric_limits<double>::infinity();
  for (int t : fan) {
    double e1[3], e2[3];
    const double alpha = CornerFrame(s, t, v, e1, e2);
    const double x = Dot(d, e1), y = Dot(d, e2);
    if (x * x + y * y == 0) continue;
    double phi = std::atan2(y, x);
    const double miss = phi < 0 ? -phi : phi > alpha ? phi - alpha : 0.0;
    if (miss < best) {
      best = miss;
      phi = std::min(std::max(phi, 0.0), alpha);
      *tri = t;
      for (int i = 0; i < 3; ++i) dir[i] = std::cos(phi) * e1[i] + std::sin(phi) * e2[i];
    }
  }
  return best < std::numeric_limits<double>::infinity();
}

bool GeodesicOppositeAtVertex(const TriSurface &s, int v, int tri, const double ray[3], int *tri_out,
                              double dir_out[3]) {
  std::vector<int> fan;
  bool boundary;
  VertexFan(s, v, &fan, &boundary);
  if (boundary) return false;
  double theta = 0, e1[3], e2[3];
  for (int t : fan) theta += CornerFrame(s, t, v, e1, e2);
  double alpha = CornerFrame(s, tri, v, e1, e2);
  const double beta = std::min(std::max(std::atan2(Dot(ray, e2), Dot(ray, e1)), 0.0), alpha);
  double rest = beta + 0.5 * theta - alpha;  // angle still to turn past this triangle
  int t = tri;
  for (size_t step = 0; step <= fan.size(); ++step) {
    const int j = IndexIn(s, t, v);
    t = s.nbr[3 * t + (j + 2) % 3];
    if (t < 0) return false;
    alpha = CornerFrame(s, t, v, e1, e2);
    if (rest <= alpha) {
      rest = std::max(rest, 0.0);
      for (int i = 0; i < 3; ++i) dir_out[i] = std::cos(rest) * e1[i] + std::sin(rest) * e2[i];
      *tri_out = t;
      return true;
    }
    rest -= alpha;
  }
  return false;
}

bool GeodesicTrace(const TriSurface &s, int tri, const double P0[3], const double d[3], int max_steps,
                   GeodesicPath *out, std::string *err) {
  *out = GeodesicPath();
  int T = tri;
  double P[3] = {P0[0], P0[1], P0[2]}, u[3], n[3];
  if (!Normal(s, T, n)) {
    *err = "geodesic trace: triangle " + std::to_string(T) + " is degenerate";
    return false;
  }
  const double dn = Dot(d, n);
  for (int i = 0; i < 3; ++i) u[i] = d[i] - dn * n[i];
  if (!(Normalize(u) > 0)) {
    *err = "geodesic trace: the direction is zero or normal to triangle " + std::to_string(T);
    return false;
  }
  // A crossing this close to an edge end (relative) goes through the vertex.
  const double vertex_tol = 1e-12;
  for (int step = 0; step < max_steps; ++step) {
    const int *v = &s.tris[3 * T];
    if (!Normal(s, T, n)) {
      *err = "geodesic trace: triangle " + std::to_string(T) + " is degenerate";
      return false;
    }
    double smin, m_exit[3];
    const int kexit = ExitEdge(s, T, n, P, u, &smin, m_exit);
    if (kexit < 0) {
      *err = "geodesic trace: the direction leaves triangle " + std::to_string(T) + " at once (start outside it)";
      return false;
    }
    const int a = v[kexit], b = v[(kexit + 1) % 3];
    double x[3], e[3], w[3];
    for (int i = 0; i < 3; ++i) x[i] = P[i] + smin * u[i];
    Sub(X(s, b), X(s, a), e);
    Sub(x, X(s, a), w);
    const double tau = Dot(w, e) / Dot(e, e);
    out->segment_tri.push_back(T);
    out->segment_dir.insert(out->segment_dir.end(), u, u + 3);
    SurfacePoint sp;
    if (tau <= vertex_tol || tau >= 1 - vertex_tol) {
      const int c = tau <= vertex_tol ? a : b;
      sp.a = c;
      for (int i = 0; i < 3; ++i) sp.x[i] = s.coords[3 * (size_t)c + i];
      double step3[3];
      Sub(sp.x, P, step3);
      out->length += std::sqrt(Dot(step3, step3));
      out->points.push_back(sp);
      const double back[3] = {-u[0], -u[1], -u[2]};
      int T2;
      if (!GeodesicOppositeAtVertex(s, c, T, back, &T2, u)) {
        out->reached_boundary = true;  // a boundary vertex
        return true;
      }
      ++out->vertices_passed;
      T = T2;
      for (int i = 0; i < 3; ++i) P[i] = sp.x[i];
      continue;
    }
    sp.a = std::min(a, b), sp.b = std::max(a, b), sp.t = a < b ? tau : 1 - tau;
    for (int i = 0; i < 3; ++i) sp.x[i] = x[i];
    out->length += smin;
    out->points.push_back(sp);
    const int N = s.nbr[3 * T + kexit];
    if (N < 0) {
      out->reached_boundary = true;
      return true;
    }
    if (!UnfoldInto(s, N, e, m_exit, u)) {
      *err = "geodesic trace: triangle " + std::to_string(N) + " is degenerate";
      return false;
    }
    T = N;
    for (int i = 0; i < 3; ++i) P[i] = x[i];
  }
  out->reached_boundary = false;
  return true;
}

} // namespace etfe
