// Cutting lines into a triangle mesh: neighbours, edge splits along a traced polyline, the pieces
// between cut edges (see etfe/kernels/geodesic.h). Splitting only (no edge flips), so every new
// triangle lies in the plane of the input triangle it came from and the surface is unchanged.
#include <algorithm>
#include <cmath>
#include <array>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <unordered_map>

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

using EdgeTris = std::unordered_map<long long, std::array<int, 2>>;  // edge key -> its (one or two) triangles

long long EKey(int a, int b) { return (long long)std::min(a, b) << 32 | (unsigned)std::max(a, b); }

EdgeTris BuildEdgeTris(const TriSurface &s) {
  EdgeTris m;
  m.reserve(2 * s.tris.size());
  for (int e = 0; e < s.NumTris(); ++e)
    for (int k = 0; k < 3; ++k) {
      auto it = m.emplace(EKey(s.tris[3 * e + k], s.tris[3 * e + (k + 1) % 3]), std::array<int, 2>{-1, -1}).first;
      (it->second[0] < 0 ? it->second[0] : it->second[1]) = e;
    }
  return m;
}

void EdgeReplace(EdgeTris *m, int a, int b, int from, int to) {
  auto &t = (*m)[EKey(a, b)];
  if (t[0] == from) t[0] = to;
  else if (t[1] == from) t[1] = to;
}
void EdgeAdd(EdgeTris *m, int a, int b, int e) {
  auto it = m->emplace(EKey(a, b), std::array<int, 2>{-1, -1}).first;
  (it->second[0] < 0 ? it->second[0] : it->second[1]) = e;
}

// Splits edge (a, b) at a + t (b - a): each triangle on it becomes two, the new node joined to the
// opposite vertex, orientation kept; the edge map follows. Returns the new node.
int SplitEdge(TriSurface *s, EdgeTris *m, int a, int b, double t) {
  const int p = s->NumNodes();
  for (int i = 0; i < 3; ++i)
    s->coords.push_back(s->coords[3 * (size_t)a + i] + t * (s->coords[3 * (size_t)b + i] - s->coords[3 * (size_t)a + i]));
  s->new_node_edge.push_back({a, b});
  if (!s->fixed.empty()) s->fixed.push_back(0);
  const std::array<int, 2> on = m->at(EKey(a, b));
  m->erase(EKey(a, b));
  for (int e : on) {
    if (e < 0) continue;
    for (int k = 0; k < 3; ++k) {
      const int x = s->tris[3 * e + k], y = s->tris[3 * e + (k + 1) % 3], z = s->tris[3 * e + (k + 2) % 3];
      if (!((x == a && y == b) || (x == b && y == a))) continue;
      const int f = s->NumTris();
      s->tris[3 * e] = x, s->tris[3 * e + 1] = p, s->tris[3 * e + 2] = z;
      s->tris.insert(s->tris.end(), {p, y, z});
      s->parent.push_back(s->parent[e]);
      EdgeReplace(m, y, z, e, f);
      EdgeAdd(m, x, p, e), EdgeAdd(m, p, y, f), EdgeAdd(m, p, z, e), EdgeAdd(m, p, z, f);
      break;
    }
  }
  // A split cut edge stays cut in both halves (only the line's own ends can lie on one).
  if (s->cut.erase(Key(a, b))) s->cut.insert(Key(a, p)), s->cut.insert(Key(p, b));
  return p;
}

double Dist(const double *x, const double *y) {
  return std::sqrt((x[0] - y[0]) * (x[0] - y[0]) + (x[1] - y[1]) * (x[1] - y[1]) + (x[2] - y[2]) * (x[2] - y[2]));
}

void Normal3(const double *x0, const double *x1, const double *x2, double n[3]) {
  double a[3], b[3];
  for (int i = 0; i < 3; ++i) a[i] = x1[i] - x0[i], b[i] = x2[i] - x0[i];
  n[0] = a[1] * b[2] - a[2] * b[1], n[1] = a[2] * b[0] - a[0] * b[2], n[2] = a[0] * b[1] - a[1] * b[0];
}

// Moves node v to x when none of its triangles turns over and their smallest quality keeps
// `keep` of what it was and `floor`; true when moved.
bool TryMove(TriSurface *s, const std::vector<int> &fan, int v, const double x[3], double keep, double floor) {
  double q0 = 1, q1 = 1;
  const double *X = s->coords.data();
  for (int e : fan) {
    const int *t = &s->tris[3 * e];
    const double *p[3] = {X + 3 * t[0], X + 3 * t[1], X + 3 * t[2]}, *r[3];
    for (int k = 0; k < 3; ++k) r[k] = t[k] == v ? x : p[k];
    double n0[3], n1[3];
    Normal3(p[0], p[1], p[2], n0);
    Normal3(r[0], r[1], r[2], n1);
    if (!(n0[0] * n1[0] + n0[1] * n1[1] + n0[2] * n1[2] > 0)) return false;
    q0 = std::min(q0, TriangleQuality(p[0], p[1], p[2]));
    q1 = std::min(q1, TriangleQuality(r[0], r[1], r[2]));
  }
  if (q1 < keep * q0 || q1 < floor) return false;
  for (int i = 0; i < 3; ++i) s->coords[3 * (size_t)v + i] = x[i];
  return true;
}

// Whether node v may move by dist along the edge (v, w): an interior node that is not fixed and
// on no cut, or a boundary node on the boundary edge (v, w) where the outline is straight or
// turns by less than 20 deg and the move stays within an eighth of the shorter boundary edge at v
// (the outline then moves by at most dist sin(turn), below the chord's own sagitta there).
bool Movable(const TriSurface &s, const EdgeTris &m, const std::vector<std::vector<int>> &vt,
             const std::vector<char> &on_cut, int v, int w, double dist) {
  if (on_cut[v] || (!s.fixed.empty() && s.fixed[v])) return false;
  std::vector<int> bnd;  // boundary neighbours of v
  for (int e : vt[v])
    for (int k = 0; k < 3; ++k) {
      const int x = s.tris[3 * e + k], y = s.tris[3 * e + (k + 1) % 3];
      if (x != v && y != v) continue;
      const auto &t = m.at(EKey(x, y));
      if (t[1] < 0) bnd.push_back(x == v ? y : x);
    }
  if (bnd.empty()) return true;
  std::sort(bnd.begin(), bnd.end());
  bnd.erase(std::unique(bnd.begin(), bnd.end()), bnd.end());
  if (bnd.size() != 2 || (bnd[0] != w && bnd[1] != w)) return false;
  const double *X = s.coords.data();
  double u[3], z[3];
  for (int i = 0; i < 3; ++i) u[i] = X[3 * bnd[0] + i] - X[3 * v + i], z[i] = X[3 * bnd[1] + i] - X[3 * v + i];
  const double c[3] = {u[1] * z[2] - u[2] * z[1], u[2] * z[0] - u[0] * z[2], u[0] * z[1] - u[1] * z[0]};
  const double lu = std::sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]), lz = std::sqrt(z[0] * z[0] + z[1] * z[1] + z[2] * z[2]);
  const double sin_turn = std::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]) / (lu * lz);
  if (u[0] * z[0] + u[1] * z[1] + u[2] * z[2] >= 0) return false;  // a corner
  return sin_turn <= 1e-9 || (sin_turn < std::sin(20.0 * 3.14159265358979323846 / 180) && dist <= std::min(lu, lz) / 8);
}

// The corner angles at v of the triangles around it, summed, and whether their normals differ
// (*bent).
double AngleSum(const TriSurface &s, const std::vector<int> &fan, int v, bool *bent) {
  double sum = 0, n0[3] = {0, 0, 0}, bend = 0;
  const double *X = s.coords.data();
  for (size_t i = 0; i < fan.size(); ++i) {
    const int *t = &s.tris[3 * fan[i]];
    int k = 0;
    while (t[k] != v) ++k;
    const double *a = X + 3 * t[k], *b = X + 3 * t[(k + 1) % 3], *c = X + 3 * t[(k + 2) % 3];
    double u[3], w[3], n[3];
    for (int j = 0; j < 3; ++j) u[j] = b[j] - a[j], w[j] = c[j] - a[j];
    sum += std::acos(std::max(-1.0, std::min(1.0, (u[0] * w[0] + u[1] * w[1] + u[2] * w[2]) /
                                                      std::sqrt((u[0] * u[0] + u[1] * u[1] + u[2] * u[2]) *
                                                                (w[0] * w[0] + w[1] * w[1] + w[2] * w[2])))));
    Normal3(a, b, c, n);
    const double ln = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    for (int j = 0; j < 3; ++j) n[j] /= ln;
    if (i == 0)
      for (int j = 0; j < 3; ++j) n0[j] = n[j];
    const double c2[3] = {n[1] * n0[2] - n[2] * n0[1], n[2] * n0[0] - n[0] * n0[2], n[0] * n0[1] - n[1] * n0[0]};
    bend = std::max(bend, std::sqrt(c2[0] * c2[0] + c2[1] * c2[1] + c2[2] * c2[2]));
  }
  *bent = bend > 1e-12;
  return sum;
}

// Whether moving v would spoil a developable surface: its triangles are bent (not in one plane)
// and every interior node among v and its neighbours has corner angles summing to 2 pi (1e-9):
// there the surface lies flat, and a moved node would no longer let its pattern flatten exactly.
bool DevelopableBend(const TriSurface &s, const EdgeTris &m, const std::vector<std::vector<int>> &vt, int v) {
  bool bent = false;
  const double two_pi = 2 * 3.14159265358979323846;
  auto interior = [&](int w) {
    for (int e : vt[w])
      for (int k = 0; k < 3; ++k) {
        const int x = s.tris[3 * e + k], y = s.tris[3 * e + (k + 1) % 3];
        if ((x == w || y == w) && m.at(EKey(x, y))[1] < 0) return false;
      }
    return true;
  };
  AngleSum(s, vt[v], v, &bent);
  if (!bent) return false;
  // v and its neighbours: every interior one flat (one alone can be flat on a curved mesh: a
  // hypar's grid has 2 pi at every other node, its curvature sitting at the nodes between).
  int flat = 0;
  std::vector<int> ring{v};
  for (int e : vt[v])
    for (int k = 0; k < 3; ++k) ring.push_back(s.tris[3 * e + k]);
  std::sort(ring.begin(), ring.end());
  ring.erase(std::unique(ring.begin(), ring.end()), ring.end());
  for (int w : ring) {
    if (!interior(w)) continue;
    bool b;
    if (std::fabs(AngleSum(s, vt[w], w, &b) - two_pi) >= 1e-9) return false;
    ++flat;
  }
  return flat > 0;
}

// The pre-pass: where the line passes near a node, the run of consecutive crossings on that
// node's edges becomes the node (moved onto the line at the nearest crossing, or, within tol,
// left where it is). Nodes nearest the line first. Returns the new point list.
std::vector<SurfacePoint> MeshToLine(TriSurface *s, const EdgeTris &m, const std::vector<char> &on_cut,
                                     const std::vector<SurfacePoint> &line, const LineInsertOptions &o,
                                     LineInsertStats *st, std::vector<char> *exact) {
  const int n = (int)line.size();
  struct Near {
    double d;
    int i, v, w;
  };
  std::vector<Near> cand;
  for (int i = 0; i < n; ++i) {
    const SurfacePoint &p = line[i];
    if (p.b < 0) continue;
    const double L = Dist(&s->coords[3 * (size_t)p.a], &s->coords[3 * (size_t)p.b]);
    const bool at_a = p.t <= 0.5;
    const double f = at_a ? p.t : 1 - p.t;
    if (f < o.relocate || f * L <= o.tol) cand.push_back({f * L, i, at_a ? p.a : p.b, at_a ? p.b : p.a});
  }
  exact->assign(n, 0);
  if (cand.empty()) return line;
  std::sort(cand.begin(), cand.end(), [](const Near &x, const Near &y) { return x.d < y.d; });
  std::vector<std::vector<int>> vt(s->NumNodes());
  for (int e = 0; e < s->NumTris(); ++e)
    for (int k = 0; k < 3; ++k) vt[s->tris[3 * e + k]].push_back(e);
  std::vector<int> owner(n, -1);  // the node a point's run became
  auto has = [&](int j, int v) { return line[j].a == v || line[j].b == v; };
  for (const Near &c : cand) {
    if (owner[c.i] >= 0) continue;
    // The run stops at points already taken by a neighbour (the line then goes from that node
    // to this one along the edge they share, which the point between them lies on).
    int lo = c.i, hi = c.i;
    while (lo > 0 && has(lo - 1, c.v) && owner[lo - 1] < 0) --lo;
    while (hi + 1 < n && has(hi + 1, c.v) && owner[hi + 1] < 0) ++hi;
    bool take = c.d <= o.tol;
    if (!take && DevelopableBend(*s, m, vt, c.v)) {
      for (int j = lo; j <= hi; ++j) (*exact)[j] = 1;
      continue;
    }
    if (take) {
      st->line_moved = std::max(st->line_moved, c.d);
    } else if (Movable(*s, m, vt, on_cut, c.v, c.w, c.d) && TryMove(s, vt[c.v], c.v, line[c.i].x, o.keep_quality, o.quality_floor)) {
      take = true;
      ++st->relocated;
      st->relocated_max = std::max(st->relocated_max, c.d);
    }
    if (take)
      for (int j = lo; j <= hi; ++j) owner[j] = c.v;
  }
  std::vector<SurfacePoint> out;
  std::vector<char> out_exact;
  for (int i = 0; i < n; ++i) {
    if (owner[i] < 0) {
      out.push_back(line[i]);
      out_exact.push_back((*exact)[i]);
    } else if (i == 0 || owner[i - 1] != owner[i]) {
      SurfacePoint p;
      p.a = owner[i];
      for (int k = 0; k < 3; ++k) p.x[k] = s->coords[3 * (size_t)p.a + k];
      out.push_back(p);
      out_exact.push_back(0);
    }
  }
  *exact = out_exact;
  return out;
}

} // namespace

bool SurfaceBuildNeighbours(TriSurface *s, std::string *err) {
  const int nt = s->NumTris();
  std::vector<std::pair<long long, int>> half(3 * (size_t)nt);  // edge key, 3 * triangle + k
  for (int e = 0; e < nt; ++e)
    for (int k = 0; k < 3; ++k) half[3 * e + k] = {EKey(s->tris[3 * e + k], s->tris[3 * e + (k + 1) % 3]), 3 * e + k};
  std::sort(half.begin(), half.end());
  s->nbr.assign(3 * (size_t)nt, -1);
  s->vtri.assign(s->NumNodes(), -1);
  for (int e = 0; e < nt; ++e)
    for (int k = 0; k < 3; ++k) s->vtri[s->tris[3 * e + k]] = e;
  for (size_t i = 0; i < half.size();) {
    size_t j = i;
    while (j < half.size() && half[j].first == half[i].first) ++j;
    const int a = (int)(half[i].first >> 32), b = (int)(half[i].first & 0xffffffff);
    if (j - i > 2) {
      *err = "the edge between nodes " + std::to_string(a) + " and " + std::to_string(b) + " is in " +
             std::to_string(j - i) + " triangles: not a manifold surface";
      return false;
    }
    if (j - i == 2) {
      const int p = half[i].second, q = half[i + 1].second;
      if (s->tris[p] == s->tris[q]) {
        *err = "triangles " + std::to_string(p / 3) + " and " + std::to_string(q / 3) + " are oriented differently";
        return false;
      }
      s->nbr[p] = q / 3, s->nbr[q] = p / 3;
    }
    i = j;
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
  LineInsertOptions o;
  o.relocate = snap;
  LineInsertStats st;
  const bool ok = SurfaceInsertLine(s, line, o, vertices, &st, err);
  if (moved) *moved = st.line_moved;
  return ok;
}

bool SurfaceInsertLine(TriSurface *s, const std::vector<SurfacePoint> &line0, const LineInsertOptions &o,
                       std::vector<int> *vertices, LineInsertStats *stats, std::string *err) {
  LineInsertStats local;
  LineInsertStats &st = stats ? *stats : local;
  st = LineInsertStats();
  std::vector<char> on_cut(s->NumNodes(), 0);
  for (const auto &c : s->cut) on_cut[c.first] = on_cut[c.second] = 1;
  EdgeTris m = BuildEdgeTris(*s);
  std::vector<char> exact;  // points split in where they are (no snap): a developable bend
  const std::vector<SurfacePoint> line = MeshToLine(s, m, on_cut, line0, o, &st, &exact);
  // Splits made by this line: edge key -> (new node, t along the key's order), so that a point
  // on an edge split before is found on the right half.
  std::map<std::pair<int, int>, std::pair<int, double>> split;
  vertices->clear();
  for (size_t ip = 0; ip < line.size(); ++ip) {
    const SurfacePoint &pt = line[ip];
    // Next to a developable bend only a crossing within kBendSnap of a node goes to it: the seam
    // steps by at most that fraction of an edge, the split triangles keep about that fraction of
    // their quality, and the surface stays as it was (its pattern flattens exactly).
    const double kBendSnap = 0.05;
    const double snap = exact[ip] ? std::min(o.relocate, kBendSnap) : o.relocate;
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
      // A node that could not move: the line goes to it (the old snap), the step reported.
      const double L = Dist(&s->coords[3 * (size_t)a], &s->coords[3 * (size_t)b]);
      const bool near_a = t < snap || t * L <= o.tol, near_b = 1 - t < snap || (1 - t) * L <= o.tol;
      if (near_a && (!near_b || t <= 0.5)) v = a;
      else if (near_b) v = b;
      else {
        if (s->cut.count(Key(a, b))) {
          *err = "the line crosses another cutting line at " + Where(*s, a) + " - " + Where(*s, b);
          return false;
        }
        v = SplitEdge(s, &m, a, b, t);
        on_cut.push_back(0);
        split[Key(a, b)] = {v, t};
      }
      if (v == a || v == b) {
        const double d = Dist(&s->coords[3 * (size_t)v], pt.x);
        if (d > o.tol) ++st.snapped;
        st.line_moved = std::max(st.line_moved, d);
      }
    }
    if (on_cut[v] && v != o.shared_node) {
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
  for (size_t i = 1; i < vertices->size(); ++i) {
    const int a = (*vertices)[i - 1], b = (*vertices)[i];
    if (!m.count(EKey(a, b))) {
      *err = "the line crosses one triangle twice near " + Where(*s, std::min(a, b)) +
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
