// MeshCheck: the checks every mesh passes before the solver distributes it, whether it came from
// a file or a generator. Each message names the mesh, the offending element or node and what to
// change, because the person reading it is looking at a mesh generator, not at this code.
#include <climits>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "etfe/mesh/mesh_data.h"

namespace etfe {
namespace {

bool Fail(const MeshData &mesh, std::string *err, const std::string &msg) {
  if (err) *err = (mesh.source.empty() ? std::string("mesh") : mesh.source) + ": " + msg;
  return false;
}

std::string Num(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.6g", v);
  return b;
}

std::string Id(size_t v) { return std::to_string(v); }

std::string Nodes(const int *t) {
  return "nodes " + std::to_string(t[0]) + " " + std::to_string(t[1]) + " " + std::to_string(t[2]);
}

// Sets index into the mesh; a stale or unsorted set would silently pick the wrong nodes later.
bool CheckSets(const MeshData &mesh, const std::map<std::string, std::vector<int>> &sets,
               const char *kind, size_t n, std::string *err) {
  for (const auto &s : sets) {
    for (size_t i = 0; i < s.second.size(); ++i) {
      const int v = s.second[i];
      if (v < 0 || (size_t)v >= n) {
        return Fail(mesh, err, std::string(kind) + " set '" + s.first + "' holds " + kind + " " +
                                   std::to_string(v) + ", but the mesh has " + Id(n) + " " +
                                   kind + "s (ids 0.." + std::to_string((long long)n - 1) +
                                   "): rebuild the set after changing the mesh");
      }
      if (i > 0 && v <= s.second[i - 1]) {
        return Fail(mesh, err, std::string(kind) + " set '" + s.first +
                                   "' is not sorted and unique (at position " + Id(i) +
                                   "): sort it and remove duplicates");
      }
    }
  }
  return true;
}

} // namespace

bool MeshCheck(const MeshData &mesh, double min_area, std::string *err) {
  if (mesh.coords.size() % 3 != 0) {
    return Fail(mesh, err, "coords has " + Id(mesh.coords.size()) +
                               " values, not 3 per node: the mesh was built incorrectly");
  }
  if (mesh.triangles.size() % 3 != 0) {
    return Fail(mesh, err, "triangles has " + Id(mesh.triangles.size()) +
                               " values, not 3 per element: the mesh was built incorrectly");
  }
  const size_t nn = mesh.coords.size() / 3, ne = mesh.triangles.size() / 3;
  if (nn > (size_t)INT_MAX || ne > (size_t)INT_MAX) {
    return Fail(mesh, err, "too many nodes or elements for int ids");
  }
  for (size_t i = 0; i < nn; ++i) {
    const double *x = &mesh.coords[3 * i];
    if (!std::isfinite(x[0]) || !std::isfinite(x[1]) || !std::isfinite(x[2])) {
      return Fail(mesh, err, "node " + Id(i) + " has a non-finite coordinate (" + Num(x[0]) +
                                 ", " + Num(x[1]) + ", " + Num(x[2]) +
                                 "): fix the mesh file or the generator input");
    }
  }
  if (ne == 0) return Fail(mesh, err, "the mesh has no triangles");

  std::vector<char> used(nn, 0);
  size_t small = 0, first_small = 0;
  double first_area = 0;
  for (size_t e = 0; e < ne; ++e) {
    const int *t = &mesh.triangles[3 * e];
    for (int k = 0; k < 3; ++k) {
      if (t[k] < 0 || (size_t)t[k] >= nn) {
        return Fail(mesh, err, "element " + Id(e) + " (" + Nodes(t) + ") refers to node " +
                                   std::to_string(t[k]) + ", but the mesh has " + Id(nn) +
                                   " nodes (ids 0.." + std::to_string((long long)nn - 1) + ")");
      }
      used[(size_t)t[k]] = 1;
    }
    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) {
      return Fail(mesh, err, "element " + Id(e) + " (" + Nodes(t) +
                                 ") repeats a node, so it has no area: remove or merge it in the "
                                 "mesh generator");
    }
    const double *a = &mesh.coords[3 * (size_t)t[0]];
    const double *b = &mesh.coords[3 * (size_t)t[1]];
    const double *c = &mesh.coords[3 * (size_t)t[2]];
    const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    const double v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    const double n[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2],
                         u[0] * v[1] - u[1] * v[0]};
    const double area = 0.5 * std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    if (!(area >= min_area)) {  // also catches a NaN from overflowing coordinates
      if (small++ == 0) {
        first_small = e;
        first_area = area;
      }
    }
  }
  if (small > 0) {
    const int *t = &mesh.triangles[3 * first_small];
    std::string more = small > 1 ? " (and " + Id(small - 1) + " more such elements)" : "";
    return Fail(mesh, err, "element " + Id(first_small) + " (" + Nodes(t) + ") has area " +
                               Num(first_area) + " mm^2, below the minimum " + Num(min_area) +
                               " mm^2" + more +
                               ": remove or merge it in the mesh generator, or lower "
                               "-mesh_min_area");
  }
  size_t unused = 0, first_unused = 0;
  for (size_t i = 0; i < nn; ++i) {
    if (!used[i] && unused++ == 0) first_unused = i;
  }
  if (unused > 0) {
    std::string more = unused > 1 ? " (and " + Id(unused - 1) + " more)" : "";
    return Fail(mesh, err, "node " + Id(first_unused) + more +
                               " is not used by any triangle: remove it from the mesh (a free "
                               "node has no stiffness and makes the system singular)");
  }
  if (!CheckSets(mesh, mesh.node_sets, "node", nn, err)) return false;
  return CheckSets(mesh, mesh.element_sets, "element", ne, err);
}

} // namespace etfe
