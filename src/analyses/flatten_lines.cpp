// Results of a flattened strip: outline loops, the polylines of named node sets, and the final
// placement and report (see flatten.cpp).

#include <algorithm>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <map>
#include <queue>
#include <string>
#include <utility>
#include <vector>

#include "etfe/kernels/flatten_link.h"
#include "etfe/kernels/status.h"
#include "flatten_internal.h"

namespace etfe {
namespace flatten {

// Boundary loops with the interior on their left, the outer (largest) loop first.
void OutlineLoops(const Topology &t, const std::vector<double> &x, int nn,
                  std::vector<std::vector<int>> *loops) {
  std::vector<std::vector<std::pair<int, int>>> out_edges(nn);  // (to, link)
  for (int i = 0; i < t.NumLinks(); ++i) {
    if (!t.Boundary(i)) continue;
    int a = t.links[2 * i], b = t.links[2 * i + 1];
    if (Cross2(&x[2 * (size_t)a], &x[2 * (size_t)b], &x[2 * (size_t)t.opp[2 * i]]) < 0)
      std::swap(a, b);
    out_edges[a].push_back({b, i});
  }
  std::vector<char> used(t.NumLinks(), 0);
  std::vector<std::pair<double, std::vector<int>>> found;
  for (int s = 0; s < nn; ++s)
    for (const auto &e0 : out_edges[s]) {
      if (used[e0.second]) continue;
      std::vector<int> loop{s};
      used[e0.second] = 1;
      int cur = e0.first;
      while (cur != s) {
        loop.push_back(cur);
        int next = -1;
        for (const auto &e : out_edges[cur])
          if (!used[e.second]) {
            used[e.second] = 1;
            next = e.first;
            break;
          }
        if (next < 0) break;  // cannot happen on a manifold mesh: every boundary node closes
        cur = next;
      }
      double area = 0.0;
      for (size_t k = 0; k < loop.size(); ++k) {
        const double *p = &x[2 * (size_t)loop[k]], *q = &x[2 * (size_t)loop[(k + 1) % loop.size()]];
        area += 0.5 * (p[0] * q[1] - p[1] * q[0]);
      }
      found.push_back({area, loop});
    }
  std::stable_sort(found.begin(), found.end(), [](const auto &a, const auto &b) {
    return std::fabs(a.first) > std::fabs(b.first);
  });
  loops->clear();
  for (auto &f : found) loops->push_back(std::move(f.second));
}

// The polyline of a node set (see PatternLine); false with a message when the set's edges do
// not form simple lines.
bool MeasureLine(const MeshData &m, const Topology &t, const std::vector<double> &x,
                 const std::string &name, const std::vector<int> &set, PatternLine *line,
                 std::string *err) {
  const int nn = m.NumNodes();
  std::vector<char> in(nn, 0);
  for (int v : set) in[v] = 1;
  std::vector<int> edges;
  for (int pass = 0; pass < 2 && edges.empty(); ++pass)
    for (int i = 0; i < t.NumLinks(); ++i)
      if (in[t.links[2 * i]] && in[t.links[2 * i + 1]] && (pass == 1 || t.Boundary(i)))
        edges.push_back(i);
  line->name = name;
  line->on_boundary = !edges.empty() && t.Boundary(edges[0]);
  if (edges.empty()) {
    return Fail(m, err, "node set '" + name + "' has no two nodes joined by a mesh edge, so it "
                        "is not a line: list the nodes of a boundary or cutting line");
  }
  std::vector<std::vector<std::pair<int, int>>> adj(nn);
  for (int i : edges) {
    adj[t.links[2 * i]].push_back({t.links[2 * i + 1], i});
    adj[t.links[2 * i + 1]].push_back({t.links[2 * i], i});
  }
  for (int v = 0; v < nn; ++v)
    if (adj[v].size() > 2) {
      return Fail(m, err, Format("node set '%s': node %d joins %d of the set's %s edges, so the "
                                 "set is not a simple line; split it into separate lines",
                                 name.c_str(), v, (int)adj[v].size(),
                                 line->on_boundary ? "boundary" : "mesh"));
    }
  std::vector<char> used(t.NumLinks(), 0);
  // Open pieces start at their end points (one edge), then the closed pieces.
  for (int pass = 0; pass < 2; ++pass)
    for (int s = 0; s < nn; ++s) {
      if (adj[s].empty() || (pass == 0 && adj[s].size() != 1)) continue;
      if (used[adj[s][0].second] && (adj[s].size() == 1 || used[adj[s][1].second])) continue;
      std::vector<int> path{s};
      int cur = s;
      for (;;) {
        int next = -1;
        for (const auto &e : adj[cur])
          if (!used[e.second]) {
            used[e.second] = 1;
            next = e.first;
            ++line->segments;
            line->length3d += Dist3(&m.coords[3 * (size_t)cur], &m.coords[3 * (size_t)e.first]);
            line->length2d += std::hypot(x[2 * (size_t)e.first] - x[2 * (size_t)cur],
                                         x[2 * (size_t)e.first + 1] - x[2 * (size_t)cur + 1]);
            break;
          }
        if (next < 0) break;
        path.push_back(next);
        cur = next;
        if (cur == s) break;
      }
      line->paths.push_back(std::move(path));
    }
  line->expansion_pct = (line->length2d - line->length3d) / line->length3d * 100.0;
  return true;
}

// Final mirror, rotation and translation; link errors; outline; lines.
bool Report(const MeshData &m, const Topology &t, const FlattenOptions &opt, const Problem &p,
            std::vector<double> x, FlattenResult *out, std::string *err) {
  const int nn = m.NumNodes();
  // S is invariant under reflection, so the solution may be the mirror image of the strip seen
  // from triangle 0's normal side; a fabricator needs the film's face, so undo that.
  const int *v0 = &m.triangles[0];
  if (Cross2(&x[2 * (size_t)v0[0]], &x[2 * (size_t)v0[1]], &x[2 * (size_t)v0[2]]) < 0)
    for (int i = 0; i < nn; ++i) x[2 * (size_t)i] = -x[2 * (size_t)i];
  AlignPrincipal(&x);
  out->xy = x;
  const int nl = t.NumLinks();
  out->links = t.links;
  out->link_on_boundary.assign(nl, 0);
  out->link_length3d = p.L;
  out->link_error.assign(nl, 0.0);
  double sum2 = 0.0, sum2i = 0.0;
  int ni = 0;
  out->num_boundary_links = 0;
  out->max_rel_error = out->max_rel_error_boundary = out->max_rel_error_interior = 0.0;
  for (int i = 0; i < nl; ++i) {
    const int a = t.links[2 * i], b = t.links[2 * i + 1];
    const double l = std::hypot(x[2 * (size_t)b] - x[2 * (size_t)a],
                                x[2 * (size_t)b + 1] - x[2 * (size_t)a + 1]);
    const double e = (l - p.L[i]) / p.L[i];
    out->link_error[i] = e;
    out->max_rel_error = std::max(out->max_rel_error, std::fabs(e));
    sum2 += e * e;
    if (t.Boundary(i)) {
      out->link_on_boundary[i] = 1;
      ++out->num_boundary_links;
      out->max_rel_error_boundary = std::max(out->max_rel_error_boundary, std::fabs(e));
    } else {
      ++ni;
      sum2i += e * e;
      out->max_rel_error_interior = std::max(out->max_rel_error_interior, std::fabs(e));
    }
  }
  out->rms_rel_error = std::sqrt(sum2 / nl);
  out->rms_rel_error_interior = ni ? std::sqrt(sum2i / ni) : 0.0;
  OutlineLoops(t, x, nn, &out->outline);
  out->outline_length3d = out->outline_length2d = 0.0;
  for (const auto &loop : out->outline)
    for (size_t k = 0; k < loop.size(); ++k) {
      const int a = loop[k], b = loop[(k + 1) % loop.size()];
      out->outline_length3d += Dist3(&m.coords[3 * (size_t)a], &m.coords[3 * (size_t)b]);
      out->outline_length2d += std::hypot(x[2 * (size_t)b] - x[2 * (size_t)a],
                                          x[2 * (size_t)b + 1] - x[2 * (size_t)a + 1]);
    }
  std::vector<std::string> names = opt.line_sets;
  for (const auto &s : m.node_sets)
    for (const auto &pre : opt.line_prefixes)
      if (s.first.compare(0, pre.size(), pre) == 0 &&
          std::find(names.begin(), names.end(), s.first) == names.end())
        names.push_back(s.first);
  out->lines.clear();
  for (const auto &name : names) {
    auto it = m.node_sets.find(name);
    if (it == m.node_sets.end()) {
      return Fail(m, err, "line set '" + name + "' is not a node set of the strip (it has " +
                              std::to_string(m.node_sets.size()) + " node sets)");
    }
    // A cutting or weld line found by its prefix that only touches this strip at separate nodes
    // (where three strips meet: two surfaces cut into strips each) is no line of this strip.
    if (std::find(opt.line_sets.begin(), opt.line_sets.end(), name) == opt.line_sets.end()) {
      std::vector<char> in(m.NumNodes(), 0);
      for (int v : it->second) in[v] = 1;
      bool any = false;
      for (int i = 0; i < t.NumLinks() && !any; ++i) any = in[t.links[2 * i]] && in[t.links[2 * i + 1]];
      if (!any) continue;
    }
    PatternLine line;
    if (!MeasureLine(m, t, x, name, it->second, &line, err)) return false;
    out->lines.push_back(std::move(line));
  }
  return true;
}

} // namespace flatten
} // namespace etfe
