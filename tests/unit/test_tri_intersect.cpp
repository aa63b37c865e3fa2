// Triangle-triangle contact (etfe/kernels/tri_intersect.h) and the mesh's self-intersection check
// (etfe/mesh/self_intersection.h): crossing triangles are found with a point on the crossing;
// touching at a vertex, sharing an edge (coincident, separate nodes), an edge lying on the other
// triangle, coplanar and apart are not crossing; coplanar overlap is reported as such. On meshes:
// a strip folded through itself is refused naming its two file tags; a wavy grid, two coplanar
// layers in different groups and a closed lens of two foils sharing the rim pass; coplanar layers
// in one group are refused; a triangle 1000 times the grid's, above it, passes, and through it
// is refused. ETFE_TIME_N=n times the check on a 2 n^2 triangle wavy grid.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "check.h"
#include "etfe/kernels/tri_intersect.h"
#include "etfe/mesh/self_intersection.h"

using etfe::MeshData;
using etfe::TriContact;
using etfe::TriangleContact;

namespace {

bool Contains(const std::string &s, const std::string &part) { return s.find(part) != std::string::npos; }

// An n x n grid of squares of side 1 over [0,n]^2 at height z(x, y), two triangles per square,
// node ids from `base`.
void Grid(MeshData *m, int n, double (*z)(double, double)) {
  const int base = m->NumNodes();
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      m->coords.push_back(i);
      m->coords.push_back(j);
      m->coords.push_back(z(i, j));
    }
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const int a = base + j * (n + 1) + i, b = a + 1, c = a + n + 2, d = a + n + 1;
      for (int v : {a, b, c, a, c, d}) m->triangles.push_back(v);
    }
}

double Wavy(double x, double y) { return 0.3 * std::sin(0.7 * x) * std::cos(0.5 * y); }
double Flat(double, double) { return 0.0; }

void Group(MeshData *m, const std::string &name, int from, int to) {
  for (int e = from; e < to; ++e) m->element_sets[name].push_back(e);
}

} // namespace

int main() {
  double x[3];
  {  // the kernel
    const double a[9] = {0, 0, 0, 2, 0, 0, 0, 2, 0};
    const double cross[9] = {0.5, 0.5, -1, 0.5, 0.5, 1, 1.5, -0.5, 0};  // through a's interior
    CHECK(TriangleContact(a, cross, 1e-9, x) == TriContact::Cross, "crossing");
    CHECK(std::fabs(x[2]) < 1e-12 && x[0] > 0 && x[1] > 0 && x[0] + x[1] < 2, "point on both: %g %g %g", x[0], x[1],
          x[2]);
    const double vertex[9] = {0, 0, 0, -1, -1, 1, -1, 1, -1};  // one corner at a's corner
    CHECK(TriangleContact(a, vertex, 1e-9, x) == TriContact::None, "touching at a vertex");
    const double vertex_in[9] = {0.5, 0.5, 0, 0.5, 1, 1, 1, 0.5, 1};  // one corner on a's face, above
    CHECK(TriangleContact(a, vertex_in, 1e-9, x) == TriContact::None, "a corner resting on the face");
    const double edge[9] = {0, 0, 0, 2, 0, 0, 1, 0, 1};  // a's edge, coincident nodes, folded up
    CHECK(TriangleContact(a, edge, 1e-9, x) == TriContact::None, "sharing an edge");
    const double edge_down[9] = {0, 0, 0, 2, 0, 0, 1, 1, -1};  // a's edge, then under a
    CHECK(TriangleContact(a, edge_down, 1e-9, x) == TriContact::None, "sharing an edge, the other under");
    const double edge_on[9] = {0.2, 0.2, 0, 1.2, 0.2, 0, 0.7, 0.2, 1};  // its edge lying on a's face
    CHECK(TriangleContact(a, edge_on, 1e-9, x) == TriContact::None, "an edge lying on the face");
    const double apart[9] = {3, 3, 0, 4, 3, 0, 3, 4, 0};
    CHECK(TriangleContact(a, apart, 1e-9, x) == TriContact::None, "coplanar, disjoint");
    const double beside[9] = {2, 0, 0, 2, 2, 0, 0, 2, 0};  // the other half of the square
    CHECK(TriangleContact(a, beside, 1e-9, x) == TriContact::None, "coplanar, touching along the diagonal");
    const double over[9] = {0.5, 0.5, 0, 3, 0.5, 0, 0.5, 3, 0};
    CHECK(TriangleContact(a, over, 1e-9, x) == TriContact::Coplanar, "coplanar, overlapping");
    CHECK(std::fabs(x[2]) < 1e-12 && x[0] > 0.5 && x[1] > 0.5 && x[0] + x[1] < 2, "point in the overlap: %g %g",
          x[0], x[1]);
    const double same[9] = {0, 0, 0, 2, 0, 0, 0, 2, 0};
    CHECK(TriangleContact(a, same, 1e-9, x) == TriContact::Coplanar, "coplanar, the same triangle");
    const double graze[9] = {0.5, 0.5, 1e-12, 1.5, 0.2, 1, 0.2, 1.5, 1};  // a corner within tol of a's face
    CHECK(TriangleContact(a, graze, 1e-9, x) == TriContact::None, "within tol is touching");
    const double near[9] = {0.5, 0.5, -1e-3, 0.5, 0.5, 1, 1.5, -0.5, 0};  // just through
    CHECK(TriangleContact(a, near, 1e-9, x) == TriContact::Cross, "just through by 1e-3");
  }
  std::string err;
  {  // a strip folded through itself: two 1 x 4 strips, the second tilted through the first
    MeshData m;
    m.source = "fold.msh";
    Grid(&m, 4, Flat);
    const int nn = m.NumNodes();
    Grid(&m, 4, Flat);
    for (int i = nn; i < m.NumNodes(); ++i) {  // rotate the copy 90 degrees about the line y = 2, z = 0 and shift it (no node on the crossing line)
      const double y = m.coords[3 * i + 1], z = m.coords[3 * i + 2];
      m.coords[3 * i + 1] = 2.0 - z + 0.5;
      m.coords[3 * i + 2] = y - 2.3;
    }
    for (int e = 0; e < m.NumElements(); ++e) m.element_tags.push_back(100 + e);
    CHECK(!etfe::MeshCheckIntersections(m, &err), "fold refused");
    CHECK(Contains(err, "fold.msh: element") && Contains(err, "(tag 1") && Contains(err, "cross each other at") &&
              Contains(err, "-mesh_check_intersections false"),
          "message: %s", err.c_str());
  }
  {  // a wavy grid passes; with a huge tilted triangle over it too (cells grow, no blow-up), and
     // with that triangle lowered through the grid it is refused
    MeshData m;
    Grid(&m, 30, Wavy);
    CHECK(etfe::MeshCheckIntersections(m, &err), "wavy grid: %s", err.c_str());
    const int base = m.NumNodes();
    m.coords.insert(m.coords.end(), {-500, -500, 5, 1500, -500, 300, -500, 1500, 600});
    m.triangles.insert(m.triangles.end(), {base, base + 1, base + 2});
    CHECK(etfe::MeshCheckIntersections(m, &err), "wavy grid and a large triangle above: %s", err.c_str());
    for (int k = 0; k < 3; ++k) m.coords[3 * (size_t)(base + k) + 2] -= 234;  // its plane through the grid's middle
    CHECK(!etfe::MeshCheckIntersections(m, &err) && Contains(err, "and element 1800 cross"),
          "a large triangle through the grid: %s", err.c_str());
  }
  {  // two flat layers on each other: different groups pass, one group is refused
    MeshData m;
    Grid(&m, 6, Flat);
    const int ne = m.NumElements();
    Grid(&m, 6, Flat);
    Group(&m, "top", 0, ne);
    Group(&m, "bottom", ne, 2 * ne);
    CHECK(etfe::MeshCheckIntersections(m, &err), "flat layers in two groups: %s", err.c_str());
    m.element_sets.clear();
    Group(&m, "film", 0, 2 * ne);
    CHECK(!etfe::MeshCheckIntersections(m, &err) && Contains(err, "coplanar, in one group"), "one group: %s",
          err.c_str());
  }
  {  // a lens: two foils sharing the rim nodes, one lifted and one lowered
    MeshData m;
    const int n = 8;
    Grid(&m, n, Flat);
    const int ne = m.NumElements(), nn = m.NumNodes();
    for (int i = 0; i < nn; ++i) {
      const double u = m.coords[3 * i] / n, v = m.coords[3 * i + 1] / n;
      m.coords[3 * i + 2] = 0.5 * u * (1 - u) * v * (1 - v);
    }
    std::vector<int> map(nn);
    for (int i = 0; i < nn; ++i) {
      const double u = m.coords[3 * i] / n, v = m.coords[3 * i + 1] / n;
      const bool rim = u == 0 || u == 1 || v == 0 || v == 1;
      if (rim) {
        map[i] = i;
      } else {
        map[i] = m.NumNodes();
        m.coords.insert(m.coords.end(), {m.coords[3 * i], m.coords[3 * i + 1], -m.coords[3 * i + 2]});
      }
    }
    for (int e = 0; e < ne; ++e)
      for (int k : {0, 2, 1}) m.triangles.push_back(map[m.triangles[3 * e + k]]);
    CHECK(etfe::MeshCheckIntersections(m, &err), "lens: %s", err.c_str());
  }
  if (const char *t = std::getenv("ETFE_TIME_N")) {
    MeshData m;
    Grid(&m, std::atoi(t), Wavy);
    const auto t0 = std::chrono::steady_clock::now();
    const bool ok = etfe::MeshCheckIntersections(m, &err);
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::printf("%d triangles: %s in %.3f s\n", m.NumElements(), ok ? "passed" : err.c_str(), s);
  }
  TEST_MAIN_END();
}
