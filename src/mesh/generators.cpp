// Structured meshes: rectangle (4 diagonal patterns, optional random perturbation), disc, annulus,
// tube and a strip wrapped on a cylinder.
#include "etfe/mesh/generators.h"

#include <cmath>
#include <cstdio>
#include <random>
#include <string>

namespace etfe {

namespace {
void AddNode(MeshData &m, double x, double y, double z) {
  m.coords.push_back(x);
  m.coords.push_back(y);
  m.coords.push_back(z);
}
void AddTriangle(MeshData &m, int a, int b, int c) {
  m.triangles.push_back(a);
  m.triangles.push_back(b);
  m.triangles.push_back(c);
}
void FillAllSet(MeshData &m) {
  std::vector<int> &all = m.node_sets["all"];
  all.resize(m.NumNodes());
  for (int i = 0; i < m.NumNodes(); ++i) all[i] = i;
  std::vector<int> &elems = m.element_sets["all"];
  elems.resize(m.NumElements());
  for (int e = 0; e < m.NumElements(); ++e) elems[e] = e;
}
} // namespace

MeshData MakeRectangleMesh(double x0, double y0, double lx, double ly, int nx, int ny,
                           DiagonalPattern pattern, double perturb, unsigned seed) {
  MeshData m;
  m.source = "rectangle " + std::to_string(nx) + "x" + std::to_string(ny);
  const double hx = lx / nx, hy = ly / ny;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  auto grid = [nx](int i, int j) { return j * (nx + 1) + i; };
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i) {
      double x = x0 + i * hx, y = y0 + j * hy;
      if (perturb > 0 && i > 0 && i < nx && j > 0 && j < ny) {
        x += perturb * hx * unit(rng);
        y += perturb * hy * unit(rng);
      }
      AddNode(m, x, y, 0.0);
    }
  const int ncorner = (nx + 1) * (ny + 1);
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const int a = grid(i, j), b = grid(i + 1, j), c = grid(i + 1, j + 1), d = grid(i, j + 1);
      bool right = pattern == DiagonalPattern::Right ||
                   (pattern == DiagonalPattern::Alternate && (i + j) % 2 == 0);
      if (pattern == DiagonalPattern::Crossed) {
        continue;  // needs the cell centres, added below
      } else if (right) {
        AddTriangle(m, a, b, c);
        AddTriangle(m, a, c, d);
      } else {
        AddTriangle(m, a, b, d);
        AddTriangle(m, b, c, d);
      }
    }
  if (pattern == DiagonalPattern::Crossed) {
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        const double *pa = &m.coords[3 * grid(i, j)], *pc = &m.coords[3 * grid(i + 1, j + 1)];
        const double *pb = &m.coords[3 * grid(i + 1, j)], *pd = &m.coords[3 * grid(i, j + 1)];
        AddNode(m, 0.25 * (pa[0] + pb[0] + pc[0] + pd[0]), 0.25 * (pa[1] + pb[1] + pc[1] + pd[1]),
                0.0);
      }
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        const int a = grid(i, j), b = grid(i + 1, j), c = grid(i + 1, j + 1), d = grid(i, j + 1);
        const int mid = ncorner + j * nx + i;
        AddTriangle(m, a, b, mid);
        AddTriangle(m, b, c, mid);
        AddTriangle(m, c, d, mid);
        AddTriangle(m, d, a, mid);
      }
  }
  for (int i = 0; i <= nx; ++i) {
    m.node_sets["bottom"].push_back(grid(i, 0));
    m.node_sets["top"].push_back(grid(i, ny));
  }
  for (int j = 0; j <= ny; ++j) {
    m.node_sets["left"].push_back(grid(0, j));
    m.node_sets["right"].push_back(grid(nx, j));
  }
  m.node_sets["corner_ll"] = {grid(0, 0)};
  m.node_sets["corner_lr"] = {grid(nx, 0)};
  m.node_sets["corner_ul"] = {grid(0, ny)};
  m.node_sets["corner_ur"] = {grid(nx, ny)};
  FillAllSet(m);
  return m;
}

MeshData MakeDiscMesh(double radius, int rings) {
  MeshData m;
  m.source = "disc with " + std::to_string(rings) + " rings";
  AddNode(m, 0, 0, 0);
  // ring i starts at node 1 + 3 i (i - 1) and holds 6 i nodes
  auto first = [](int i) { return i == 0 ? 0 : 1 + 3 * i * (i - 1); };
  for (int i = 1; i <= rings; ++i) {
    const double r = radius * i / rings;
    for (int k = 0; k < 6 * i; ++k) {
      const double phi = 2.0 * M_PI * k / (6.0 * i);
      AddNode(m, r * std::cos(phi), r * std::sin(phi), 0.0);
    }
  }
  auto node = [&](int i, int k) {
    if (i == 0) return 0;
    return first(i) + (k % (6 * i));
  };
  for (int i = 1; i <= rings; ++i)
    for (int s = 0; s < 6; ++s) {
      // sextant s: outer nodes s*i .. s*i+i, inner nodes s*(i-1) .. s*(i-1)+i-1
      for (int j = 0; j < i; ++j)
        AddTriangle(m, node(i, s * i + j), node(i, s * i + j + 1), node(i - 1, s * (i - 1) + j));
      for (int j = 0; j + 1 < i; ++j)
        AddTriangle(m, node(i - 1, s * (i - 1) + j), node(i, s * i + j + 1),
                    node(i - 1, s * (i - 1) + j + 1));
    }
  for (int k = 0; k < 6 * rings; ++k) m.node_sets["rim"].push_back(node(rings, k));
  m.node_sets["centre"] = {0};
  FillAllSet(m);
  return m;
}

MeshData MakeTubeMesh(double radius, double z0, double length, int ntheta, int nz) {
  MeshData m;
  m.source = "tube " + std::to_string(ntheta) + "x" + std::to_string(nz);
  auto id = [ntheta](int i, int j) { return j * ntheta + (i % ntheta); };
  for (int j = 0; j <= nz; ++j)
    for (int i = 0; i < ntheta; ++i) {
      const double phi = 2.0 * M_PI * i / ntheta;
      AddNode(m, radius * std::cos(phi), radius * std::sin(phi), z0 + length * j / nz);
    }
  // Counter-clockwise seen from outside, so the normals point away from the axis.
  for (int j = 0; j < nz; ++j)
    for (int i = 0; i < ntheta; ++i) {
      const int a = id(i, j), b = id(i + 1, j), c = id(i + 1, j + 1), d = id(i, j + 1);
      if ((i + j) % 2 == 0) {
        AddTriangle(m, a, b, c);
        AddTriangle(m, a, c, d);
      } else {
        AddTriangle(m, a, b, d);
        AddTriangle(m, b, c, d);
      }
    }
  for (int i = 0; i < ntheta; ++i) {
    m.node_sets["bottom"].push_back(id(i, 0));
    m.node_sets["top"].push_back(id(i, nz));
    if (nz % 2 == 0) m.node_sets["middle"].push_back(id(i, nz / 2));
  }
  FillAllSet(m);
  return m;
}

MeshData MakeAnnulusMesh(double a, double b, int nr, int nt) {
  MeshData m;
  const double pi = std::acos(-1.0);
  for (int i = 0; i <= nr; ++i)
    for (int j = 0; j < nt; ++j) {
      const double r = a + (b - a) * i / nr, th = 2 * pi * j / nt;
      m.coords.insert(m.coords.end(), {r * std::cos(th), r * std::sin(th), 0.0});
    }
  for (int i = 0; i < nr; ++i)
    for (int j = 0; j < nt; ++j) {
      const int n00 = i * nt + j, n01 = i * nt + (j + 1) % nt, n10 = n00 + nt, n11 = n01 + nt;
      if ((i + j) % 2 == 0) m.triangles.insert(m.triangles.end(), {n00, n10, n11, n00, n11, n01});
      else m.triangles.insert(m.triangles.end(), {n00, n10, n01, n01, n10, n11});
    }
  for (int j = 0; j < nt; ++j) {
    m.node_sets["hub"].push_back(j);
    m.node_sets["outer"].push_back(nr * nt + j);
  }
  for (int n = 0; n < m.NumNodes(); ++n) m.node_sets["all"].push_back(n);
  char src[96];
  std::snprintf(src, sizeof src, "generated annulus, %d rings x %d sectors", nr, nt);
  m.source = src;
  return m;
}

MeshData MakeWrappedStripMesh(double radius, double theta, double width, int nx, int ny) {
  // Laid flat first (arc length s along the wrap, y across), then onto the cylinder: stress free.
  MeshData m = MakeRectangleMesh(0.0, -0.5 * width, radius * theta, width, nx, ny, DiagonalPattern::Alternate, 0.0, 0u);
  m.source = "capstan strip " + std::to_string(nx) + "x" + std::to_string(ny);
  for (int n = 0; n < m.NumNodes(); ++n) {
    double *x = &m.coords[3 * n];
    const double phi = x[0] / radius - 0.5 * theta;
    x[0] = radius * std::sin(phi);
    x[2] = radius * std::cos(phi);
  }
  return m;
}

} // namespace etfe
