// Cutting-pattern export (SPEC §7: "fabricators cut from DXF (or SVG)"; thesis Fig. 2.10 reports
// each line's length and its expansion against 3D).
//
// DXF: ASCII R12 (AC1009), the oldest version every CAD program and plotter driver reads. It has
// no LWPOLYLINE, so outlines are POLYLINE/VERTEX/SEQEND with the closed flag (70 = 1). The
// TABLES section defines the layers (with colours), the CONTINUOUS line type they name and the
// STANDARD text style the labels use, so strict readers find every referenced table entry.
// Drawing units are mm (R12 has no units variable). SVG: width/height in mm with a viewBox in
// mm, so 1 user unit = 1 mm at print; y is flipped to keep the DXF's orientation (y up).
#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "etfe/flatten_strip.h"

namespace etfe {
namespace {

void Append(std::string *s, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
void Append(std::string *s, const char *fmt, ...) {
  char buf[512];
  va_list ap;
  va_start(ap, fmt);
  const int n = std::vsnprintf(buf, sizeof buf, fmt, ap);
  va_end(ap);
  if (n < (int)sizeof buf) {
    s->append(buf, n > 0 ? (size_t)n : 0);
    return;
  }
  std::vector<char> big((size_t)n + 1);
  va_start(ap, fmt);
  std::vsnprintf(big.data(), big.size(), fmt, ap);
  va_end(ap);
  s->append(big.data(), (size_t)n);
}

bool WriteFile(const std::string &path, const std::string &text, std::string *err) {
  std::FILE *f = std::fopen(path.c_str(), "wb");
  if (!f) {
    if (err) *err = "cannot open '" + path + "' for writing: " + std::strerror(errno);
    return false;
  }
  const bool ok = std::fwrite(text.data(), 1, text.size(), f) == text.size();
  const bool closed = std::fclose(f) == 0;
  if (!ok || !closed) {
    if (err) *err = "writing '" + path + "' failed: " + std::strerror(errno);
    return false;
  }
  return true;
}

// Line class by set name: cut lines red, weld lines blue, others green (ACI colours and RGB).
int LineKind(const std::string &name) {
  if (name.compare(0, 4, "cut_") == 0) return 0;
  if (name.compare(0, 5, "weld_") == 0) return 1;
  return 2;
}
const int kAci[3] = {1, 5, 3};
const char *const kRgb[3] = {"#d00000", "#0040d0", "#008000"};

// R12 layer names: at most 31 of A-Z 0-9 _ - $, upper case.
std::string LayerName(const std::string &name) {
  std::string s;
  for (char c : name) {
    const unsigned char u = (unsigned char)c;
    s += (std::isalnum(u) || c == '_' || c == '-' || c == '$') ? (char)std::toupper(u) : '_';
  }
  if (s.empty()) s = "LINE";
  return s.substr(0, 31);
}

// Text values: printable ASCII only, and no "%%" (a DXF control-code prefix).
std::string DxfText(const std::string &t) {
  std::string s;
  for (char c : t) {
    const unsigned char u = (unsigned char)c;
    if (u < 32 || u > 126 || (c == '%' && !s.empty() && s.back() == '%')) continue;
    s += c;
  }
  return s;
}

std::string XmlEscape(const std::string &t) {
  std::string s;
  for (char c : t) {
    switch (c) {
    case '&': s += "&amp;"; break;
    case '<': s += "&lt;"; break;
    case '>': s += "&gt;"; break;
    case '"': s += "&quot;"; break;
    default:
      if ((unsigned char)c >= 32 || c == '\t') s += c;
    }
  }
  return s;
}

std::string XmlId(const std::string &t) {
  std::string s;
  for (char c : t) s += std::isalnum((unsigned char)c) || c == '_' || c == '-' ? c : '_';
  return s;
}

// RFC 4180 quoting for names that hold a separator or a quote.
std::string CsvField(const std::string &t) {
  if (t.find_first_of(",\"\r\n") == std::string::npos) return t;
  std::string s = "\"";
  for (char c : t) s += c == '"' ? std::string("\"\"") : std::string(1, c);
  return s + "\"";
}

struct Box {
  double lo[2] = {HUGE_VAL, HUGE_VAL}, hi[2] = {-HUGE_VAL, -HUGE_VAL};
  double Size() const { return std::max(hi[0] - lo[0], hi[1] - lo[1]); }
};

Box Bounds(const FlattenResult &r) {
  Box b;
  for (size_t i = 0; i + 1 < r.xy.size(); i += 2)
    for (int k = 0; k < 2; ++k) {
      b.lo[k] = std::min(b.lo[k], r.xy[i + k]);
      b.hi[k] = std::max(b.hi[k], r.xy[i + k]);
    }
  return b;
}

bool CheckResult(const FlattenResult &r, const std::string &path, std::string *err) {
  if (r.xy.empty() || r.outline.empty()) {
    if (err) *err = "'" + path + "': the flattening result is empty (FlattenStrip failed?)";
    return false;
  }
  return true;
}

std::string LineLabel(const PatternLine &l) {
  char b[256];
  std::snprintf(b, sizeof b, "%s %.1f mm (3D %.1f mm, %+.3f %%)", l.name.c_str(), l.length2d,
                l.length3d, l.expansion_pct);
  return b;
}

// Label placement: centred on the middle vertex of the line's longest piece, along the line
// there, turned to read left to right (angle in (-90, 90] degrees, counter-clockwise).
struct Label {
  double x, y, deg;
};
Label LabelAt(const FlattenResult &r, const PatternLine &l) {
  size_t best = 0;
  for (size_t k = 1; k < l.paths.size(); ++k)
    if (l.paths[k].size() > l.paths[best].size()) best = k;
  const std::vector<int> &p = l.paths[best];
  const size_t k = p.size() / 2;
  const double *m = &r.xy[2 * (size_t)p[k]];
  const double *a = &r.xy[2 * (size_t)p[k > 0 ? k - 1 : 0]];
  const double *b = &r.xy[2 * (size_t)p[k + 1 < p.size() ? k + 1 : k]];
  double deg = std::atan2(b[1] - a[1], b[0] - a[0]) * 180.0 / 3.14159265358979323846;
  if (deg > 90.0) deg -= 180.0;
  if (deg <= -90.0) deg += 180.0;
  return {m[0], m[1], deg};
}

// ---- DXF ----------------------------------------------------------------------------------------

void Pair(std::string *s, int code, const std::string &v) {
  Append(s, "%3d\n%s\n", code, v.c_str());
}
void Pair(std::string *s, int code, int v) { Append(s, "%3d\n%6d\n", code, v); }
void Pair(std::string *s, int code, double v) { Append(s, "%3d\n%.6f\n", code, v); }

void DxfLayer(std::string *s, const std::string &name, int color) {
  Pair(s, 0, "LAYER");
  Pair(s, 2, name);
  Pair(s, 70, 0);
  Pair(s, 62, color);
  Pair(s, 6, "CONTINUOUS");
}

// A polyline from node ids; closed when the path repeats its first node at the end (the repeat
// is dropped: the flag closes it).
// A POLYLINE through points (2 per point).
void DxfPolylinePoints(std::string *s, const std::string &layer, const std::vector<double> &pts, bool closed) {
  Pair(s, 0, "POLYLINE");
  Pair(s, 8, layer);
  Pair(s, 66, 1);  // vertices follow
  Pair(s, 10, 0.0);
  Pair(s, 20, 0.0);
  Pair(s, 30, 0.0);
  Pair(s, 70, closed ? 1 : 0);
  for (size_t k = 0; k + 1 < pts.size(); k += 2) {
    Pair(s, 0, "VERTEX");
    Pair(s, 8, layer);
    Pair(s, 10, pts[k]);
    Pair(s, 20, pts[k + 1]);
    Pair(s, 30, 0.0);
  }
  Pair(s, 0, "SEQEND");
  Pair(s, 8, layer);
}

void DxfPolyline(std::string *s, const std::string &layer, const FlattenResult &r,
                 std::vector<int> ids, bool closed) {
  if (ids.size() > 1 && ids.front() == ids.back()) {
    ids.pop_back();
    closed = true;
  }
  std::vector<double> pts;
  for (int v : ids) pts.push_back(r.xy[2 * (size_t)v]), pts.push_back(r.xy[2 * (size_t)v + 1]);
  DxfPolylinePoints(s, layer, pts, closed);
}

// The MD arrow: a shaft along the long axis over half the extent and a head at its end (2 per
// point, as two polylines: shaft, head).
void MdArrow(const FlattenResult &r, std::vector<double> *shaft, std::vector<double> *head, double *x, double *y) {
  double c[2], d[2], extent;
  PatternLongAxis(r, c, d, &extent);
  const double half = 0.25 * extent, h = 0.04 * extent;
  const double tip[2] = {c[0] + half * d[0], c[1] + half * d[1]};
  *shaft = {c[0] - half * d[0], c[1] - half * d[1], tip[0], tip[1]};
  *head = {tip[0] - h * d[0] - 0.5 * h * d[1], tip[1] - h * d[1] + 0.5 * h * d[0], tip[0], tip[1],
           tip[0] - h * d[0] + 0.5 * h * d[1], tip[1] - h * d[1] - 0.5 * h * d[0]};
  *x = c[0] - 0.5 * h * d[1], *y = c[1] + 0.5 * h * d[0];
}

// TEXT; centred (72 = 1) texts need the alignment point 11/21/31 as well.
void DxfTextEntity(std::string *s, double x, double y, double h, double deg, bool centred,
                   const std::string &text) {
  Pair(s, 0, "TEXT");
  Pair(s, 8, "LABELS");
  Pair(s, 10, x);
  Pair(s, 20, y);
  Pair(s, 30, 0.0);
  Pair(s, 40, h);
  Pair(s, 1, DxfText(text));
  if (deg != 0.0) Pair(s, 50, deg);
  if (centred) {
    Pair(s, 72, 1);
    Pair(s, 11, x);
    Pair(s, 21, y);
    Pair(s, 31, 0.0);
  }
}

// The HEADER section: DXF R12, the drawing's extent (with room for the title label).
void DxfHeader(std::string *s, const Box &b, double label_room) {
  Pair(s, 0, "SECTION");
  Pair(s, 2, "HEADER");
  Pair(s, 9, "$ACADVER");
  Pair(s, 1, "AC1009");
  Pair(s, 9, "$INSBASE");
  Pair(s, 10, 0.0);
  Pair(s, 20, 0.0);
  Pair(s, 30, 0.0);
  Pair(s, 9, "$EXTMIN");
  Pair(s, 10, b.lo[0]);
  Pair(s, 20, b.lo[1]);
  Pair(s, 30, 0.0);
  Pair(s, 9, "$EXTMAX");
  Pair(s, 10, b.hi[0]);
  Pair(s, 20, b.hi[1] + label_room);
  Pair(s, 30, 0.0);
  Pair(s, 0, "ENDSEC");
}

// Layers (name, colour): 0 (always present), OUTLINE, one per named line, LABELS.
std::vector<std::pair<std::string, int>> DxfLayers(const FlattenResult &r, const PatternDrawing &d) {
  const bool labels = d.labels;
  std::vector<std::pair<std::string, int>> layers = {{"0", 7}, {"OUTLINE", 7}};
  if (d.seam_allowance > 0) layers.push_back({"SEAM", 6});
  if (d.md_mark) layers.push_back({"MD", 30});
  for (const PatternLine &l : r.lines) {
    const std::string name = LayerName(l.name);
    bool have = false;
    for (const auto &ly : layers) have = have || ly.first == name;
    if (!have) layers.push_back({name, kAci[LineKind(l.name)]});
  }
  if (labels) layers.push_back({"LABELS", 8});
  return layers;
}

// The head of a TABLE of `count` entries.
void DxfTableHead(std::string *s, const char *name, int count) {
  Pair(s, 0, "TABLE");
  Pair(s, 2, name);
  Pair(s, 70, count);
}

// The TABLES section: the continuous line type, the layers and the text style of height h.
void DxfTables(std::string *s, const std::vector<std::pair<std::string, int>> &layers, double h) {
  Pair(s, 0, "SECTION");
  Pair(s, 2, "TABLES");
  DxfTableHead(s, "LTYPE", 1);
  Pair(s, 0, "LTYPE");
  Pair(s, 2, "CONTINUOUS");
  Pair(s, 70, 0);
  Pair(s, 3, "Solid line");
  Pair(s, 72, 65);
  Pair(s, 73, 0);
  Pair(s, 40, 0.0);
  Pair(s, 0, "ENDTAB");
  DxfTableHead(s, "LAYER", (int)layers.size());
  for (const auto &ly : layers) DxfLayer(s, ly.first, ly.second);
  Pair(s, 0, "ENDTAB");
  DxfTableHead(s, "STYLE", 1);
  Pair(s, 0, "STYLE");
  Pair(s, 2, "STANDARD");
  Pair(s, 70, 0);
  Pair(s, 40, 0.0);
  Pair(s, 41, 1.0);
  Pair(s, 50, 0.0);
  Pair(s, 71, 0);
  Pair(s, 42, h);
  Pair(s, 3, "txt");
  Pair(s, 4, "");
  Pair(s, 0, "ENDTAB");
  Pair(s, 0, "ENDSEC");
}

} // namespace

bool WritePatternDxf(const std::string &path, const FlattenResult &r, const std::string &strip_name,
                     const PatternDrawing &drawing, std::string *err) {
  const bool labels = drawing.labels;
  if (!CheckResult(r, path, err)) return false;
  Box b = Bounds(r);
  for (int k = 0; k < 2; ++k) b.lo[k] -= drawing.seam_allowance, b.hi[k] += drawing.seam_allowance;
  const double h = std::max(2.5, 0.012 * b.Size());  // label height, mm
  std::string s;
  Pair(&s, 999, DxfText("cutting pattern " + strip_name + " (etfe, units mm)"));
  DxfHeader(&s, b, labels ? 2.0 * h : 0.0);
  DxfTables(&s, DxfLayers(r, drawing), h);

  Pair(&s, 0, "SECTION");
  Pair(&s, 2, "ENTITIES");
  for (const auto &loop : r.outline) DxfPolyline(&s, "OUTLINE", r, loop, true);
  if (drawing.seam_allowance > 0)
    for (const auto &loop : r.outline) DxfPolylinePoints(&s, "SEAM", OffsetOutline(r, loop, drawing.seam_allowance), true);
  for (const PatternLine &l : r.lines)
    for (const auto &p : l.paths) DxfPolyline(&s, LayerName(l.name), r, p, false);
  if (drawing.md_mark) {
    std::vector<double> shaft, head;
    double x, y;
    MdArrow(r, &shaft, &head, &x, &y);
    DxfPolylinePoints(&s, "MD", shaft, false);
    DxfPolylinePoints(&s, "MD", head, false);
    DxfTextEntity(&s, x, y, h, 0.0, true, "MD");
  }
  if (labels) {
    DxfTextEntity(&s, b.lo[0], b.hi[1] + h, h, 0.0, false, strip_name);
    for (const PatternLine &l : r.lines) {
      const Label lb = LabelAt(r, l);
      DxfTextEntity(&s, lb.x, lb.y, h, lb.deg, true, LineLabel(l));
    }
  }
  Pair(&s, 0, "ENDSEC");
  Pair(&s, 0, "EOF");
  return WriteFile(path, s, err);
}

bool WritePatternSvg(const std::string &path, const FlattenResult &r, const std::string &strip_name,
                     const PatternDrawing &drawing, std::string *err) {
  const bool labels = drawing.labels;
  if (!CheckResult(r, path, err)) return false;
  Box b = Bounds(r);
  for (int k = 0; k < 2; ++k) b.lo[k] -= drawing.seam_allowance, b.hi[k] += drawing.seam_allowance;
  const double size = b.Size();
  const double margin = std::max(10.0, 0.03 * size);
  const double h = std::max(2.5, 0.012 * size);
  const double sw = std::max(0.25, 0.001 * size);  // stroke width, mm
  const double W = b.hi[0] - b.lo[0] + 2 * margin;
  const double H = b.hi[1] - b.lo[1] + 2 * margin + (labels ? 2 * h : 0.0);
  const double top = b.hi[1] + (labels ? 2 * h : 0.0);
  auto X = [&](double x) { return margin + x - b.lo[0]; };
  auto Y = [&](double y) { return margin + top - y; };
  std::string s;
  Append(&s, "<?xml version=\"1.0\" encoding=\"UTF-8\" standalone=\"no\"?>\n");
  Append(&s,
         "<svg xmlns=\"http://www.w3.org/2000/svg\" version=\"1.1\" width=\"%.3fmm\" "
         "height=\"%.3fmm\" viewBox=\"0 0 %.3f %.3f\">\n",
         W, H, W, H);
  Append(&s, "<title>%s</title>\n", XmlEscape(strip_name).c_str());
  Append(&s, "<desc>Cutting pattern, 1 user unit = 1 mm, y up as in the DXF</desc>\n");
  Append(&s, "<g id=\"outline\" fill=\"none\" stroke=\"#000000\" stroke-width=\"%.3f\" "
             "stroke-linejoin=\"round\">\n", sw);
  for (const auto &loop : r.outline) {
    s += "<path d=\"";
    for (size_t k = 0; k < loop.size(); ++k) {
      const double *p = &r.xy[2 * (size_t)loop[k]];
      Append(&s, "%s%.4f,%.4f ", k == 0 ? "M " : (k == 1 ? "L " : ""), X(p[0]), Y(p[1]));
    }
    s += "Z\"/>\n";
  }
  s += "</g>\n";
  auto svg_path = [&](const std::vector<double> &pts, bool closed) {
    s += "<path d=\"";
    for (size_t k = 0; k + 1 < pts.size(); k += 2)
      Append(&s, "%s%.4f,%.4f ", k == 0 ? "M " : (k == 2 ? "L " : ""), X(pts[k]), Y(pts[k + 1]));
    s += closed ? "Z\"/>\n" : "\"/>\n";
  };
  if (drawing.seam_allowance > 0) {
    Append(&s, "<g id=\"seam\" fill=\"none\" stroke=\"#cc00cc\" stroke-width=\"%.3f\" stroke-dasharray=\"%.3f %.3f\">\n",
           sw, 6 * sw, 3 * sw);
    for (const auto &loop : r.outline) svg_path(OffsetOutline(r, loop, drawing.seam_allowance), true);
    s += "</g>\n";
  }
  if (drawing.md_mark) {
    std::vector<double> shaft, head;
    double x, y;
    MdArrow(r, &shaft, &head, &x, &y);
    Append(&s, "<g id=\"md\" fill=\"none\" stroke=\"#ff8000\" stroke-width=\"%.3f\">\n", 2 * sw);
    svg_path(shaft, false);
    svg_path(head, false);
    Append(&s, "<text x=\"%.4f\" y=\"%.4f\" fill=\"#ff8000\" stroke=\"none\" font-family=\"sans-serif\" "
               "font-size=\"%.3f\" text-anchor=\"middle\">MD</text>\n", X(x), Y(y), h);
    s += "</g>\n";
  }
  Append(&s, "<g id=\"lines\" fill=\"none\" stroke-width=\"%.3f\" stroke-linecap=\"round\">\n",
         2 * sw);
  for (const PatternLine &l : r.lines)
    for (size_t k = 0; k < l.paths.size(); ++k) {
      const int kind = LineKind(l.name);
      Append(&s, "<polyline id=\"line-%s-%d\" class=\"%s\" stroke=\"%s\" points=\"",
             XmlId(l.name).c_str(), (int)k, kind == 0 ? "cut" : (kind == 1 ? "weld" : "line"),
             kRgb[kind]);
      for (size_t j = 0; j < l.paths[k].size(); ++j) {
        const double *p = &r.xy[2 * (size_t)l.paths[k][j]];
        Append(&s, "%s%.4f,%.4f", j ? " " : "", X(p[0]), Y(p[1]));
      }
      s += "\"/>\n";
    }
  s += "</g>\n";
  if (labels) {
    Append(&s, "<g id=\"labels\" font-family=\"sans-serif\" font-size=\"%.3f\" "
               "fill=\"#000000\">\n", h);
    Append(&s, "<text x=\"%.4f\" y=\"%.4f\">%s</text>\n", X(b.lo[0]), Y(b.hi[1] + h),
           XmlEscape(strip_name).c_str());
    for (const PatternLine &l : r.lines) {
      const Label lb = LabelAt(r, l);
      // SVG's y points down, so the counter-clockwise angle turns clockwise.
      Append(&s, "<text x=\"%.4f\" y=\"%.4f\" fill=\"%s\" text-anchor=\"middle\" "
                 "transform=\"rotate(%.3f %.4f %.4f)\">%s</text>\n",
             X(lb.x), Y(lb.y), kRgb[LineKind(l.name)], -lb.deg, X(lb.x), Y(lb.y),
             XmlEscape(LineLabel(l)).c_str());
    }
    s += "</g>\n";
  }
  s += "</svg>\n";
  return WriteFile(path, s, err);
}

std::vector<double> OffsetOutline(const FlattenResult &r, const std::vector<int> &loop, double d) {
  std::vector<double> out;
  const size_t n = loop.size();
  for (size_t k = 0; k < n; ++k) {
    const double *p = &r.xy[2 * (size_t)loop[(k + n - 1) % n]], *q = &r.xy[2 * (size_t)loop[k]],
                 *s = &r.xy[2 * (size_t)loop[(k + 1) % n]];
    // Right-hand normals of the edges in and out (outward: the interior is on the left).
    double a[2] = {q[1] - p[1], -(q[0] - p[0])}, b[2] = {s[1] - q[1], -(s[0] - q[0])};
    const double la = std::hypot(a[0], a[1]), lb = std::hypot(b[0], b[1]);
    if (la > 0) a[0] /= la, a[1] /= la;
    if (lb > 0) b[0] /= lb, b[1] /= lb;
    double m[2] = {a[0] + b[0], a[1] + b[1]};
    const double lm = std::hypot(m[0], m[1]);
    if (lm < 1e-12) {  // the outline turns back on itself: move along one edge's normal
      m[0] = a[0], m[1] = a[1];
    } else {
      m[0] /= lm, m[1] /= lm;
    }
    const double c = m[0] * a[0] + m[1] * a[1];           // cos of half the turn
    const double reach = std::min(4.0 * d, c > 0 ? d / c : 4.0 * d);
    out.push_back(q[0] + reach * m[0]);
    out.push_back(q[1] + reach * m[1]);
  }
  return out;
}

void PatternLongAxis(const FlattenResult &r, double centre[2], double dir[2], double *extent) {
  const size_t n = r.xy.size() / 2;
  double mx = 0, my = 0, sxx = 0, syy = 0, sxy = 0;
  for (size_t k = 0; k < n; ++k) mx += r.xy[2 * k] / n, my += r.xy[2 * k + 1] / n;
  for (size_t k = 0; k < n; ++k) {
    const double x = r.xy[2 * k] - mx, y = r.xy[2 * k + 1] - my;
    sxx += x * x, syy += y * y, sxy += x * y;
  }
  const double angle = 0.5 * std::atan2(2 * sxy, sxx - syy);  // the covariance's major axis
  dir[0] = std::cos(angle), dir[1] = std::sin(angle);
  centre[0] = mx, centre[1] = my;
  double lo = HUGE_VAL, hi = -HUGE_VAL;
  for (size_t k = 0; k < n; ++k) {
    const double t = (r.xy[2 * k] - mx) * dir[0] + (r.xy[2 * k + 1] - my) * dir[1];
    lo = std::min(lo, t), hi = std::max(hi, t);
  }
  *extent = hi - lo;
}

bool WritePatternLineTable(const std::string &path, const std::vector<PatternTableEntry> &strips,
                           std::string *err) {
  std::string s = "strip,line,on_boundary,pieces,segments,length3d_mm,length2d_mm,expansion_pct,"
                  "length2d_uncompensated_mm,compensation_pct\n";
  auto comp = [](double l, double l0) { return l0 > 0 ? (l - l0) / l0 * 100 : 0.0; };
  for (const PatternTableEntry &e : strips) {
    if (!e.result) continue;
    const FlattenResult &r = *e.result;
    int segs = 0;
    for (const auto &loop : r.outline) segs += (int)loop.size();
    const double pct = r.outline_length3d > 0
                           ? (r.outline_length2d - r.outline_length3d) / r.outline_length3d * 100
                           : 0.0;
    const FlattenResult &u = e.uncompensated ? *e.uncompensated : r;
    const std::string strip = CsvField(e.strip);
    Append(&s, "%s,(outline),1,%d,%d,%.4f,%.4f,%.6g,%.4f,%.6g\n", strip.c_str(),
           (int)r.outline.size(), segs, r.outline_length3d, r.outline_length2d, pct,
           u.outline_length2d, comp(r.outline_length2d, u.outline_length2d));
    for (size_t k = 0; k < r.lines.size(); ++k) {
      const PatternLine &l = r.lines[k];
      // Both patterns measure the same sets in the same order.
      const double l0 = k < u.lines.size() ? u.lines[k].length2d : l.length2d;
      Append(&s, "%s,%s,%d,%d,%d,%.4f,%.4f,%.6g,%.4f,%.6g\n", strip.c_str(),
             CsvField(l.name).c_str(), l.on_boundary ? 1 : 0, (int)l.paths.size(), l.segments,
             l.length3d, l.length2d, l.expansion_pct, l0, comp(l.length2d, l0));
    }
  }
  return WriteFile(path, s, err);
}

} // namespace etfe
