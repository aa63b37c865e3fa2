// Link topology of a strip for its flattening: unique edges with their triangles and opposite
// nodes, breadth-first triangle order, plane folds (see flatten.cpp for the formulation).

#include <algorithm>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <map>
#include <queue>
#include <string>
#include <utility>
#include <vector>

#include "flatten_internal.h"

namespace etfe {
namespace flatten {

std::string Format(const char *fmt, ...) {
  char buf[1024];
  va_list ap;
  va_start(ap, fmt);
  std::vsnprintf(buf, sizeof buf, fmt, ap);
  va_end(ap);
  return buf;
}

bool Fail(const MeshData &m, std::string *err, const std::string &msg) {
  if (err) *err = (m.source.empty() ? std::string("strip") : m.source) + ": " + msg;
  return false;
}

// Links (unique mesh edges) with their one or two triangles and the nodes opposite them.

bool BuildTopology(const MeshData &m, Topology *t, std::string *err) {
  std::map<std::pair<int, int>, int> id;
  const int ne = m.NumElements();
  t->tri_links.assign(3 * (size_t)ne, -1);
  for (int e = 0; e < ne; ++e) {
    const int *v = &m.triangles[3 * (size_t)e];
    for (int k = 0; k < 3; ++k) {
      const int a = std::min(v[k], v[(k + 1) % 3]), b = std::max(v[k], v[(k + 1) % 3]);
      const int c = v[(k + 2) % 3];
      auto ins = id.emplace(std::make_pair(a, b), t->NumLinks());
      const int i = ins.first->second;
      if (ins.second) {
        t->links.insert(t->links.end(), {a, b});
        t->tri.insert(t->tri.end(), {e, -1});
        t->opp.insert(t->opp.end(), {c, -1});
      } else if (t->tri[2 * i + 1] < 0) {
        t->tri[2 * i + 1] = e;
        t->opp[2 * i + 1] = c;
      } else {
        return Fail(m, err, Format("the edge between nodes %d and %d belongs to three or more "
                                   "triangles (%d, %d, %d): a cutting strip must be a manifold "
                                   "surface; split the mesh into strips along that line",
                                   a, b, t->tri[2 * i], t->tri[2 * i + 1], e));
      }
      t->tri_links[3 * (size_t)e + k] = i;
    }
  }
  return true;
}

double Dist3(const double *a, const double *b) {
  return std::sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
                   (a[2] - b[2]) * (a[2] - b[2]));
}

double Cross2(const double *o, const double *a, const double *b) {
  return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]);
}

// Triangles reached from triangle `start` across shared links (breadth first), in visit order,
// with the link each one was reached through (-1 for the start).
void TriangleBfs(const MeshData &m, const Topology &t, int start, std::vector<int> *order,
                 std::vector<int> *via) {
  const int ne = m.NumElements();
  std::vector<char> seen(ne, 0);
  order->clear();
  via->assign(ne, -1);
  std::queue<int> q;
  q.push(start);
  seen[start] = 1;
  while (!q.empty()) {
    const int e = q.front();
    q.pop();
    order->push_back(e);
    for (int k = 0; k < 3; ++k) {
      const int i = t.tri_links[3 * (size_t)e + k];
      const int f = t.tri[2 * i] == e ? t.tri[2 * i + 1] : t.tri[2 * i];
      if (f < 0 || seen[f]) continue;
      seen[f] = 1;
      (*via)[f] = i;
      q.push(f);
    }
  }
}

// Interior links whose two triangles lie on the same side of them in the plane (a fold).
int CountFolds(const Topology &t, const std::vector<double> &x, int *first) {
  int n = 0;
  for (int i = 0; i < t.NumLinks(); ++i) {
    if (t.Boundary(i)) continue;
    const double *a = &x[2 * (size_t)t.links[2 * i]], *b = &x[2 * (size_t)t.links[2 * i + 1]];
    const double s1 = Cross2(a, b, &x[2 * (size_t)t.opp[2 * i]]);
    const double s2 = Cross2(a, b, &x[2 * (size_t)t.opp[2 * i + 1]]);
    if (!(s1 * s2 < 0)) {
      if (n++ == 0 && first) *first = i;
    }
  }
  return n;
}

} // namespace flatten
} // namespace etfe
