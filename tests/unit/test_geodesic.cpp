// Geodesic cutting lines (etfe/kernels/geodesic.h): a traced geodesic on a plane is the straight
// line (1e-12), on a cylinder (a prism of flat faces: developable) it is a helix or generator whose
// developed image is straight (1e-10); inserting lines keeps the area (1e-12), leaves no triangle
// below a quality bound, cuts the surface into the expected pieces and refuses crossing lines.
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "check.h"
#include "etfe/kernels/geodesic.h"

using namespace etfe;

namespace {

// An nx x ny grid of the unit square mapped by f, alternating diagonals (as the scene tests').
template <class F>
void Grid(int nx, int ny, F f, std::vector<double> *coords, std::vector<int> *tris) {
  coords->clear(), tris->clear();
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i) {
      double x[3];
      f(i, j, x);
      coords->insert(coords->end(), x, x + 3);
    }
  auto id = [&](int i, int j) { return j * (nx + 1) + i; };
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const int a = id(i, j), b = id(i + 1, j), c = id(i + 1, j + 1), d = id(i, j + 1);
      if ((i + j) % 2 == 0) tris->insert(tris->end(), {a, b, c, a, c, d});
      else tris->insert(tris->end(), {a, b, d, b, c, d});
    }
}

double TotalArea(const TriSurface &s) {
  double A = 0;
  for (int e = 0; e < s.NumTris(); ++e)
    A += TriangleArea(&s.coords[3 * s.tris[3 * e]], &s.coords[3 * s.tris[3 * e + 1]], &s.coords[3 * s.tris[3 * e + 2]]);
  return A;
}

double MinQuality(const TriSurface &s) {
  double q = 1;
  for (int e = 0; e < s.NumTris(); ++e)
    q = std::min(q, TriangleQuality(&s.coords[3 * s.tris[3 * e]], &s.coords[3 * s.tris[3 * e + 1]],
                                    &s.coords[3 * s.tris[3 * e + 2]]));
  return q;
}

// A triangle of s holding the point p of the plane z = 0 (barycentric test).
int Locate2D(const TriSurface &s, const double p[2]) {
  for (int e = 0; e < s.NumTris(); ++e) {
    const double *a = &s.coords[3 * s.tris[3 * e]], *b = &s.coords[3 * s.tris[3 * e + 1]],
                 *c = &s.coords[3 * s.tris[3 * e + 2]];
    auto side = [](const double *u, const double *v, const double *w) {
      return (v[0] - u[0]) * (w[1] - u[1]) - (v[1] - u[1]) * (w[0] - u[0]);
    };
    if (side(a, b, p) >= 0 && side(b, c, p) >= 0 && side(c, a, p) >= 0) return e;
  }
  return -1;
}

// The plane z = 0 over [0, 1000]^2 mm, nodes moved off the grid (a deterministic jitter).
void JitteredPlane(TriSurface *s) {
  std::vector<double> c;
  std::vector<int> t;
  Grid(12, 10, [](int i, int j, double *x) {
    const bool inner = i > 0 && i < 12 && j > 0 && j < 10;
    x[0] = 1000.0 * i / 12 + (inner ? 25.0 * std::sin(7.1 * i + 3.3 * j) : 0.0);
    x[1] = 1000.0 * j / 10 + (inner ? 25.0 * std::cos(5.3 * i - 2.9 * j) : 0.0);
    x[2] = 0.0;
  }, &c, &t);
  std::string err;
  CHECK(SurfaceFromArrays(c, t, s, &err), "%s", err.c_str());
}

} // namespace

int main() {
  std::string err;
  // 1. Plane: straight lines, through the jittered mesh and along grid lines through vertices.
  {
    TriSurface s;
    JitteredPlane(&s);
    const double P[3] = {480.0, 510.0, 0.0};
    const int T = Locate2D(s, P);
    double worst = 0;
    for (double ang : {0.1, 0.7, 1.3, 2.0, 2.9, 4.0, 5.5}) {
      const double d[3] = {std::cos(ang), std::sin(ang), 0.0};
      GeodesicPath g;
      CHECK(GeodesicTrace(s, T, P, d, 1000, &g, &err), "%s", err.c_str());
      CHECK(g.reached_boundary && !g.points.empty(), "plane: the line reaches the boundary (angle %g)", ang);
      for (const SurfacePoint &p : g.points) {
        const double off = -(p.x[0] - P[0]) * d[1] + (p.x[1] - P[1]) * d[0];
        worst = std::max(worst, std::fabs(off));
      }
      const SurfacePoint &last = g.points.back();
      CHECK(std::fabs(std::hypot(last.x[0] - P[0], last.x[1] - P[1]) - g.length) < 1e-9,
            "plane: the traced length is the distance to its end");
    }
    std::printf("plane (jittered 12 x 10 mesh, 1000 mm): largest distance of a traced point from the line %.2e mm\n",
                worst);
    CHECK(worst < 1e-12 * 1000, "plane: every crossing on the straight line (%.2e mm)", worst);
    // Along a grid line of a regular mesh: through vertices (the theta/2 rule, theta = 2 pi).
    std::vector<double> c;
    std::vector<int> t;
    Grid(8, 8, [](int i, int j, double *x) { x[0] = 100.0 * i, x[1] = 100.0 * j, x[2] = 0.0; }, &c, &t);
    TriSurface g8;
    CHECK(SurfaceFromArrays(c, t, &g8, &err), "%s", err.c_str());
    const int v = 4 * 9 + 4;  // the middle node (400, 400)
    for (double ang : {0.0, M_PI / 4, M_PI / 2, 3.0}) {
      const double d[3] = {std::cos(ang), std::sin(ang), 0.0};
      int tri;
      double dir[3];
      CHECK(GeodesicStartAtVertex(g8, v, d, &tri, dir), "start at a vertex");
      GeodesicPath g;
      CHECK(GeodesicTrace(g8, tri, &g8.coords[3 * v], dir, 1000, &g, &err), "%s", err.c_str());
      double off = 0;
      for (const SurfacePoint &p : g.points)
        off = std::max(off, std::fabs(-(p.x[0] - 400.0) * d[1] + (p.x[1] - 400.0) * d[0]));
      CHECK(off < 1e-12 * 1000 && g.reached_boundary, "grid line at %g rad through %d vertices: off %.2e", ang,
            g.vertices_passed, off);
      int back_tri;
      double back[3];
      CHECK(GeodesicOppositeAtVertex(g8, v, tri, dir, &back_tri, back), "the opposite direction");
      CHECK(std::fabs(back[0] + dir[0]) < 1e-14 && std::fabs(back[1] + dir[1]) < 1e-14,
            "flat vertex: the theta/2 rule turns by pi (%g, %g)", back[0], back[1]);
    }
    CHECK(std::fabs(SurfaceVertexAngle(g8, v) - 2 * M_PI) < 1e-14, "a flat interior vertex has 2 pi around it");
  }
  // 2. Cylinder R = 500 mm as a prism of 24 flat faces over 120 degrees, 800 mm high: developable.
  {
    const int nx = 24, ny = 10;
    const double R = 500.0, span = 2.0 * M_PI / 3.0, H = 800.0;
    std::vector<double> c;
    std::vector<int> t;
    Grid(nx, ny, [&](int i, int j, double *x) {
      x[0] = R * std::cos(span * i / nx), x[1] = R * std::sin(span * i / nx), x[2] = H * j / ny;
    }, &c, &t);
    TriSurface s;
    CHECK(SurfaceFromArrays(c, t, &s, &err), "%s", err.c_str());
    const double chord = 2 * R * std::sin(0.5 * span / nx);
    // Developed coordinates of a point on the prism: (arc along the polygon, z).
    auto develop = [&](const double *x, double *u) {
      double phi = std::atan2(x[1], x[0]);
      int i = std::min(nx - 1, std::max(0, (int)std::floor(phi / (span / nx))));
      const double a0 = span * i / nx;
      const double p[2] = {R * std::cos(a0), R * std::sin(a0)};
      u[0] = i * chord + std::hypot(x[0] - p[0], x[1] - p[1]);
      u[1] = x[2];
    };
    const int vmid = 5 * (nx + 1) + 12;  // a node in the middle
    const double *Pm = &s.coords[3 * vmid];
    const double tangent[3] = {-Pm[1] / R, Pm[0] / R, 0.0};
    for (double tilt : {0.0, 0.35, 0.9, M_PI / 2}) {  // 0: around the axis; pi/2: a generator
      const double d[3] = {std::cos(tilt) * tangent[0], std::cos(tilt) * tangent[1], std::sin(tilt)};
      int tri;
      double dir[3];
      CHECK(GeodesicStartAtVertex(s, vmid, d, &tri, dir), "cylinder: start");
      GeodesicPath g;
      CHECK(GeodesicTrace(s, tri, Pm, dir, 1000, &g, &err), "%s", err.c_str());
      CHECK(g.reached_boundary, "cylinder: reaches the boundary (tilt %g)", tilt);
      double u0[2], u1[2], off = 0;
      develop(Pm, u0);
      develop(g.points.back().x, u1);
      const double L = std::hypot(u1[0] - u0[0], u1[1] - u0[1]);
      for (const SurfacePoint &p : g.points) {
        double u[2];
        develop(p.x, u);
        off = std::max(off, std::fabs((u[0] - u0[0]) * (u1[1] - u0[1]) - (u[1] - u0[1]) * (u1[0] - u0[0])) / L);
      }
      std::printf("cylinder R %g mm, tilt %.2f rad: %zu crossings, %d vertices passed, developed line off straight "
                  "by %.2e mm, length %.6f (developed %.6f) mm\n",
                  R, tilt, g.points.size(), g.vertices_passed, off, g.length, L);
      CHECK(off < 1e-10 * 1000, "cylinder: the developed geodesic is straight (%.2e mm)", off);
      CHECK(std::fabs(g.length - L) < 1e-10 * L, "cylinder: its length is the developed distance");
    }
  }
  // 3. Insertion on the jittered plane: parallel lines cut it into pieces, area kept, quality.
  {
    TriSurface s;
    JitteredPlane(&s);
    const double A0 = TotalArea(s), q0 = MinQuality(s), snap = 0.2;
    int lines = 0;
    for (double y : {500.0, 300.0, 700.0, 420.0}) {
      const double P[3] = {500.0, y, 0.0}, d[3] = {std::cos(0.2), std::sin(0.2), 0.0},
                   back[3] = {-d[0], -d[1], 0.0};
      const int T = Locate2D(s, P);
      GeodesicPath f, b;
      CHECK(GeodesicTrace(s, T, P, d, 1000, &f, &err) && GeodesicTrace(s, T, P, back, 1000, &b, &err), "%s",
            err.c_str());
      std::vector<SurfacePoint> line(b.points.rbegin(), b.points.rend());
      line.insert(line.end(), f.points.begin(), f.points.end());
      std::vector<int> verts;
      double moved = 0;
      CHECK(SurfaceInsertLine(&s, line, snap, &verts, &moved, &err), "%s", err.c_str());
      ++lines;
      // The inserted line stays within snap * (edge length) of the traced one.
      double off = 0;
      for (int v : verts) off = std::max(off, std::fabs(-(s.coords[3 * v] - P[0]) * d[1] + (s.coords[3 * v + 1] - P[1]) * d[0]));
      std::vector<int> label;
      const int pieces = SurfaceComponents(s, &label);
      std::printf("plane, line %d at y %g: %zu vertices, %d triangles, %d pieces, area change %.2e, min quality %.3f "
                  "(mesh %.3f), inserted line off the geodesic by at most %.2f mm\n",
                  lines, y, verts.size(), s.NumTris(), pieces, std::fabs(TotalArea(s) - A0) / A0, MinQuality(s), q0, off);
      CHECK(pieces == lines + 1, "%d lines across the plane cut it into %d pieces (%d)", lines, lines + 1, pieces);
      CHECK(std::fabs(TotalArea(s) - A0) <= 1e-12 * A0, "the area is kept to 1e-12");
      CHECK(MinQuality(s) >= 0.25 * snap * q0, "no triangle below 0.25 snap x the mesh's worst quality (%.3f)",
            MinQuality(s));
      // Nodes near the line are moved onto it (the plane's boundary is straight, so even there):
      // the inserted line is the traced one.
      CHECK(off < 1e-9, "every node of the inserted line lies on the traced line (%.2e mm)", off);
      CHECK(off <= moved + 1e-9 && moved <= snap * 130.0,
            "the inserted line is within the reported snap distance %.2f mm (<= snap x the longest edge) of the "
            "traced line", moved);
    }
    // A line across them is refused by name.
    const double P[3] = {500.0, 100.0, 0.0}, d[3] = {0.0, 1.0, 0.0};
    GeodesicPath g;
    CHECK(GeodesicTrace(s, Locate2D(s, P), P, d, 1000, &g, &err), "%s", err.c_str());
    std::vector<int> verts;
    const bool ok = SurfaceInsertLine(&s, g.points, snap, &verts, nullptr, &err);
    CHECK(!ok && (err.find("crosses another cutting line") != std::string::npos ||
                  err.find("meets another cutting line") != std::string::npos),
          "a crossing line is refused: %s", err.c_str());
  }
  // 4. Plane sections: the jittered plane cut by the plane x = 333: one line from boundary to
  // boundary, every crossing on the plane; inserted, every seam node on it and two pieces.
  {
    TriSurface s;
    JitteredPlane(&s);
    const double n[3] = {1.0, 0.0, 0.0};
    int loops = -1;
    const auto lines = SurfacePlaneSection(s, n, 333.0, &loops);
    CHECK(lines.size() == 1 && loops == 0, "plane x = 333: one open section (%zu lines, %d loops)", lines.size(), loops);
    double off = 0;
    for (const SurfacePoint &p : lines[0]) off = std::max(off, std::fabs(p.x[0] - 333.0));
    CHECK(off < 1e-9, "every crossing on the plane (%.2e mm)", off);
    std::vector<int> verts;
    LineInsertOptions io;
    LineInsertStats st;
    CHECK(SurfaceInsertLine(&s, lines[0], io, &verts, &st, &err), "%s", err.c_str());
    double voff = 0;
    for (int v : verts) voff = std::max(voff, std::fabs(s.coords[3 * v] - 333.0));
    std::vector<int> label;
    std::printf("plane section x = 333: %zu crossings, %zu seam nodes, %d nodes moved onto it (%.2f mm at most), "
                "largest turn %.2e rad, seam nodes off the plane %.2e mm\n",
                lines[0].size(), verts.size(), st.relocated, st.relocated_max, PolylineMaxTurn(s, verts), voff);
    CHECK(voff < 1e-9 && PolylineMaxTurn(s, verts) < 1e-9, "the seam is the straight section (%.2e mm)", voff);
    CHECK(SurfaceComponents(s, &label) == 2, "the section cuts the plane in two");
  }
  TEST_MAIN_END();
}
