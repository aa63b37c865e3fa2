// MeshCheck: the checks every mesh passes before the solver distributes it, whether it came from
// a file or a generator. Each message names the mesh, the offending element or node and what to
// change, because the person reading it is looking at a mesh generator, not at this code.
#include <algorithm>
#include <array>
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

// Ids count from 0 in file order; a mesh read from a file also names the tags the file uses.
std::string NodeName(const MeshData &mesh, size_t i) {
  std::string s = "node " + Id(i);
  if (i < mesh.node_tags.size())
    s += " (tag " + std::to_string(mesh.node_tags[i]) + " in the file)";
  return s;
}

std::string ElementName(const MeshData &mesh, size_t e) {
  std::string s = "element " + Id(e);
  if (e < mesh.element_tags.size()) {
    s += " (tag " + std::to_string(mesh.element_tags[e]) + " in the file)";
  }
  return s;
}

std::string Nodes(const int *t) {
  return "nodes " + std::to_string(t[0]) + " " + std::to_string(t[1]) + " " + std::to_string(t[2]);
}

// One directed edge of a triangle, keyed by its sorted end nodes; forward when the triangle
// runs from a to b. A manifold edge has two entries, and they run opposite ways when the two
// triangles are oriented alike.
struct Edge {
  int a, b, element;
  bool forward;
  bool operator<(const Edge &o) const {
    return a != o.a ? a < o.a : b != o.b ? b < o.b : element < o.element;
  }
};

std::vector<Edge> SortedEdges(const MeshData &mesh) {
  std::vector<Edge> edges;
  edges.reserve(mesh.triangles.size());
  for (size_t e = 0; e < mesh.triangles.size() / 3; ++e) {
    const int *t = &mesh.triangles[3 * e];
    for (int k = 0; k < 3; ++k) {
      const int p = t[k], q = t[(k + 1) % 3];
      edges.push_back({std::min(p, q), std::max(p, q), (int)e, p < q});
    }
  }
  std::sort(edges.begin(), edges.end());
  return edges;
}

// Ids in range and no repeated node: what the topology passes need to be meaningful.
bool IdsValid(const MeshData &mesh) {
  if (mesh.coords.size() % 3 != 0 || mesh.triangles.size() % 3 != 0) return false;
  const long long nn = (long long)(mesh.coords.size() / 3);
  for (size_t e = 0; e < mesh.triangles.size(); e += 3) {
    const int *t = &mesh.triangles[e];
    for (int k = 0; k < 3; ++k) {
      if (t[k] < 0 || t[k] >= nn) return false;
    }
    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) return false;
  }
  return true;
}

// First pair of triangles on the same three nodes, as (lower, higher) element ids; -1 if none.
std::pair<int, int> DuplicateTriangle(const MeshData &mesh) {
  std::vector<std::array<int, 4>> keys;
  for (size_t e = 0; e < mesh.triangles.size() / 3; ++e) {
    std::array<int, 4> k = {mesh.triangles[3 * e], mesh.triangles[3 * e + 1],
                            mesh.triangles[3 * e + 2], (int)e};
    std::sort(k.begin(), k.begin() + 3);
    keys.push_back(k);
  }
  std::sort(keys.begin(), keys.end());
  for (size_t i = 1; i < keys.size(); ++i) {
    if (std::equal(keys[i].begin(), keys[i].begin() + 3, keys[i - 1].begin())) {
      return {keys[i - 1][3], keys[i][3]};
    }
  }
  return {-1, -1};
}

bool CheckTopology(const MeshData &mesh, std::string *err) {
  const std::pair<int, int> dup = DuplicateTriangle(mesh);
  if (dup.first >= 0) {
    return Fail(mesh, err, ElementName(mesh, (size_t)dup.second) + " and " +
                               ElementName(mesh, (size_t)dup.first) + " are the same triangle (" +
                               Nodes(&mesh.triangles[3 * (size_t)dup.first]) +
                               "): remove the duplicate in the mesh generator (a surface "
                               "meshed twice, or two physical surfaces on one entity)");
  }
  const std::vector<Edge> edges = SortedEdges(mesh);
  for (size_t i = 0; i < edges.size();) {
    size_t j = i + 1;
    while (j < edges.size() && edges[j].a == edges[i].a && edges[j].b == edges[i].b) ++j;
    if (j - i > 2 && mesh.welds) {  // layers welded along this edge: each layer is checked alone
      i = j;
      continue;
    }
    if (j - i > 2) {
      std::string who;
      for (size_t k = i; k < j && k < i + 4; ++k) {
        who += (k > i ? ", " : "") + ElementName(mesh, (size_t)edges[k].element);
      }
      return Fail(mesh, err,
                  "the edge between " + NodeName(mesh, (size_t)edges[i].a) + " and " +
                      NodeName(mesh, (size_t)edges[i].b) + " belongs to three or more triangles (" +
                      Id(j - i) + ": " + who +
                      "), so the surface is not a membrane (non-manifold): a membrane "
                      "edge has one or two triangles; split the mesh or remove the "
                      "extra surface (layers welded along it, as a three-layer cushion's rim: "
                      "-mesh_welds)");
    }
    if (j - i == 2 && edges[i].forward == edges[i + 1].forward) {
      return Fail(mesh, err,
                  ElementName(mesh, (size_t)edges[i].element) + " and " +
                      ElementName(mesh, (size_t)edges[i + 1].element) +
                      " run the same way along their common edge (" +
                      NodeName(mesh, (size_t)edges[i].a) + ", " +
                      NodeName(mesh, (size_t)edges[i].b) +
                      "): the surface has no consistent orientation; reorient the "
                      "triangles in the mesh generator (Gmsh: Mesh.ReverseOrientation or "
                      "reorient the surface)");
    }
    i = j;
  }
  return true;
}

// Coincident nodes that triangles use separately leave a crack: the two sides are not joined.
// Nodes are binned on a grid of the tolerance, and each node is compared with the 27 cells
// around it, so the pass is n log n whatever the mesh's shape.
bool CheckCoincidentNodes(const MeshData &mesh, std::string *err) {
  const size_t nn = mesh.coords.size() / 3, ne = mesh.triangles.size() / 3;
  double sum = 0;
  for (size_t e = 0; e < ne; ++e) {
    for (int k = 0; k < 3; ++k) {
      const double *p = &mesh.coords[3 * (size_t)mesh.triangles[3 * e + k]];
      const double *q = &mesh.coords[3 * (size_t)mesh.triangles[3 * e + (k + 1) % 3]];
      sum += std::sqrt((p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) +
                       (p[2] - q[2]) * (p[2] - q[2]));
    }
  }
  const double mean_edge = sum / (3.0 * (double)ne);
  const double tol = 1e-6 * mean_edge;
  if (!(tol > 0) || !std::isfinite(tol)) return true;  // a zero-size mesh fails the area check
  double lo[3] = {mesh.coords[0], mesh.coords[1], mesh.coords[2]};
  for (size_t i = 0; i < nn; ++i) {
    for (int c = 0; c < 3; ++c) lo[c] = std::min(lo[c], mesh.coords[3 * i + c]);
  }
  using Cell = std::array<long long, 3>;
  std::vector<std::pair<Cell, int>> cells(nn);
  for (size_t i = 0; i < nn; ++i) {
    for (int c = 0; c < 3; ++c) {
      const double x = std::floor((mesh.coords[3 * i + c] - lo[c]) / tol);
      cells[i].first[c] = x < 4e18 ? (long long)x : (long long)4e18;
    }
    cells[i].second = (int)i;
  }
  std::sort(cells.begin(), cells.end());
  for (size_t i = 0; i < nn; ++i) {
    const Cell &ci = cells[i].first;
    for (int d = 0; d < 27; ++d) {
      const Cell cj = {ci[0] + d % 3 - 1, ci[1] + d / 3 % 3 - 1, ci[2] + d / 9 - 1};
      auto it = std::lower_bound(cells.begin(), cells.end(), std::make_pair(cj, -1));
      for (; it != cells.end() && it->first == cj; ++it) {
        const int a = cells[i].second, b = it->second;
        if (b <= a) continue;
        const double *p = &mesh.coords[3 * (size_t)a], *q = &mesh.coords[3 * (size_t)b];
        const double dist =
            std::sqrt((p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) +
                      (p[2] - q[2]) * (p[2] - q[2]));
        if (dist <= tol) {
          return Fail(mesh, err,
                      NodeName(mesh, (size_t)a) + " and " + NodeName(mesh, (size_t)b) +
                          " coincide (at " + Num(p[0]) + ", " + Num(p[1]) + ", " + Num(p[2]) +
                          "; " + Num(dist) +
                          " mm apart, within 1e-6 "
                          "of the mean edge length " +
                          Num(mean_edge) +
                          " mm): the mesh has a crack there; merge duplicate nodes in the "
                          "mesh generator (Gmsh: Geometry.Tolerance, or Coherence Mesh). If two foils lie on each "
                          "other (a cushion's flat layers), start them apart (scripts/cushion-mesh --lens)");
        }
      }
    }
  }
  return true;
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

// " (all in group bottom)" / " (in groups a, b)": the element groups of the piece's triangles
// whose flip mark is `which`, so a message points to the surface of the file that is the wrong way.
std::string GroupsOf(const MeshData &mesh, const std::vector<int> &piece, const std::vector<int> &flip, int which) {
  std::vector<int> sel;
  for (int e : piece)
    if (flip[(size_t)e] == which) sel.push_back(e);
  std::sort(sel.begin(), sel.end());
  std::string names;
  bool all = true;
  size_t in_any = 0;
  for (const auto &kv : mesh.element_sets) {
    size_t hit = 0;
    for (int e : sel) hit += std::binary_search(kv.second.begin(), kv.second.end(), e) ? 1 : 0;
    if (hit == 0) continue;
    in_any += hit;
    all = all && hit == kv.second.size();
    names += (names.empty() ? "" : ", ") + kv.first;
  }
  if (names.empty()) return "";
  return std::string(" (those ") + (all && in_any == sel.size() ? "are all of group " : "lie in group ") + names + ")";
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
  if (!CheckTopology(mesh, err) || !CheckCoincidentNodes(mesh, err)) return false;
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

bool MeshOrient(MeshData *mesh, std::string *err) {
  if (!IdsValid(*mesh) || DuplicateTriangle(*mesh).first >= 0) return true;
  const std::vector<Edge> edges = SortedEdges(*mesh);
  const size_t ne = mesh->triangles.size() / 3;
  // Neighbours across manifold edges, with whether they must be flipped relative to each other.
  std::vector<std::vector<std::pair<int, bool>>> nbr(ne);
  for (size_t i = 0; i < edges.size();) {
    size_t j = i + 1;
    while (j < edges.size() && edges[j].a == edges[i].a && edges[j].b == edges[i].b) ++j;
    if (j - i > 2) return true;  // non-manifold: MeshCheck says so
    if (j - i == 2) {
      const bool differ = edges[i].forward == edges[i + 1].forward;
      nbr[(size_t)edges[i].element].push_back({edges[i + 1].element, differ});
      nbr[(size_t)edges[i + 1].element].push_back({edges[i].element, differ});
    }
    i = j;
  }
  std::vector<int> flip(ne, -1);
  std::vector<int> piece, stack;
  size_t flipped = 0, pieces = 0;
  std::vector<std::string> notes;  // per piece with flips: how many and of which groups
  for (size_t seed = 0; seed < ne; ++seed) {
    if (flip[seed] >= 0) continue;
    ++pieces;
    piece.clear();
    flip[seed] = 0;
    stack.assign(1, (int)seed);
    while (!stack.empty()) {
      const int e = stack.back();
      stack.pop_back();
      piece.push_back(e);
      for (const auto &n : nbr[(size_t)e]) {
        const int want = flip[(size_t)e] ^ (n.second ? 1 : 0);
        if (flip[(size_t)n.first] < 0) {
          flip[(size_t)n.first] = want;
          stack.push_back(n.first);
        } else if (flip[(size_t)n.first] != want) {
          return Fail(*mesh, err, "the surface through " + ElementName(*mesh, seed) + " and " +
                                      ElementName(*mesh, (size_t)n.first) +
                                      " cannot be oriented (like a Moebius strip): a membrane "
                                      "needs a two-sided surface; cut it or remesh it");
        }
      }
    }
    size_t against = 0;
    for (int e : piece) against += (size_t)flip[(size_t)e];
    if (against == 0) continue;
    if (2 * against == piece.size()) {
      // An even split gives no majority, and the first triangle's way is no better a guess: a
      // cushion whose two foils both face up splits exactly so, and keeping either foil's way
      // turns the other inside out. Only the user knows which normals are meant.
      return Fail(*mesh, err, "the connected surface through " + ElementName(*mesh, seed) + " has " +
                                  Id(piece.size() - against) + " triangles oriented like that one" +
                                  GroupsOf(*mesh, piece, flip, 0) + " and " + Id(against) + " the other way" +
                                  GroupsOf(*mesh, piece, flip, 1) +
                                  ": the orientations split evenly, so which way the normals should point "
                                  "cannot be told; orient the surface consistently in the mesh generator (Gmsh: "
                                  "Reverse Surface on the surfaces whose normals point the wrong way; a cushion's "
                                  "top and bottom normals point out of the cushion)");
    }
    const int minority = 2 * against > piece.size() ? 0 : 1;
    const size_t nflip = minority ? against : piece.size() - against;
    notes.push_back(Id(nflip) + " of " + Id(piece.size()) + " in the piece through " + ElementName(*mesh, seed) +
                    GroupsOf(*mesh, piece, flip, minority));
    for (int e : piece) {
      if (flip[(size_t)e] != minority) continue;
      std::swap(mesh->triangles[3 * (size_t)e + 1], mesh->triangles[3 * (size_t)e + 2]);
      ++flipped;
    }
  }
  if (flipped > 0) {
    std::string which;
    for (size_t k = 0; k < notes.size() && k < 3; ++k) which += (k ? "; " : "") + notes[k];
    if (notes.size() > 3) which += "; and " + Id(notes.size() - 3) + " more pieces";
    mesh->notes.push_back("flipped " + Id(flipped) + " of " + Id(ne) +
                          " triangles to the orientation of the majority of their connected piece (" +
                          Id(pieces) + (pieces > 1 ? " pieces" : " piece") + "): " + which +
                          "; if the flipped ones were the right way, reverse the others in the mesh generator");
  }
  return true;
}

} // namespace etfe
