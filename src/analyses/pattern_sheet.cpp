// The drawing of one strip (see etfe/analyses/pattern_sheet.h): outlines, the MD arrow and a label block
// placed where it crosses no outline, with the dimensions a fabricator checks on the table.
#include "etfe/analyses/pattern_sheet.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>

namespace etfe {
namespace {

const double kPi = 3.14159265358979323846;

std::string Fmt(const char *fmt, double a, double b = 0, double c = 0) {
  char buf[256];
  std::snprintf(buf, sizeof buf, fmt, a, b, c);
  return buf;
}

// Layer names: at most 31 of A-Z 0-9 _ - $, upper case (R12).
std::string LayerName(const std::string &name) {
  std::string s;
  for (char c : name) {
    const unsigned char u = (unsigned char)c;
    s += (std::isalnum(u) || c == '_' || c == '-' || c == '$') ? (char)std::toupper(u) : '_';
  }
  if (s.empty()) s = "LINE";
  return s.substr(0, 31);
}

// Named lines: cut_* red, weld_* blue, others green (ACI).
int LineColour(const std::string &name) {
  if (name.compare(0, 4, "cut_") == 0) return 1;
  if (name.compare(0, 5, "weld_") == 0) return 5;
  return 3;
}

bool InPolygon(const std::vector<double> &p, double x, double y) {
  bool in = false;
  const size_t n = p.size() / 2;
  for (size_t i = 0, j = n - 1; i < n; j = i++) {
    const double xi = p[2 * i], yi = p[2 * i + 1], xj = p[2 * j], yj = p[2 * j + 1];
    if ((yi > y) != (yj > y) && x < (xj - xi) * (y - yi) / (yj - yi) + xi) in = !in;
  }
  return in;
}

// Liang-Barsky: does the segment a-b meet the box?
bool SegmentMeetsBox(const double *a, const double *b, const double box[4]) {
  // Both ends beyond one side: the common case when a label box is tried against a long outline
  // (a strip of 6525 nodes spent 26 % of a pattern run's instructions here without it).
  for (int k = 0; k < 2; ++k)
    if ((a[k] < box[k] && b[k] < box[k]) || (a[k] > box[k + 2] && b[k] > box[k + 2])) return false;
  double t0 = 0, t1 = 1;
  const double d[2] = {b[0] - a[0], b[1] - a[1]};
  for (int k = 0; k < 2; ++k) {
    const double lo = box[k], hi = box[k + 2];
    if (std::fabs(d[k]) < 1e-300) {
      if (a[k] < lo || a[k] > hi) return false;
      continue;
    }
    double ta = (lo - a[k]) / d[k], tb = (hi - a[k]) / d[k];
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta), t1 = std::min(t1, tb);
    if (t0 > t1) return false;
  }
  return true;
}

bool BoxesMeet(const double *a, const double *b) {
  return a[0] <= b[2] && b[0] <= a[2] && a[1] <= b[3] && b[1] <= a[3];
}

bool BoxClear(const double box[4], const std::vector<double> *inside, const std::vector<const SheetPolyline *> &polys,
              const std::vector<double> &avoid) {
  // The cheap tests first: the boxes to avoid, then the lines, then the corners inside.
  for (size_t k = 0; k + 3 < avoid.size(); k += 4)
    if (BoxesMeet(box, &avoid[k])) return false;
  for (const SheetPolyline *p : polys)
    if (BoxCrossesPolyline(box, *p)) return false;
  if (inside) {
    const double c[8] = {box[0], box[1], box[2], box[1], box[2], box[3], box[0], box[3]};
    for (int k = 0; k < 4; ++k)
      if (!InPolygon(*inside, c[2 * k], c[2 * k + 1])) return false;
  }
  return true;
}

std::vector<double> LoopPoints(const FlattenResult &r, const std::vector<int> &loop) {
  std::vector<double> pts;
  for (int v : loop) pts.push_back(r.xy[2 * (size_t)v]), pts.push_back(r.xy[2 * (size_t)v + 1]);
  return pts;
}

} // namespace

void TextBox(const SheetText &t, double box[4]) {
  box[0] = t.x, box[1] = t.y - 0.35 * t.h;
  box[2] = t.x + t.h * (double)t.text.size(), box[3] = t.y + 1.2 * t.h;
}

void SheetExtent(Sheet *s) {
  double lo[2] = {HUGE_VAL, HUGE_VAL}, hi[2] = {-HUGE_VAL, -HUGE_VAL};
  auto add = [&](double x, double y) {
    lo[0] = std::min(lo[0], x), lo[1] = std::min(lo[1], y), hi[0] = std::max(hi[0], x), hi[1] = std::max(hi[1], y);
  };
  for (const SheetPolyline &p : s->lines)
    for (size_t k = 0; k + 1 < p.pts.size(); k += 2) add(p.pts[k], p.pts[k + 1]);
  for (const SheetText &t : s->texts) {
    double b[4];
    TextBox(t, b);
    add(b[0], b[1]), add(b[2], b[3]);
  }
  if (!(lo[0] <= hi[0])) lo[0] = lo[1] = hi[0] = hi[1] = 0;
  for (int k = 0; k < 2; ++k) s->lo[k] = lo[k], s->hi[k] = hi[k];
}

void SheetLayer(Sheet *s, const std::string &name, int aci) {
  for (const auto &l : s->layers)
    if (l.first == name) return;
  s->layers.push_back({name, aci});
}

bool BoxCrossesPolyline(const double box[4], const SheetPolyline &p) {
  const size_t n = p.pts.size() / 2;
  for (size_t k = 0; k + 1 < n + (p.closed ? 1 : 0); ++k)
    if (SegmentMeetsBox(&p.pts[2 * k], &p.pts[2 * ((k + 1) % n)], box)) return true;
  return n == 1 && SegmentMeetsBox(&p.pts[0], &p.pts[0], box);
}

std::vector<int> PatternCorners(const FlattenResult &r, double min_turn_deg) {
  std::vector<int> c;
  if (r.outline.empty()) return c;
  const std::vector<int> &loop = r.outline[0];
  const size_t n = loop.size();
  for (size_t k = 0; k < n; ++k) {
    const double *p = &r.xy[2 * (size_t)loop[(k + n - 1) % n]], *q = &r.xy[2 * (size_t)loop[k]],
                 *s = &r.xy[2 * (size_t)loop[(k + 1) % n]];
    const double a = std::atan2(q[1] - p[1], q[0] - p[0]), b = std::atan2(s[1] - q[1], s[0] - q[0]);
    double turn = std::fabs(b - a) * 180.0 / kPi;
    if (turn > 180.0) turn = 360.0 - turn;
    if (turn > min_turn_deg) c.push_back((int)k);
  }
  return c;
}

std::vector<std::vector<int>> PatternEdges(const FlattenResult &r, const std::vector<int> &corners) {
  std::vector<std::vector<int>> edges;
  if (r.outline.empty()) return edges;
  const std::vector<int> &loop = r.outline[0];
  const size_t n = loop.size();
  if (corners.empty()) {
    edges.push_back(loop);
    edges.back().push_back(loop[0]);
    return edges;
  }
  for (size_t k = 0; k < corners.size(); ++k) {
    const size_t a = (size_t)corners[k], b = (size_t)corners[(k + 1) % corners.size()];
    std::vector<int> e{loop[a]};
    for (size_t j = (a + 1) % n;; j = (j + 1) % n) {
      e.push_back(loop[j]);
      if (j == b) break;
    }
    edges.push_back(e);
  }
  return edges;
}

std::string CornerName(int k) {
  std::string s(1, (char)('A' + k % 26));
  if (k >= 26) s += std::to_string(k / 26);
  return s;
}

bool PlaceBox(const std::vector<double> &inside, const std::vector<const SheetPolyline *> &polys,
              const std::vector<double> &avoid, double bw, double bh, double cx, double cy, double *x, double *y) {
  double lo[2] = {HUGE_VAL, HUGE_VAL}, hi[2] = {-HUGE_VAL, -HUGE_VAL};
  for (size_t k = 0; k + 1 < inside.size(); k += 2)
    for (int i = 0; i < 2; ++i) lo[i] = std::min(lo[i], inside[k + i]), hi[i] = std::max(hi[i], inside[k + i]);
  if (hi[0] - lo[0] < bw || hi[1] - lo[1] < bh) return false;
  // Lower-left corners on a 41 x 41 grid over the room left, nearest to the centre first.
  const int N = 40;
  std::vector<std::pair<double, std::pair<double, double>>> cand;
  for (int i = 0; i <= N; ++i)
    for (int j = 0; j <= N; ++j) {
      const double px = lo[0] + (hi[0] - lo[0] - bw) * i / N, py = lo[1] + (hi[1] - lo[1] - bh) * j / N;
      cand.push_back({std::hypot(px + 0.5 * bw - cx, py + 0.5 * bh - cy), {px, py}});
    }
  std::sort(cand.begin(), cand.end());
  for (const auto &c : cand) {
    const double box[4] = {c.second.first, c.second.second, c.second.first + bw, c.second.second + bh};
    if (BoxClear(box, &inside, polys, avoid)) {
      *x = box[0], *y = box[1];
      return true;
    }
  }
  return false;
}

Sheet PatternSheet(const FlattenResult &r, const std::string &name, const PatternDrawing &d) {
  Sheet s;
  s.title = name;
  for (const auto &l : std::vector<std::pair<std::string, int>>{{"0", 7}, {"OUTLINE", 7}, {"WELD", 5}})
    SheetLayer(&s, l.first, l.second);
  if (d.md_mark) SheetLayer(&s, "MD", 30);
  if (d.labels) SheetLayer(&s, "TEXT", 8);
  for (const auto &loop : r.outline) s.lines.push_back({"WELD", LoopPoints(r, loop), true});
  for (const auto &loop : r.outline)
    s.lines.push_back({"OUTLINE", d.seam_allowance > 0 ? OffsetOutline(r, loop, d.seam_allowance) : LoopPoints(r, loop),
                       true});
  for (const PatternLine &l : r.lines) {
    SheetLayer(&s, LayerName(l.name), LineColour(l.name));
    for (std::vector<int> p : l.paths) {
      const bool closed = p.size() > 1 && p.front() == p.back();
      if (closed) p.pop_back();
      s.lines.push_back({LayerName(l.name), LoopPoints(r, p), closed});
    }
  }
  SheetExtent(&s);
  const double size = std::max(s.hi[0] - s.lo[0], s.hi[1] - s.lo[1]);
  const double h = std::max(2.5, 0.012 * size);
  s.text_height = h;
  double centre[2], dir[2], extent;
  PatternLongAxis(r, centre, dir, &extent);
  std::vector<double> avoid;  // boxes of the MD arrow and the texts placed so far, 0.5 h around
  auto keep_clear = [&](const double *b) {
    for (int k = 0; k < 4; ++k) avoid.push_back(b[k] + (k < 2 ? -0.5 * h : 0.5 * h));
  };
  if (d.md_mark) {
    const double half = 0.25 * extent, hh = 0.04 * extent;
    const double tip[2] = {centre[0] + half * dir[0], centre[1] + half * dir[1]};
    s.lines.push_back({"MD", {centre[0] - half * dir[0], centre[1] - half * dir[1], tip[0], tip[1]}, false});
    s.lines.push_back({"MD",
                       {tip[0] - hh * dir[0] - 0.5 * hh * dir[1], tip[1] - hh * dir[1] + 0.5 * hh * dir[0], tip[0],
                        tip[1], tip[0] - hh * dir[0] + 0.5 * hh * dir[1], tip[1] - hh * dir[1] - 0.5 * hh * dir[0]},
                       false});
    s.texts.push_back({"MD", "MD", centre[0] - h, centre[1] + 0.5 * h, h});
    for (size_t k = s.lines.size() - 2; k < s.lines.size(); ++k) {
      double b[4] = {HUGE_VAL, HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
      for (size_t j = 0; j + 1 < s.lines[k].pts.size(); j += 2)
        for (int i = 0; i < 2; ++i)
          b[i] = std::min(b[i], s.lines[k].pts[j + i]), b[i + 2] = std::max(b[i + 2], s.lines[k].pts[j + i]);
      keep_clear(b);
    }
    double b[4];
    TextBox(s.texts.back(), b);
    keep_clear(b);
  }
  if (!d.labels) {
    SheetExtent(&s);
    return s;
  }
  std::vector<const SheetPolyline *> polys;  // what labels must not cross (s.lines is complete now)
  for (const SheetPolyline &p : s.lines)
    if (p.layer != "MD") polys.push_back(&p);
  const std::vector<double> net = LoopPoints(r, r.outline[0]);
  // Corner letters inside each corner, along its bisector, as near as they stay clear.
  const std::vector<int> corners = PatternCorners(r);
  const std::vector<int> &loop = r.outline[0];
  const size_t n = loop.size();
  for (size_t k = 0; k < corners.size(); ++k) {
    const size_t i = (size_t)corners[k];
    const double *p = &r.xy[2 * (size_t)loop[(i + n - 1) % n]], *q = &r.xy[2 * (size_t)loop[i]],
                 *t = &r.xy[2 * (size_t)loop[(i + 1) % n]];
    double a[2] = {p[0] - q[0], p[1] - q[1]}, b[2] = {t[0] - q[0], t[1] - q[1]};
    const double la = std::hypot(a[0], a[1]), lb = std::hypot(b[0], b[1]);
    double m[2] = {a[0] / la + b[0] / lb, a[1] / la + b[1] / lb};
    const double lm = std::hypot(m[0], m[1]);
    if (lm < 1e-9) m[0] = -a[1] / la, m[1] = a[0] / la;  // straight: the inward normal (interior on the left)
    else m[0] /= lm, m[1] /= lm;
    SheetText c{"TEXT", CornerName((int)k), 0, 0, h};
    for (double f : {1.0, 1.5, 2.0, 3.0, 4.5, 6.0}) {
      const double w = h * (double)c.text.size();
      c.x = q[0] + f * h * m[0] - 0.5 * w, c.y = q[1] + f * h * m[1] - 0.4 * h;
      double box[4];
      TextBox(c, box);
      if (BoxClear(box, &net, polys, avoid)) {
        s.texts.push_back(c);
        keep_clear(box);
        break;
      }
    }
  }
  // The label block.
  double lo[2] = {HUGE_VAL, HUGE_VAL}, hi[2] = {-HUGE_VAL, -HUGE_VAL};
  for (size_t k = 0; k + 1 < net.size(); k += 2)
    for (int i = 0; i < 2; ++i) lo[i] = std::min(lo[i], net[k + i]), hi[i] = std::max(hi[i], net[k + i]);
  std::vector<std::string> block{name + " (units mm, 1:1)",
                                 Fmt("length %.1f x width %.1f (box along/across MD)", hi[0] - lo[0], hi[1] - lo[1])};
  if (d.seam_allowance > 0) block.push_back(Fmt("cut line %.1f outside the weld line", d.seam_allowance));
  const std::vector<std::vector<int>> edges = PatternEdges(r, corners);
  auto arc = [&](const std::vector<int> &e) {
    double L = 0;
    for (size_t j = 0; j + 1 < e.size(); ++j)
      L += std::hypot(r.xy[2 * (size_t)e[j + 1]] - r.xy[2 * (size_t)e[j]],
                      r.xy[2 * (size_t)e[j + 1] + 1] - r.xy[2 * (size_t)e[j] + 1]);
    return L;
  };
  for (size_t k = 0; k < edges.size(); ++k)
    block.push_back(corners.empty() ? Fmt("edge (the whole outline) %.1f", arc(edges[k]))
                                    : "edge " + CornerName((int)k) + "-" +
                                          CornerName((int)((k + 1) % corners.size())) + Fmt(" %.1f", arc(edges[k])));
  // Diagonals between the four sharpest corners (in their order along the outline).
  if (corners.size() >= 4) {
    std::vector<std::pair<double, int>> sharp;
    for (size_t k = 0; k < corners.size(); ++k) {
      const size_t i = (size_t)corners[k];
      const double *p = &r.xy[2 * (size_t)loop[(i + n - 1) % n]], *q = &r.xy[2 * (size_t)loop[i]],
                   *t = &r.xy[2 * (size_t)loop[(i + 1) % n]];
      const double ang = std::fabs(std::remainder(
          std::atan2(t[1] - q[1], t[0] - q[0]) - std::atan2(q[1] - p[1], q[0] - p[0]), 2 * kPi));
      sharp.push_back({-ang, (int)k});
    }
    std::sort(sharp.begin(), sharp.end());
    std::vector<int> four;
    for (int k = 0; k < 4; ++k) four.push_back(sharp[k].second);
    std::sort(four.begin(), four.end());
    for (int k = 0; k < 2; ++k) {
      const double *a = &r.xy[2 * (size_t)loop[corners[four[k]]]], *b = &r.xy[2 * (size_t)loop[corners[four[k + 2]]]];
      block.push_back("diagonal " + CornerName(four[k]) + "-" + CornerName(four[k + 2]) +
                      Fmt(" %.1f", std::hypot(b[0] - a[0], b[1] - a[1])));
    }
  }
  for (const PatternLine &l : r.lines)
    block.push_back(l.name + Fmt(" %.1f (3D %.1f, %+.3f %%)", l.length2d, l.length3d,
                                 std::fabs(l.expansion_pct) < 5e-4 ? 0.0 : l.expansion_pct));  // no "-0.000"
  size_t chars = 0;
  for (const std::string &b : block) chars = std::max(chars, b.size());
  // Inside the pattern (on the film), smaller text if it must (not below 2.5 mm); else above it.
  double x = 0, y = 0, th = h;
  bool inside = false;
  for (double f : {1.0, 0.75, 0.5, 0.35}) {
    th = f * h;
    if (th < 2.5 && f < 1.0) break;
    const double bw = th * (double)(chars + 1), bh = 1.6 * th * (double)block.size() + th;
    if ((inside = PlaceBox(net, polys, avoid, bw, bh, centre[0], centre[1], &x, &y))) break;
  }
  if (!inside) {  // above the drawing, clear of everything
    th = h;
    SheetExtent(&s);
    x = s.lo[0], y = s.hi[1] + h;
  }
  const double step = 1.6 * th, bh = step * (double)block.size() + th;
  for (size_t k = 0; k < block.size(); ++k)
    s.texts.push_back({"TEXT", block[k], x + 0.5 * th, y + bh - 1.7 * th - step * (double)k, th});
  SheetExtent(&s);
  return s;
}

SheetPage::SheetPage(const Sheet &s) {
  w = s.hi[0] - s.lo[0], hgt = s.hi[1] - s.lo[1];
  const double size = std::max(w, hgt);
  margin = std::max(10.0, 0.03 * size), h = s.text_height;
  line = std::max(0.25, 0.001 * size);
  W = w + 2 * margin, H = hgt + 2 * margin + 4 * h;
}

double NiceLength(double x) {
  const double p = std::pow(10.0, std::floor(std::log10(x)));
  for (double f : {5.0, 2.0, 1.0})
    if (f * p <= x) return f * p;
  return p;
}

} // namespace etfe
