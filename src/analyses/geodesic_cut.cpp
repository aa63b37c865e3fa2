// Strips of width W cut by seams (see etfe/analyses/geodesic_cut.h), per physical surface: the middle, the
// transverse geodesic, the seams (geodesics or plane sections) traced and inserted one after
// another (each traced on the mesh as the seams before it left it: split triangles lie in their
// parents' planes; nodes moved onto a seam change the surface near it by at most the move times
// the angle between their triangles), then the strips by flood fill, named in order across.
#include "etfe/analyses/geodesic_cut.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <set>

#include "etfe/analyses/cutpattern.h"
#include "etfe/kernels/geodesic.h"

namespace etfe {

namespace {

const char *const kAxis[] = {"x", "y", "z"};

std::string Fmt(const char *f, double a, double b = 0, double c = 0, double d = 0) {
  char buf[256];
  std::snprintf(buf, sizeof buf, f, a, b, c, d);
  return buf;
}

// Barycentric coordinates of the point q (in the plane of triangle e) in e.
void Barycentric(const TriSurface &s, int e, const double q[3], double l[3]) {
  double n[3];
  SurfaceTriangleNormal(s, e, n);
  const double nn = n[0] * n[0] + n[1] * n[1] + n[2] * n[2];
  for (int k = 0; k < 3; ++k) {
    const double *a = &s.coords[3 * s.tris[3 * e + (k + 1) % 3]], *b = &s.coords[3 * s.tris[3 * e + (k + 2) % 3]];
    const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, w[3] = {q[0] - a[0], q[1] - a[1], q[2] - a[2]};
    const double c[3] = {u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]};
    l[k] = (c[0] * n[0] + c[1] * n[1] + c[2] * n[2]) / nn;
  }
}

// The triangle of s holding q (a child of the input triangle `parent` first, then any triangle
// whose plane q lies in: a point on an edge of the input mesh is in the triangles on both
// sides), with d not leaving it through an edge q lies on; -1 if none.
int Locate(const TriSurface &s, int parent, const double q[3], const double d[3], double l[3]) {
  const double tol = 1e-9;
  for (int pass = 0; pass < 2; ++pass)
    for (int e = 0; e < s.NumTris(); ++e) {
      if ((pass == 0) != (s.parent[e] == parent)) continue;
      Barycentric(s, e, q, l);
      if (std::min({l[0], l[1], l[2]}) < -tol) continue;
      double n[3], off = 0;
      SurfaceTriangleNormal(s, e, n);
      const double *a = &s.coords[3 * s.tris[3 * e]];
      for (int i = 0; i < 3; ++i) off += (q[i] - a[i]) * n[i];
      const double nl = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);  // twice the area ~ h^2
      if (std::fabs(off) > tol * nl * std::sqrt(nl)) continue;  // q off the plane by more than ~tol h
      bool inward = true;
      for (int k = 0; k < 3; ++k) {
        if (l[k] > tol) continue;
        // q on the edge opposite node k: d must not decrease l[k].
        const double qd[3] = {q[0] + d[0], q[1] + d[1], q[2] + d[2]};
        double m[3];
        Barycentric(s, e, qd, m);
        if (m[k] - l[k] < -1e-12) inward = false;
      }
      if (inward) return e;
    }
  return -1;
}

struct Trace {
  bool ok = false;
  std::vector<SurfacePoint> line;  // boundary to boundary
  double length = 0.0;
  int vertices = 0;
};

// Both halves of the geodesic through q (in triangle tri, or at node v when v >= 0) along +-d.
bool TraceBothWays(const TriSurface &s, int v, int parent, const double q[3], const double d[3], int max_steps,
                   Trace *out, std::string *err) {
  GeodesicPath f, b;
  int tf = -1, tb = -1;
  double df[3], db[3], l[3];
  const double md[3] = {-d[0], -d[1], -d[2]};
  SurfacePoint mid;
  for (int i = 0; i < 3; ++i) mid.x[i] = v >= 0 ? s.coords[3 * (size_t)v + i] : q[i];
  bool mid_is_point = false;
  if (v >= 0) {
    if (!GeodesicStartAtVertex(s, v, d, &tf, df) || !GeodesicOppositeAtVertex(s, v, tf, df, &tb, db)) {
      *err = "no direction through the middle node";
      return false;
    }
    mid.a = v, mid_is_point = true;
  } else {
    // A point at a node of the mesh starts there (the theta/2 rule gives the way back).
    const int e = Locate(s, parent, q, d, l);
    for (int k = 0; k < 3 && e >= 0; ++k)
      if (l[k] > 1 - 1e-9) return TraceBothWays(s, s.tris[3 * e + k], parent, q, d, max_steps, out, err);
    tf = Locate(s, parent, q, d, l), tb = Locate(s, parent, q, md, l);
    if (tf < 0 || tb < 0) {
      *err = "the point on the transverse geodesic is not found in the mesh";
      return false;
    }
    for (int i = 0; i < 3; ++i) df[i] = d[i], db[i] = md[i];
    Barycentric(s, tf, q, l);
    for (int k = 0; k < 3; ++k)
      if (l[k] < 1e-9) {  // on the edge opposite node k
        const int a = s.tris[3 * tf + (k + 1) % 3], c = s.tris[3 * tf + (k + 2) % 3];
        mid.a = std::min(a, c), mid.b = std::max(a, c);
        mid.t = a < c ? l[(k + 2) % 3] : l[(k + 1) % 3];
        mid_is_point = true;
      }
  }
  const double *start = v >= 0 ? &s.coords[3 * (size_t)v] : q;
  if (!GeodesicTrace(s, tf, start, df, max_steps, &f, err) || !GeodesicTrace(s, tb, start, db, max_steps, &b, err))
    return false;
  out->ok = f.reached_boundary && b.reached_boundary;
  out->line.assign(b.points.rbegin(), b.points.rend());
  if (mid_is_point) out->line.push_back(mid);
  out->line.insert(out->line.end(), f.points.begin(), f.points.end());
  out->length = f.length + b.length;
  out->vertices = f.vertices_passed + b.vertices_passed;
  return true;
}

// The mean edge length h (each edge once) and the area centroid of s.
void MeanEdgeAndCentroid(const TriSurface &s, double *h, double centroid[3]) {
  double area = 0;
  *h = 0;
  for (int i = 0; i < 3; ++i) centroid[i] = 0;
  std::set<std::pair<int, int>> edges;
  for (int e = 0; e < s.NumTris(); ++e) {
    const double *x[3] = {&s.coords[3 * s.tris[3 * e]], &s.coords[3 * s.tris[3 * e + 1]], &s.coords[3 * s.tris[3 * e + 2]]};
    const double A = TriangleArea(x[0], x[1], x[2]);
    area += A;
    for (int i = 0; i < 3; ++i) centroid[i] += A * (x[0][i] + x[1][i] + x[2][i]) / 3;
    for (int k = 0; k < 3; ++k) {
      const int a = s.tris[3 * e + k], b = s.tris[3 * e + (k + 1) % 3];
      if (edges.insert({std::min(a, b), std::max(a, b)}).second)
        *h += std::sqrt(std::pow(s.coords[3 * a] - s.coords[3 * b], 2) + std::pow(s.coords[3 * a + 1] - s.coords[3 * b + 1], 2) +
                        std::pow(s.coords[3 * a + 2] - s.coords[3 * b + 2], 2));
    }
  }
  *h /= std::max<size_t>(1, edges.size());
  for (int i = 0; i < 3; ++i) centroid[i] /= area;
}

// The interior node nearest the point c; -1 when s has no interior node.
int InteriorNodeNearest(const TriSurface &s, const double c[3]) {
  int v = -1;
  double best = std::numeric_limits<double>::infinity();
  for (int n = 0; n < s.NumNodes(); ++n) {
    const double d2 = std::pow(s.coords[3 * n] - c[0], 2) + std::pow(s.coords[3 * n + 1] - c[1], 2) +
                      std::pow(s.coords[3 * n + 2] - c[2], 2);
    if (d2 < best && !SurfaceVertexOnBoundary(s, n)) best = d2, v = n;
  }
  return v;
}

// The unit direction across the strips at node v: its normal (the sum of its triangles' normals)
// times the strip axis. False when the axis is (nearly) normal to the surface there.
bool TransverseDirection(const TriSurface &s, int v, const double axis[3], double tr[3]) {
  double nv[3] = {0, 0, 0};
  for (int e = 0; e < s.NumTris(); ++e)
    if (s.tris[3 * e] == v || s.tris[3 * e + 1] == v || s.tris[3 * e + 2] == v) {
      double n[3];
      SurfaceTriangleNormal(s, e, n);
      for (int i = 0; i < 3; ++i) nv[i] += n[i];
    }
  tr[0] = nv[1] * axis[2] - nv[2] * axis[1], tr[1] = nv[2] * axis[0] - nv[0] * axis[2], tr[2] = nv[0] * axis[1] - nv[1] * axis[0];
  const double nn = std::sqrt(nv[0] * nv[0] + nv[1] * nv[1] + nv[2] * nv[2]);
  const double tn = std::sqrt(tr[0] * tr[0] + tr[1] * tr[1] + tr[2] * tr[2]);
  if (!(tn > 0.1 * nn)) return false;
  for (int i = 0; i < 3; ++i) tr[i] /= tn;
  return true;
}

// The middle of the surface and the transverse geodesic through it, on which the cutting lines start.
struct Transverse {
  int vmid = -1;                   // the middle node
  double mid[3] = {0, 0, 0};       // its coordinates (a copy: inserting lines grows s.coords)
  double axis[3] = {0, 0, 0};      // the strip direction
  double dir[3] = {0, 0, 0};       // the direction across the strips at the middle
  int max_steps = 0;               // triangle crossings a trace may take
  GeodesicPath fwd, back;          // the transverse geodesic from the middle along +dir and -dir
};

// Both halves of the transverse geodesic through the middle node of the uncut surface.
bool TraceTransverse(const TriSurface &s, Transverse *t, std::string *err) {
  int tf, tb;
  double df[3], db[3];
  return GeodesicStartAtVertex(s, t->vmid, t->dir, &tf, df) && GeodesicOppositeAtVertex(s, t->vmid, tf, df, &tb, db) &&
         GeodesicTrace(s, tf, t->mid, df, t->max_steps, &t->fwd, err) &&
         GeodesicTrace(s, tb, t->mid, db, t->max_steps, &t->back, err);
}

// The cutting lines' signed arc lengths from the middle on the transverse geodesic (+ along fwd):
// 0, then steps of W each way while at least W/4 is left to the boundary.
std::vector<double> LineOffsets(double width, double fwd_length, double back_length) {
  std::vector<double> offsets{0.0};
  for (int k = 1; k * width <= fwd_length - 0.25 * width; ++k) offsets.push_back(k * width);
  for (int k = 1; k * width <= back_length - 0.25 * width; ++k) offsets.push_back(-k * width);
  return offsets;
}

// Where the cutting line `off` mm from the middle (off != 0) crosses the transverse geodesic: the
// point q in the input triangle *parent, and the line's direction c there, at right angles to the
// geodesic and along the strip axis.
void CuttingLineStart(const TriSurface &s, const Transverse &t, double off, double q[3], double c[3], int *parent) {
  const GeodesicPath &g = off > 0 ? t.fwd : t.back;
  double prev[3] = {t.mid[0], t.mid[1], t.mid[2]}, sum = 0;
  const double want = std::fabs(off);
  size_t i = 0;
  for (; i < g.points.size(); ++i) {
    const double *x = g.points[i].x;
    const double l = std::sqrt(std::pow(x[0] - prev[0], 2) + std::pow(x[1] - prev[1], 2) + std::pow(x[2] - prev[2], 2));
    if (sum + l >= want) break;
    sum += l;
    for (int j = 0; j < 3; ++j) prev[j] = x[j];
  }
  i = std::min(i, g.points.size() - 1);
  const double *u = &g.segment_dir[3 * i];
  for (int j = 0; j < 3; ++j) q[j] = prev[j] + (want - sum) * u[j];
  *parent = g.segment_tri[i];
  double n[3];
  SurfaceTriangleNormal(s, *parent, n);  // the transverse trace ran on the uncut mesh: parent ids are its own
  c[0] = n[1] * u[2] - n[2] * u[1], c[1] = n[2] * u[0] - n[0] * u[2], c[2] = n[0] * u[1] - n[1] * u[0];
  if (c[0] * t.axis[0] + c[1] * t.axis[1] + c[2] * t.axis[2] < 0)
    for (int i = 0; i < 3; ++i) c[i] = -c[i];
}

// What the insertion of the lines did, over all lines of a surface.
struct SeamStats {
  double line_moved = 0, relocated_max = 0, max_turn = 0;
  int relocated = 0, snapped = 0;
  void Add(const LineInsertStats &st, double turn) {
    line_moved = std::max(line_moved, st.line_moved), relocated_max = std::max(relocated_max, st.relocated_max);
    relocated += st.relocated, snapped += st.snapped, max_turn = std::max(max_turn, turn);
  }
};

const double kDeg = 180.0 / 3.14159265358979323846;

// Traces the cutting line `off` mm from the middle both ways and inserts it into s, with a note.
bool InsertCuttingLine(TriSurface *s, const Transverse &t, double off, const LineInsertOptions &io,
                       const std::string &opt, SeamStats *seams, std::vector<std::string> *notes, std::string *err) {
  Trace line;
  std::string why;
  int parent = -1;
  double q[3], c[3];
  if (off == 0) {
    for (int i = 0; i < 3; ++i) q[i] = t.mid[i], c[i] = t.axis[i];
  } else {
    CuttingLineStart(*s, t, off, q, c, &parent);
  }
  std::vector<int> verts;
  LineInsertStats st;
  if (!TraceBothWays(*s, off == 0 ? t.vmid : -1, parent, q, c, t.max_steps, &line, &why) || !line.ok ||
      !SurfaceInsertLine(s, line.line, io, &verts, &st, &why)) {
    if (why.empty()) why = "it does not reach the boundary within " + std::to_string(t.max_steps) + " crossings (it winds on the surface)";
    const bool meets = why.find("another cutting line") != std::string::npos;
    *err = opt + ": the cutting line " + Fmt("%+.1f", off) + " mm from the middle " +
           Fmt("(%.1f, %.1f, %.1f) mm", q[0], q[1], q[2]) + ": " + why +
           (meets ? " (geodesics started W apart converge where the surface curves like a sphere, K > 0, or "
                    "meet at a node when W is near the element size): split the surface into shorter pieces, "
                    "choose another -cutpattern_strip_direction or refine the mesh"
                  : "; give a larger width or another -cutpattern_strip_direction");
    return false;
  }
  const double turn = PolylineMaxTurn(*s, verts);
  seams->Add(st, turn);
  notes->push_back("geodesic line " + Fmt("%+.1f", off) + " mm from the middle: " + Fmt("%.3f", line.length) +
                   " mm long, " + std::to_string(verts.size()) + " nodes, " + std::to_string(line.vertices) +
                   " mesh nodes passed, inserted within " + Fmt("%.3f", st.line_moved) +
                   " mm of the traced geodesic, " + std::to_string(st.relocated) + " mesh nodes moved onto it (" +
                   Fmt("%.3f", st.relocated_max) + " mm at most), largest turn between seam segments " +
                   Fmt("%.3f", turn * kDeg) + " deg");
  return true;
}

// The plane section through the point q of the transverse geodesic, normal to the strips
// (normal t.dir): inserted into s, each piece (a section may leave and re-enter the surface) a
// line, with a note.
bool InsertPlaneLine(TriSurface *s, const Transverse &t, double off, const LineInsertOptions &io,
                     const std::string &opt, SeamStats *seams, std::vector<std::string> *notes, std::string *err) {
  double q[3], c[3];
  int parent = -1;
  if (off == 0) {
    for (int i = 0; i < 3; ++i) q[i] = t.mid[i];
  } else {
    CuttingLineStart(*s, t, off, q, c, &parent);
  }
  const double level = t.dir[0] * q[0] + t.dir[1] * q[1] + t.dir[2] * q[2];
  int loops = 0;
  const std::vector<std::vector<SurfacePoint>> lines = SurfacePlaneSection(*s, t.dir, level, &loops);
  const std::string where = "the planar cut " + Fmt("%+.1f", off) + " mm from the middle " +
                            Fmt("(%.1f, %.1f, %.1f) mm", q[0], q[1], q[2]);
  if (lines.empty() || loops > 0) {
    *err = opt + ": " + where + (lines.empty() ? " does not cross the surface" : " closes on itself") +
           "; give another width or direction, or -cutpattern_strip_layout geodesic";
    return false;
  }
  for (const auto &line : lines) {
    std::vector<int> verts;
    LineInsertStats st;
    std::string why;
    if (!SurfaceInsertLine(s, line, io, &verts, &st, &why)) {
      *err = opt + ": " + where + ": " + why + "; give another width or direction";
      return false;
    }
    double length = 0;
    for (size_t i = 1; i < verts.size(); ++i) {
      const double *x = &s->coords[3 * (size_t)verts[i - 1]], *y = &s->coords[3 * (size_t)verts[i]];
      length += std::sqrt((x[0] - y[0]) * (x[0] - y[0]) + (x[1] - y[1]) * (x[1] - y[1]) + (x[2] - y[2]) * (x[2] - y[2]));
    }
    const double turn = PolylineMaxTurn(*s, verts);
    seams->Add(st, turn);
    notes->push_back("planar line " + Fmt("%+.1f", off) + " mm from the middle: " + Fmt("%.3f", length) +
                     " mm long, " + std::to_string(verts.size()) + " nodes, inserted within " +
                     Fmt("%.3f", st.line_moved) + " mm of the plane section, " + std::to_string(st.relocated) +
                     " mesh nodes moved onto it (" + Fmt("%.3f", st.relocated_max) +
                     " mm at most), largest turn between seam segments " + Fmt("%.3f", turn * kDeg) + " deg");
  }
  return true;
}

// The pieces (labels 0..count-1) in order across: by their area centroids along the transverse
// direction at the middle.
std::vector<int> PiecesAcross(const TriSurface &s, const std::vector<int> &label, int count, const Transverse &t) {
  std::vector<double> key(count, 0.0), weight(count, 0.0);
  for (int e = 0; e < s.NumTris(); ++e) {
    const double *x[3] = {&s.coords[3 * s.tris[3 * e]], &s.coords[3 * s.tris[3 * e + 1]], &s.coords[3 * s.tris[3 * e + 2]]};
    const double A = TriangleArea(x[0], x[1], x[2]);
    for (int i = 0; i < 3; ++i) key[label[e]] += A * t.dir[i] * ((x[0][i] + x[1][i] + x[2][i]) / 3 - t.mid[i]);
    weight[label[e]] += A;
  }
  std::vector<int> order(count);
  for (int k = 0; k < count; ++k) order[k] = k, key[k] /= weight[k];
  std::sort(order.begin(), order.end(), [&](int a, int b) { return key[a] < key[b]; });
  return order;
}

// One strip per piece, in order across: its name <base>_NN and triangles (ids of s), with a
// note of its width on the transverse geodesic (offsets sorted; geodesic layout).
void NameStrips(const TriSurface &s, const std::vector<int> &label, const std::vector<int> &order,
                const std::vector<double> &offsets, const Transverse &t, const std::string &base, bool widths,
                std::vector<std::pair<std::string, std::vector<int>>> *strips, std::vector<std::string> *notes) {
  const int count = (int)order.size();
  std::vector<int> rank(count);
  for (int k = 0; k < count; ++k) rank[order[k]] = k;
  for (int k = 0; k < count; ++k) {
    char name[96];
    std::snprintf(name, sizeof name, "%s_%02d", base.c_str(), k + 1);
    strips->push_back({name, {}});
  }
  const size_t first = strips->size() - count;
  for (int e = 0; e < s.NumTris(); ++e) (*strips)[first + rank[label[e]]].second.push_back(e);
  for (int k = 0; k < count; ++k) {
    std::string note = "strip " + (*strips)[first + k].first + ": " + std::to_string((*strips)[first + k].second.size()) +
                       " triangles";
    if (widths) {
      const double lo = k == 0 ? -t.back.length : offsets[k - 1], hi = k == count - 1 ? t.fwd.length : offsets[k];
      note = "geodesic " + note + ", width on the transverse geodesic " + Fmt("%.3f", hi - lo) + " mm";
    }
    notes->push_back(note);
  }
}

double SmallestQuality(const std::vector<double> &coords, const std::vector<int> &tris) {
  double q = 1;
  for (size_t e = 0; e < tris.size() / 3; ++e)
    q = std::min(q, TriangleQuality(&coords[3 * tris[3 * e]], &coords[3 * tris[3 * e + 1]], &coords[3 * tris[3 * e + 2]]));
  return q;
}

// The start line's middle node (of its segments in file order, the end nearest half its length
// of the segment holding that half) and the segment's unit direction; false naming the group when
// it is no 1-D group of the mesh or has a node on no triangle (off the surface).
bool StartLineMiddle(const MeshData &m, const std::string &name, int *node, double dir[3], std::string *err) {
  const std::string opt = "-cutpattern_strip_start " + name;
  const auto it = m.line_sets.find(name);
  if (it == m.line_sets.end()) {
    const bool other = m.node_sets.count(name) || m.element_sets.count(name);
    *err = opt + ": " + m.source + (other ? " has a group of that name but it is not 1-D (line elements)"
                                          : " has no physical group of that name") +
           "; give a 1-D physical group (a curve drawn on the surface)";
    return false;
  }
  const std::vector<int> &ls = it->second;
  double total = 0;
  for (size_t k = 0; k + 1 < ls.size(); k += 2) {
    if (ls[k] < 0 || ls[k + 1] < 0) {
      *err = opt + ": a node of its line elements is on no triangle of " + m.source +
             ": the line does not lie on the surface; draw it through the surface's nodes";
      return false;
    }
    const double *a = &m.coords[3 * (size_t)ls[k]], *b = &m.coords[3 * (size_t)ls[k + 1]];
    total += std::sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
  }
  if (ls.size() < 2 || !(total > 0)) {
    *err = opt + ": the group has no line element of positive length in " + m.source + "; give a curve";
    return false;
  }
  double sum = 0;
  for (size_t k = 0; k + 1 < ls.size(); k += 2) {
    const double *a = &m.coords[3 * (size_t)ls[k]], *b = &m.coords[3 * (size_t)ls[k + 1]];
    const double l = std::sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
    if (sum + l >= 0.5 * total || k + 3 >= ls.size()) {
      *node = 0.5 * total - sum <= sum + l - 0.5 * total ? ls[k] : ls[k + 1];
      for (int i = 0; i < 3; ++i) dir[i] = (b[i] - a[i]) / l;
      return true;
    }
    sum += l;
  }
  return true;
}

// Radial seams (layout 2): the surface's sections by planes through the middle node along its
// normal there, n/2 planes at equal angles giving n gores (n even, at least 4, the fewest whose
// rim arcs, the boundary's length / n, are at most W), named in order round the middle.
bool RadialStrips(const MeshData &sub, const std::string &base, const Transverse &t, LineInsertOptions io,
                  const GeodesicCutOptions &o, const std::string &opt, TriSurface *s,
                  std::vector<std::pair<std::string, std::vector<int>>> *strips, std::vector<std::string> *notes,
                  std::string *err) {
  const auto t0 = std::chrono::steady_clock::now();
  double rim = 0;
  for (int e = 0; e < s->NumTris(); ++e)
    for (int k = 0; k < 3; ++k)
      if (s->nbr[3 * e + k] < 0) {
        const double *a = &s->coords[3 * (size_t)s->tris[3 * e + k]], *b = &s->coords[3 * (size_t)s->tris[3 * e + (k + 1) % 3]];
        rim += std::sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
      }
  int n = std::max(4, (int)std::ceil(rim / o.width - 1e-9));
  n += n % 2;
  // The frame at the middle: the normal (its triangles' normals summed), e1 across the strips, e2.
  double nv[3] = {0, 0, 0};
  for (int e = 0; e < s->NumTris(); ++e)
    if (s->tris[3 * e] == t.vmid || s->tris[3 * e + 1] == t.vmid || s->tris[3 * e + 2] == t.vmid) {
      double ne[3];
      SurfaceTriangleNormal(*s, e, ne);
      for (int i = 0; i < 3; ++i) nv[i] += ne[i];
    }
  const double ln = std::sqrt(nv[0] * nv[0] + nv[1] * nv[1] + nv[2] * nv[2]);
  for (int i = 0; i < 3; ++i) nv[i] /= ln;
  const double *e1 = t.dir;
  const double e2[3] = {nv[1] * e1[2] - nv[2] * e1[1], nv[2] * e1[0] - nv[0] * e1[2], nv[0] * e1[1] - nv[1] * e1[0]};
  io.shared_node = t.vmid;
  SeamStats seams;
  const double pi = 3.14159265358979323846;
  for (int k = 0; k < n / 2; ++k) {
    const double th = 2 * pi * k / n, d[3] = {std::cos(th) * e1[0] + std::sin(th) * e2[0],
                                              std::cos(th) * e1[1] + std::sin(th) * e2[1],
                                              std::cos(th) * e1[2] + std::sin(th) * e2[2]};
    const double pn[3] = {nv[1] * d[2] - nv[2] * d[1], nv[2] * d[0] - nv[0] * d[2], nv[0] * d[1] - nv[1] * d[0]};
    const double *c = &s->coords[3 * (size_t)t.vmid];
    const double level = pn[0] * c[0] + pn[1] * c[1] + pn[2] * c[2];
    int loops = 0;
    const auto lines = SurfacePlaneSection(*s, pn, level, &loops);
    const std::string where = "the radial cut at " + Fmt("%.1f", th * 180 / pi) + " deg";
    if (lines.size() != 1 || loops > 0) {
      *err = opt + ": " + where + " through the middle " + Fmt("(%.1f, %.1f, %.1f) mm", c[0], c[1], c[2]) +
             " crosses the surface in " + std::to_string(lines.size()) + " pieces and " + std::to_string(loops) +
             " loops, not one line: radial seams need a surface round its middle (a round foil)";
      return false;
    }
    std::vector<int> verts;
    LineInsertStats st;
    std::string why;
    if (!SurfaceInsertLine(s, lines[0], io, &verts, &st, &why)) {
      *err = opt + ": " + where + ": " + why;
      return false;
    }
    const double turn = PolylineMaxTurn(*s, verts);
    seams.Add(st, turn);
    notes->push_back("radial line at " + Fmt("%.1f", th * 180 / pi) + " deg: " + std::to_string(verts.size()) +
                     " nodes, " + std::to_string(st.relocated) + " mesh nodes moved onto it (" +
                     Fmt("%.3f", st.relocated_max) + " mm at most), largest turn between seam segments " +
                     Fmt("%.3f", turn * kDeg) + " deg");
  }
  std::vector<int> label;
  const int count = SurfaceComponents(*s, &label);
  if (count != n) {
    *err = opt + ": " + std::to_string(n / 2) + " radial cuts left " + std::to_string(count) + " pieces instead of " +
           std::to_string(n) + " gores; give another width";
    return false;
  }
  // In order round the middle: by the angle of each gore's area centroid.
  std::vector<double> cx(count, 0), cy(count, 0);
  const double *c = &s->coords[3 * (size_t)t.vmid];
  for (int e = 0; e < s->NumTris(); ++e) {
    const double *x[3] = {&s->coords[3 * s->tris[3 * e]], &s->coords[3 * s->tris[3 * e + 1]], &s->coords[3 * s->tris[3 * e + 2]]};
    const double A = TriangleArea(x[0], x[1], x[2]);
    for (int i = 0; i < 3; ++i) {
      const double r = (x[0][i] + x[1][i] + x[2][i]) / 3 - c[i];
      cx[label[e]] += A * r * e1[i], cy[label[e]] += A * r * e2[i];
    }
  }
  std::vector<int> order(count);
  for (int k = 0; k < count; ++k) order[k] = k;
  std::sort(order.begin(), order.end(), [&](int a, int b) { return std::atan2(cy[a], cx[a]) < std::atan2(cy[b], cx[b]); });
  const size_t first_note = notes->size();
  NameStrips(*s, label, order, {}, t, base, false, strips, notes);
  const double q0 = SmallestQuality(sub.coords, sub.triangles), q1 = SmallestQuality(s->coords, s->tris);
  notes->insert(notes->begin() + (long)std::min(first_note, notes->size()),
                "radial strips of " + base + ": rim " + Fmt("%.1f", rim) + " mm, " + std::to_string(n) +
                    " gores (rim arcs " + Fmt("%.1f", rim / n) + " mm, width " + Fmt("%g", o.width) +
                    " mm) round the middle node " + Fmt("(%.1f, %.1f, %.1f) mm", c[0], c[1], c[2]) + "; " +
                    std::to_string(s->NumNodes() - sub.NumNodes()) + " nodes added, smallest triangle quality " +
                    Fmt("%.3f", q1) + " (input " + Fmt("%.3f", q0) + "); seams: " + std::to_string(seams.relocated) +
                    " mesh nodes moved onto them (" + Fmt("%.3f", seams.relocated_max) + " mm at most), " +
                    std::to_string(seams.snapped) + " crossings taken to a node that could not move, seams within " +
                    Fmt("%.3f", seams.line_moved) + " mm of the traced lines, largest turn between seam segments " +
                    Fmt("%.3f", seams.max_turn * kDeg) + " deg; " +
                    Fmt("%.2f s", std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count()));
  return true;
}

// Cuts one surface (sub: its triangles as a mesh of their own; fixed: its nodes that must not
// move) into strips <base>_NN: *s the cut surface, *strips the triangles of s per strip.
bool CutOneSurface(const MeshData &sub, const std::string &base, const std::vector<char> &fixed,
                   const GeodesicCutOptions &o, const std::string &opt, int start_v, const double start_dir[3],
                   TriSurface *s,
                   std::vector<std::pair<std::string, std::vector<int>>> *strips, std::vector<std::string> *notes,
                   std::string *err) {
  const auto t0 = std::chrono::steady_clock::now();
  if (!SurfaceFromArrays(sub.coords, sub.triangles, s, err)) {
    *err = sub.source + ": " + *err;
    return false;
  }
  s->fixed = fixed;
  double h, centroid[3];
  MeanEdgeAndCentroid(*s, &h, centroid);
  if (o.width < h) {
    *err = opt + " mm is narrower than the elements of " + sub.source + " (mean edge " + Fmt("%.1f", h) +
           " mm): a strip needs a few elements across; refine the mesh or give a wider strip";
    return false;
  }
  LineInsertOptions io;
  io.relocate = o.snap;
  io.tol = o.tol >= 0 ? o.tol : 1e-3 * h;
  io.keep_quality = o.keep_quality;
  io.quality_floor = o.keep_quality * SmallestQuality(sub.coords, sub.triangles);
  // The middle: the interior node nearest the centroid, and the transverse direction there.
  // Or the start line's middle node and its direction there (-cutpattern_strip_start).
  Transverse t;
  t.vmid = start_v >= 0 ? start_v : InteriorNodeNearest(*s, centroid);
  if (t.vmid < 0) {
    *err = opt + ": " + sub.source + " has no interior node to start the cutting lines from; refine the mesh";
    return false;
  }
  for (int i = 0; i < 3; ++i) t.mid[i] = s->coords[3 * t.vmid + i];
  const std::string at_mid = Fmt("(%.1f, %.1f, %.1f) mm", t.mid[0], t.mid[1], t.mid[2]);
  const std::string start_opt = "-cutpattern_strip_start " + o.start_line;
  if (start_v >= 0 && SurfaceVertexOnBoundary(*s, start_v)) {
    *err = start_opt + ": its middle node " + at_mid + " lies on the boundary of " + sub.source +
           ": a seam starts inside the surface; give a line whose middle is inside it";
    return false;
  }
  if (start_v >= 0) {
    for (int i = 0; i < 3; ++i) t.axis[i] = start_dir[i];
  } else {
    t.axis[o.direction] = 1;
  }
  if (!TransverseDirection(*s, t.vmid, t.axis, t.dir)) {
    *err = (start_v >= 0 ? start_opt + ": the line's direction" : std::string("-cutpattern_strip_direction ") +
                                                                     kAxis[o.direction]) +
           " is (nearly) normal to " + sub.source + " at " + (start_v >= 0 ? "its middle node " : "its middle ") +
           at_mid + ": choose " + (start_v >= 0 ? "a line along the surface" : "an axis along the surface");
    return false;
  }
  // The transverse geodesic (on the uncut mesh) and the offsets of the lines on it.
  t.max_steps = 4 * s->NumTris() + 100;
  if (!TraceTransverse(*s, &t, err)) {
    *err = opt + ": the transverse geodesic through the middle: " + *err;
    return false;
  }
  if (!t.fwd.reached_boundary || !t.back.reached_boundary) {
    *err = opt + ": the transverse geodesic through the middle " + at_mid + " does not reach the boundary within " +
           std::to_string(t.max_steps) +
           " triangle crossings: it winds round the surface without ending (a tube or a closed surface across "
           "-cutpattern_strip_direction?): cut it open into a disc first, or choose another direction";
    return false;
  }
  const double across = t.fwd.length + t.back.length;
  if (o.width >= across && o.whole_if_narrow && o.layout != 2) {
    strips->push_back({base + "_01", {}});
    for (int e = 0; e < s->NumTris(); ++e) strips->back().second.push_back(e);
    notes->push_back(base + ": " + Fmt("%.1f", across) + " mm across along the geodesic through its middle, not "
                     "wider than the width " + Fmt("%.1f", o.width) + " mm: one strip " + base + "_01");
    return true;
  }
  if (o.width >= across && o.layout != 2) {
    *err = opt + " mm is wider than the surface: " + Fmt("%.1f", across) +
           " mm across along the geodesic through its middle; give a smaller width";
    return false;
  }
  if (o.layout == 2) return RadialStrips(sub, base, t, io, o, opt, s, strips, notes, err);
  std::vector<double> offsets;
  if (o.equal) {  // n strips of equal width on the transverse geodesic, n the fewest at most W wide
    const int n = (int)std::ceil(across / o.width - 1e-9);
    for (int k = 1; k < n; ++k) offsets.push_back(-t.back.length + k * across / n);
  } else {
    offsets = LineOffsets(o.width, t.fwd.length, t.back.length);
  }
  // Trace (or cut by planes) and insert the lines one by one.
  SeamStats seams;
  for (double off : offsets)
    if (!(o.layout == 1 ? InsertPlaneLine(s, t, off, io, opt, &seams, notes, err)
                        : InsertCuttingLine(s, t, off, io, opt, &seams, notes, err)))
      return false;
  // The strips: the pieces between the lines, in order across.
  std::vector<int> label;
  const int count = SurfaceComponents(*s, &label);
  if (o.layout == 0 && count != (int)offsets.size() + 1) {
    *err = opt + ": " + std::to_string(offsets.size()) + " cutting lines left " + std::to_string(count) +
           " pieces instead of " + std::to_string(offsets.size() + 1) + "; give another width or direction";
    return false;
  }
  const std::vector<int> order = PiecesAcross(*s, label, count, t);
  std::sort(offsets.begin(), offsets.end());
  const size_t first_note = notes->size();
  NameStrips(*s, label, order, offsets, t, base, o.layout == 0 && count == (int)offsets.size() + 1, strips, notes);
  const double q0 = SmallestQuality(sub.coords, sub.triangles), q1 = SmallestQuality(s->coords, s->tris);
  notes->insert(notes->begin() + (long)std::min(first_note, notes->size()),
                std::string(o.layout == 1 ? "planar" : "geodesic") + " strips of " + base + ": width " +
                    Fmt("%g", o.width) + " mm, lines along " +
                    (start_v >= 0 ? "the start line " + o.start_line + Fmt(" (%.4f, %.4f, %.4f)", t.axis[0], t.axis[1], t.axis[2])
                                  : std::string(kAxis[o.direction])) +
                    "; the transverse geodesic through the " + (start_v >= 0 ? "start line's " : "") + "middle node " +
                    at_mid + " is " +
                    Fmt("%.3f mm across (%.3f + %.3f)", across, t.back.length, t.fwd.length) + "; " +
                    std::to_string(offsets.size()) + " lines, " + std::to_string(count) + " strips; " +
                    std::to_string(s->NumNodes() - sub.NumNodes()) + " nodes added, " +
                    std::to_string(sub.NumElements()) + " -> " + std::to_string(s->NumTris()) +
                    " triangles, smallest triangle quality " + Fmt("%.3f", q1) + " (input " + Fmt("%.3f", q0) +
                    "); seams: " + std::to_string(seams.relocated) + " mesh nodes moved onto them (" +
                    Fmt("%.3f", seams.relocated_max) + " mm at most), " + std::to_string(seams.snapped) +
                    " crossings taken to a node that could not move, seams within " + Fmt("%.3f", seams.line_moved) +
                    " mm of the traced lines, largest turn between seam segments " +
                    Fmt("%.3f", seams.max_turn * kDeg) + " deg; " +
                    Fmt("%.2f s", std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count()));
  return true;
}

} // namespace

bool GeodesicCutStrips(MeshData *mesh, const GeodesicCutOptions &o, std::vector<std::string> *notes,
                       std::string *err) {
  const std::string opt = "-cutpattern_strip_width " + Fmt("%g", o.width);
  // The surfaces: each physical surface (but a group "all" of every triangle beside others), or
  // every triangle when there is none.
  std::vector<std::pair<std::string, std::vector<int>>> groups;
  for (const auto &kv : mesh->element_sets)
    if (!(kv.first == "all" && mesh->element_sets.size() > 1 && (int)kv.second.size() == mesh->NumElements()))
      groups.push_back(kv);
  if (groups.empty()) {
    groups.push_back({"strip", {}});
    for (int e = 0; e < mesh->NumElements(); ++e) groups[0].second.push_back(e);
  }
  const int nn = mesh->NumNodes();
  std::vector<int> owner(mesh->NumElements(), -1), users(nn, 0);
  for (size_t g = 0; g < groups.size(); ++g) {
    std::vector<char> mine(nn, 0);
    for (int e : groups[g].second) {
      if (owner[e] >= 0) {
        *err = opt + ": " + mesh->source + ": triangle " + std::to_string(e) + " is in the physical surfaces " +
               groups[owner[e]].first + " and " + groups[g].first + ": each triangle must be in one surface to cut";
        return false;
      }
      owner[e] = (int)g;
      for (int k = 0; k < 3; ++k) mine[mesh->triangles[3 * e + k]] = 1;
    }
    for (int n = 0; n < nn; ++n) users[n] += mine[n];
  }
  const int loose = (int)std::count(owner.begin(), owner.end(), -1);
  if (loose)
    notes->push_back(std::to_string(loose) + " triangles in no physical surface are left out of the strips");
  // Nodes that must not move onto a seam: those of named lines and those two surfaces share.
  std::vector<char> fixed(nn, 0);
  for (int n = 0; n < nn; ++n) fixed[n] = users[n] > 1;
  // (A node set named like a physical surface is that surface's nodes, which the reader adds: no line.)
  for (const auto &kv : mesh->node_sets)
    if (!mesh->element_sets.count(kv.first))
      for (int n : kv.second) fixed[n] = 1;
  int start_node = -1;
  double start_dir[3] = {0, 0, 0};
  if (!o.start_line.empty() && !StartLineMiddle(*mesh, o.start_line, &start_node, start_dir, err)) return false;
  bool started = false;
  MeshData out;
  out.source = mesh->source + " cut at " + Fmt("%g", o.width) + " mm";
  out.notes = mesh->notes;
  out.coords = mesh->coords;
  std::vector<std::vector<char>> in_set;  // per node set of the file, per node of out
  for (const auto &kv : mesh->node_sets) {
    in_set.emplace_back(nn, 0);
    for (int n : kv.second) in_set.back()[n] = 1;
  }
  for (const auto &g : groups) {
    const MeshData sub = ExtractStrip(*mesh, g.second, g.first);
    // ExtractStrip numbers nodes in order of first use: the same walk gives the global ids.
    std::vector<int> global;
    std::vector<char> seen(nn, 0);
    for (int e : g.second)
      for (int k = 0; k < 3; ++k) {
        const int n = mesh->triangles[3 * e + k];
        if (!seen[n]) seen[n] = 1, global.push_back(n);
      }
    std::vector<char> sub_fixed(global.size());
    for (size_t i = 0; i < global.size(); ++i) sub_fixed[i] = fixed[global[i]];
    TriSurface s;
    std::vector<std::pair<std::string, std::vector<int>>> strips;
    int start_v = -1;  // the start line's middle node, when it is one of this surface's
    for (size_t i = 0; i < global.size() && start_node >= 0 && !started; ++i)
      if (global[i] == start_node) start_v = (int)i, started = true;
    if (!CutOneSurface(sub, g.first, sub_fixed, o, opt, start_v, start_dir, &s, &strips, notes, err)) return false;
    for (int p = (int)global.size(); p < s.NumNodes(); ++p) {
      global.push_back(out.NumNodes());
      for (int i = 0; i < 3; ++i) out.coords.push_back(s.coords[3 * (size_t)p + i]);
      // A node put on an edge of a named line joins it.
      const auto &ab = s.new_node_edge[p - sub.NumNodes()];
      for (auto &in : in_set) in.push_back(in[global[ab.first]] && in[global[ab.second]]);
    }
    for (int p = 0; p < sub.NumNodes(); ++p)  // nodes moved onto a seam
      for (int i = 0; i < 3; ++i) out.coords[3 * (size_t)global[p] + i] = s.coords[3 * (size_t)p + i];
    const int e0 = out.NumElements();
    for (int v : s.tris) out.triangles.push_back(global[v]);
    for (auto &st : strips) {
      for (int &e : st.second) e += e0;
      out.element_sets[st.first] = st.second;
    }
  }
  // Only the nodes the strips use, in order.
  std::vector<int> id(out.NumNodes(), -1);
  MeshData packed;
  packed.source = out.source, packed.notes = out.notes, packed.element_sets = out.element_sets;
  for (int &v : out.triangles) {
    if (id[v] < 0) {
      id[v] = packed.NumNodes();
      for (int i = 0; i < 3; ++i) packed.coords.push_back(out.coords[3 * (size_t)v + i]);
    }
    packed.triangles.push_back(id[v]);
  }
  size_t k = 0;
  for (const auto &kv : mesh->node_sets) {
    std::vector<int> v;
    for (int n = 0; n < (int)in_set[k].size(); ++n)
      if (in_set[k][n] && id[n] >= 0) v.push_back(id[n]);
    std::sort(v.begin(), v.end());
    packed.node_sets[kv.first] = v;
    ++k;
  }
  if (start_node >= 0 && !started) {
    *err = "-cutpattern_strip_start " + o.start_line + ": its middle node is on no triangle of a physical surface "
           "that is cut; give a line on the surface to cut";
    return false;
  }
  *mesh = packed;
  return true;
}

} // namespace etfe
