// Cutting lines into a triangle mesh: neighbours, edge splits along a traced polyline, the pieces
// between cut edges (see etfe/kernels/geodesic.h). Splitting only (no edge flips), so every new
// triangle lies in the plane of the input triangle it came from and the surface is unchanged.
#include <algorithm>
#include <cmath>
#include <map>

#include "etfe/kernels/geodesic.h"

namespace etfe {

namespace {

std::pair<int, int> Key(int a, int b) { return {std::min(a, b), std::max(a, b)}; }

std::string Where(const TriSurface &s, int n) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "(%.1f, %.1f, %.1f) mm", s.coords[3 * (size_t)n], s.coords[3 * (size_t)n + 1],
                s.coords[3 * (size_t)n + 2]);
  return buf;
}

// Splits edge (a, b) at a + t (b - a): each triangle on it becomes two, the new node joined to the
// opposite vertex, orientation kept. Returns the new node.
int SplitEdge(TriSurface *s, int a, int b, double t) {
  const int p = s->NumNodes();
  for (int i = 0; i < 3; ++i)
    s->coords.push_back(s->coords[3 * (size_t)a + i] + t * (s->coords[3 * (size_t)b + i] - s->coords[3 * (size_t)a + i]));
  s->new_node_edge.push_back({a, b});
  const int nt = s->NumTris();
  for (int e = 0; e < nt; ++e)
    for (int k = 0; k < 3; ++k) {
      const int x = s->tris[3 * e + k], y = s->tris[3 * e + (k + 1) % 3], z = s->tris[3 * e + (k + 2) % 3];
      if (!((x == a && y == b) || (x == b && y == a))) continue;
      s->tris[3 * e] = x, s->tris[3 * e + 1] = p, s->tris[3 * e + 2] = z;
      s->tris.insert(s->tris.end(), {p, y, z});
      s->parent.push_back(s->parent[e]);
      break;
    }
  // A split cut edge stays cut in both halves (only the line's own ends can lie on one).
  if (s->cut.erase(Key(a, b))) s->cut.insert(Key(a, p)), s->cut.insert(Key(p, b));
  return p;
}

} // namespace

bool SurfaceBuildNeighbours(TriSurface *s, std::string *err) {
  const int nt = s->NumTris();
  std::map<std::pair<int, int>, std::vector<int>> edge;  // key -> 3 * triangle + k
  for (int e = 0; e < nt; ++e)
    for (int k = 0; k < 3; ++k) edge[Key(s->tris[3 * e + k], s->tris[3 * e + (k + 1) % 3])].push_back(3 * e + k);
  s->nbr.assign(3 * (size_t)nt, -1);
  s->vtri.assign(s->NumNodes(), -1);
  for (int e = 0; e < nt; ++e)
    for (int k = 0; k < 3; ++k) s->vtri[s->tris[3 * e + k]] = e;
  for (const auto &kv : edge) {
    if (kv.second.size() > 2) {
      *err = "the edge between nodes " + std::to_string(kv.first.first) + " and " + std::to_string(kv.first.second) +
             " is in " + std::to_string(kv.second.size()) + " triangles: not a manifold surface";
      return false;
    }
    if (kv.second.size() < 2) continue;
    const int i = kv.second[0], j = kv.second[1];
    if (s->tris[i] == s->tris[j]) {
      *err = "triangles " + std::to_string(i / 3) + " and " + std::to_string(j / 3) + " are oriented differently";
      return false;
    }
    s->nbr[i] = j / 3, s->nbr[j] = i / 3;
  }
  return true;
}

bool SurfaceFromArrays(const std::vector<double> &coords, const std::vector<int> &tris, TriSurface *s,
                       std::string *err) {
  *s = TriSurface();
  s->coords = coords;
  s->tris = tris;
  s->parent.resize(s->NumTris());
  for (int e = 0; e < s->NumTris(); ++e) s->parent[e] = e;
  return SurfaceBuildNeighbours(s, err);
}

bool SurfaceInsertLine(TriSurface *s, const std::vector<SurfacePoint> &line, double snap, std::vector<int> *vertices,
                       double *moved, std::string *err) {
  if (moved) *moved = 0;
  std::vector<char> on_cut(s->NumNodes(), 0);
  for (const auto &c : s->cut) on_cut[c.first] = on_cut[c.second] = 1;
  // Splits made by this line: edge key -> (new node, t along the key's order), so that a point
  // on an edge split before is found on the right half.
  std::map<std::pair<int, int>, std::pair<int, double>> split;
  vertices->clear();
  for (const SurfacePoint &pt : line) {
    int v = pt.a;
    if (pt.b >= 0) {
      int a = pt.a, b = pt.b;  // a < b
      double t = pt.t;
      for (auto it = split.find(Key(a, b)); it != split.end(); it = split.find(Key(a, b))) {
        const int p = it->second.first;
        const double t0 = it->second.second;
        if (t < t0) b = p, t = t / t0;
        else a = p, t = (t - t0) / (1 - t0);
        if (a > b) std::swap(a, b), t = 1 - t;
      }
      if (t < snap) v = a;
      else if (t > 1 - snap) v = b;
      else {
        if (s->cut.count(Key(a, b))) {
          *err = "the line crosses another cutting line at " + Where(*s, a) + " - " + Where(*s, b);
          return false;
        }
        v = SplitEdge(s, a, b, t);
        on_cut.push_back(0);
        split[Key(a, b)] = {v, t};
      }
    }
    if (moved) {
      double d2 = 0;
      for (int i = 0; i < 3; ++i) d2 += std::pow(s->coords[3 * (size_t)v + i] - pt.x[i], 2);
      *moved = std::max(*moved, std::sqrt(d2));
    }
    if (on_cut[v]) {
      *err = "the line meets another cutting line at " + Where(*s, v);
      return false;
    }
    if (!vertices->empty() && vertices->back() == v) continue;
    if (std::find(vertices->begin(), vertices->end(), v) != vertices->end()) {
      *err = "the line comes back to itself at " + Where(*s, v);
      return false;
    }
    vertices->push_back(v);
  }
  std::set<std::pair<int, int>> edges;
  for (int e = 0; e < s->NumTris(); ++e)
    for (int k = 0; k < 3; ++k) edges.insert(Key(s->tris[3 * e + k], s->tris[3 * e + (k + 1) % 3]));
  for (size_t i = 1; i < vertices->size(); ++i) {
    const auto k = Key((*vertices)[i - 1], (*vertices)[i]);
    if (!edges.count(k)) {
      *err = "the line crosses one triangle twice near " + Where(*s, k.first) +
             " (a strongly curved or coarse surface): refine the mesh there";
      return false;
    }
  }
  for (size_t i = 1; i < vertices->size(); ++i) s->cut.insert(Key((*vertices)[i - 1], (*vertices)[i]));
  return SurfaceBuildNeighbours(s, err);
}

int SurfaceComponents(const TriSurface &s, std::vector<int> *label) {
  const int nt = s.NumTris();
  label->assign(nt, -1);
  int count = 0;
  for (int e0 = 0; e0 < nt; ++e0) {
    if ((*label)[e0] >= 0) continue;
    std::vector<int> stack{e0};
    (*label)[e0] = count;
    while (!stack.empty()) {
      const int e = stack.back();
      stack.pop_back();
      for (int k = 0; k < 3; ++k) {
        const int f = s.nbr[3 * e + k];
        if (f < 0 || (*label)[f] >= 0 || s.cut.count(Key(s.tris[3 * e + k], s.tris[3 * e + (k + 1) % 3]))) continue;
        (*label)[f] = count;
        stack.push_back(f);
      }
    }
    ++count;
  }
  return count;
}

double TriangleArea(const double *x0, const double *x1, const double *x2) {
  double a[3], b[3];
  for (int i = 0; i < 3; ++i) a[i] = x1[i] - x0[i], b[i] = x2[i] - x0[i];
  const double c[3] = {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
  return 0.5 * std::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
}

double TriangleQuality(const double *x0, const double *x1, const double *x2) {
  double l2 = 0;
  for (int i = 0; i < 3; ++i)
    l2 += (x1[i] - x0[i]) * (x1[i] - x0[i]) + (x2[i] - x1[i]) * (x2[i] - x1[i]) + (x0[i] - x2[i]) * (x0[i] - x2[i]);
  return l2 > 0 ? 4 * std::sqrt(3.0) * TriangleArea(x0, x1, x2) / l2 : 0.0;
}

} // namespace etfe
