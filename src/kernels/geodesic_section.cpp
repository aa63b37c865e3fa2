// Plane sections of a triangle mesh as cutting lines (see etfe/kernels/geodesic.h), and the
// turning of a polyline of nodes (how smooth a seam is).
#include <algorithm>
#include <cmath>

#include "etfe/kernels/geodesic.h"

namespace etfe {

std::vector<std::vector<SurfacePoint>> SurfacePlaneSection(const TriSurface &s, const double n[3], double c,
                                                           int *loops) {
  const int nt = s.NumTris(), nn = s.NumNodes();
  std::vector<double> d(nn);
  for (int v = 0; v < nn; ++v) d[v] = n[0] * s.coords[3 * v] + n[1] * s.coords[3 * v + 1] + n[2] * s.coords[3 * v + 2] - c;
  // A node on the plane counts on its + side: every triangle then has 0 or 2 crossed edges.
  auto side = [&](int v) { return d[v] >= 0; };
  auto crossed = [&](int e, int k) { return side(s.tris[3 * e + k]) != side(s.tris[3 * e + (k + 1) % 3]); };
  auto point = [&](int e, int k) {
    SurfacePoint p;
    int a = s.tris[3 * e + k], b = s.tris[3 * e + (k + 1) % 3];
    if (a > b) std::swap(a, b);
    p.a = a, p.b = b;
    p.t = std::min(1.0, std::max(0.0, d[a] / (d[a] - d[b])));
    for (int i = 0; i < 3; ++i) p.x[i] = s.coords[3 * a + i] + p.t * (s.coords[3 * b + i] - s.coords[3 * a + i]);
    return p;
  };
  std::vector<char> seen(3 * (size_t)nt, 0);  // crossed half-edges walked
  std::vector<std::vector<SurfacePoint>> out;
  // Walks from the crossed edge k of e into e, to a boundary edge (or back to the start).
  auto walk = [&](int e, int k, std::vector<SurfacePoint> *line) {
    line->push_back(point(e, k));
    for (int guard = 0; guard <= 3 * nt; ++guard) {
      seen[3 * e + k] = 1;
      int j = -1;
      for (int i = 0; i < 3; ++i)
        if (i != k && crossed(e, i)) j = i;
      if (j < 0) return;
      seen[3 * e + j] = 1;
      line->push_back(point(e, j));
      const int f = s.nbr[3 * e + j];
      if (f < 0) return;
      const int a = s.tris[3 * e + j], b = s.tris[3 * e + (j + 1) % 3];
      int kf = -1;
      for (int i = 0; i < 3; ++i)
        if ((s.tris[3 * f + i] == b && s.tris[3 * f + (i + 1) % 3] == a) ||
            (s.tris[3 * f + i] == a && s.tris[3 * f + (i + 1) % 3] == b))
          kf = i;
      if (kf < 0 || seen[3 * f + kf]) return;
      e = f, k = kf;
    }
  };
  for (int e = 0; e < nt; ++e)
    for (int k = 0; k < 3; ++k)
      if (s.nbr[3 * e + k] < 0 && crossed(e, k) && !seen[3 * e + k]) {
        std::vector<SurfacePoint> line;
        walk(e, k, &line);
        if (line.size() >= 2) out.push_back(line);
      }
  int count = 0;
  for (int e = 0; e < nt; ++e)
    for (int k = 0; k < 3; ++k)
      if (crossed(e, k) && !seen[3 * e + k]) {
        std::vector<SurfacePoint> loop;
        walk(e, k, &loop);
        ++count;
      }
  if (loops) *loops = count;
  return out;
}

double PolylineMaxTurn(const TriSurface &s, const std::vector<int> &nodes) {
  double worst = 0;
  for (size_t i = 1; i + 1 < nodes.size(); ++i) {
    const double *a = &s.coords[3 * (size_t)nodes[i - 1]], *b = &s.coords[3 * (size_t)nodes[i]],
                 *c = &s.coords[3 * (size_t)nodes[i + 1]];
    double u[3], w[3];
    for (int k = 0; k < 3; ++k) u[k] = b[k] - a[k], w[k] = c[k] - b[k];
    const double lu = std::sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]), lw = std::sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
    if (lu == 0 || lw == 0) continue;
    const double cr[3] = {u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]};
    worst = std::max(worst, std::atan2(std::sqrt(cr[0] * cr[0] + cr[1] * cr[1] + cr[2] * cr[2]),
                                       u[0] * w[0] + u[1] * w[1] + u[2] * w[2]));
  }
  return worst;
}

} // namespace etfe
