// MeshCheckIntersections (etfe/mesh/self_intersection.h): a surface that passes through itself
// (a fold, a layer pushed through another) is accepted by every other check and form finding
// even converges on it, so it is refused where the mesh is read.
#include "etfe/mesh/self_intersection.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <vector>

#include "etfe/kernels/tri_intersect.h"

namespace etfe {
namespace {

bool g_check = true;

std::string Name(const MeshData &mesh, size_t e) {
  std::string s = "element " + std::to_string(e);
  if (e < mesh.element_tags.size()) s += " (tag " + std::to_string(mesh.element_tags[e]) + " in the file)";
  return s;
}

// The element groups of each triangle (indices into mesh.element_sets), for the coplanar rule.
std::vector<std::vector<int>> GroupsOfTriangles(const MeshData &mesh) {
  std::vector<std::vector<int>> g((size_t)mesh.NumElements());
  int k = 0;
  for (const auto &kv : mesh.element_sets) {
    for (int e : kv.second)
      if (e >= 0 && e < mesh.NumElements()) g[(size_t)e].push_back(k);
    ++k;
  }
  return g;
}

bool ShareGroup(const std::vector<int> &a, const std::vector<int> &b) {
  if (a.empty() && b.empty()) return true;  // both in no group: one surface as far as we know
  for (int x : a)
    if (std::find(b.begin(), b.end(), x) != b.end()) return true;
  return false;
}

} // namespace

void SetMeshIntersectionCheck(bool on) { g_check = on; }
bool MeshIntersectionCheck() { return g_check; }

bool MeshCheckIntersections(const MeshData &mesh, std::string *err) {
  const size_t ne = mesh.triangles.size() / 3, nn = mesh.coords.size() / 3;
  if (ne < 2 || mesh.coords.size() % 3 != 0) return true;
  for (int v : mesh.triangles)
    if (v < 0 || (size_t)v >= nn) return true;
  for (double c : mesh.coords)
    if (!std::isfinite(c)) return true;
  // Bounding boxes and their mean size: the cell of the grid and the length tolerance.
  std::vector<double> box(6 * ne);
  double mean = 0, edges = 0;
  for (size_t e = 0; e < ne; ++e) {
    const int *t = &mesh.triangles[3 * e];
    double *b = &box[6 * e];
    for (int k = 0; k < 3; ++k) {
      b[k] = b[3 + k] = mesh.coords[3 * (size_t)t[0] + k];
      for (int i = 1; i < 3; ++i) {
        b[k] = std::min(b[k], mesh.coords[3 * (size_t)t[i] + k]);
        b[3 + k] = std::max(b[3 + k], mesh.coords[3 * (size_t)t[i] + k]);
      }
      mean += b[3 + k] - b[k];
    }
    for (int i = 0; i < 3; ++i) {
      const double *p = &mesh.coords[3 * (size_t)t[i]], *q = &mesh.coords[3 * (size_t)t[(i + 1) % 3]];
      edges += std::sqrt((p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) + (p[2] - q[2]) * (p[2] - q[2]));
    }
  }
  mean /= 3.0 * (double)ne;
  const double tol = 1e-6 * edges / (3.0 * (double)ne);
  if (!(mean > 0)) return true;
  double lo[3] = {box[0], box[1], box[2]};
  for (size_t e = 0; e < ne; ++e)
    for (int k = 0; k < 3; ++k) lo[k] = std::min(lo[k], box[6 * e + k]);
  // Cells of twice the mean box size; a triangle goes into every cell its box (grown by tol)
  // touches. Keys pack three 21-bit cell indices; a model wider than 2^21 cells (a mesh with
  // triangles some 10^6 times smaller than it) uses larger cells.
  double cell = 2.0 * mean;
  double extent = 0;
  for (size_t e = 0; e < ne; ++e)
    for (int k = 0; k < 3; ++k) extent = std::max(extent, box[6 * e + 3 + k] - lo[k]);
  cell = std::max(cell, extent / 1.0e6);
  auto index = [&](double x, int k) { return (uint64_t)std::max(0.0, std::floor((x - lo[k]) / cell)); };
  // A few triangles much larger than the mean (a graded mesh) would fill many cells each: the
  // cells grow until the entries stay within 16 per triangle.
  for (;;) {
    double entries = 0;
    for (size_t e = 0; e < ne; ++e) {
      double n = 1;
      for (int k = 0; k < 3; ++k)
        n *= (double)(index(box[6 * e + 3 + k] + tol, k) - index(box[6 * e + k] - tol, k) + 1);
      entries += n;
    }
    if (entries <= 16.0 * (double)ne + 1e6) break;
    cell *= 2;
  }
  std::vector<std::pair<uint64_t, int>> keyed;
  keyed.reserve(2 * ne);
  for (size_t e = 0; e < ne; ++e) {
    const double *b = &box[6 * e];
    uint64_t i0[3], i1[3];
    for (int k = 0; k < 3; ++k) {
      i0[k] = index(b[k] - tol, k);
      i1[k] = index(b[3 + k] + tol, k);
    }
    for (uint64_t x = i0[0]; x <= i1[0]; ++x)
      for (uint64_t y = i0[1]; y <= i1[1]; ++y)
        for (uint64_t z = i0[2]; z <= i1[2]; ++z) keyed.push_back({(x << 42) | (y << 21) | z, (int)e});
  }
  std::sort(keyed.begin(), keyed.end());
  const std::vector<std::vector<int>> groups = GroupsOfTriangles(mesh);
  for (size_t i = 0; i < keyed.size();) {
    size_t j = i + 1;
    while (j < keyed.size() && keyed[j].first == keyed[i].first) ++j;
    for (size_t p = i; p < j; ++p) {
      const int ea = keyed[p].second;
      const double *ba = &box[6 * (size_t)ea];
      const int *ta = &mesh.triangles[3 * (size_t)ea];
      for (size_t q = p + 1; q < j; ++q) {
        const int eb = keyed[q].second;
        const double *bb = &box[6 * (size_t)eb];
        bool apart = false;
        for (int k = 0; k < 3; ++k) apart = apart || ba[k] > bb[3 + k] + tol || bb[k] > ba[3 + k] + tol;
        if (apart) continue;
        // A pair whose boxes share several cells is tested once: in the first cell of both.
        uint64_t key = 0;
        for (int k = 0; k < 3; ++k) key = (key << 21) | std::max(index(ba[k] - tol, k), index(bb[k] - tol, k));
        if (key != keyed[i].first) continue;
        const int *tb = &mesh.triangles[3 * (size_t)eb];
        bool shared = false;
        for (int r = 0; r < 3; ++r)
          for (int s = 0; s < 3; ++s) shared = shared || ta[r] == tb[s];
        if (shared) continue;
        double a[9], b[9], x[3];
        for (int r = 0; r < 3; ++r)
          for (int k = 0; k < 3; ++k) {
            a[3 * r + k] = mesh.coords[3 * (size_t)ta[r] + k];
            b[3 * r + k] = mesh.coords[3 * (size_t)tb[r] + k];
          }
        const TriContact c = TriangleContact(a, b, tol, x);
        if (c == TriContact::None) continue;
        if (c == TriContact::Coplanar && !ShareGroup(groups[(size_t)ea], groups[(size_t)eb])) continue;
        const int e1 = std::min(ea, eb), e2 = std::max(ea, eb);
        char at[96];
        std::snprintf(at, sizeof at, "(%.6g, %.6g, %.6g) mm", x[0], x[1], x[2]);
        *err = (mesh.source.empty() ? std::string("mesh") : mesh.source) + ": " + Name(mesh, (size_t)e1) + " and " +
               Name(mesh, (size_t)e2) +
               (c == TriContact::Cross ? " cross each other at " : " lie on each other (coplanar, in one group) at ") +
               at +
               ": the surface passes through itself (a fold, or a layer through another), which no film can; "
               "remesh it so that no two triangles cross (layers that are meant to lie flat on each other go in "
               "different physical surface groups), or give -mesh_check_intersections false to skip this check";
        return false;
      }
    }
    i = j;
  }
  return true;
}

} // namespace etfe
