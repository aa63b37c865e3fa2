// Cutting-pattern export (docs/theory.md §9: fabricators cut from DXF or SVG; thesis Fig. 2.10
// reports each line's length and its expansion against 3D): the strip's drawing (pattern_sheet.cpp)
// as DXF (pattern_dxf.cpp) and SVG (pattern_svg.cpp), the outline offset by the seam allowance, the
// pattern's long axis and the table of the named lines' lengths.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "etfe/analyses/flatten_strip.h"
#include "etfe/analyses/pattern_sheet.h"
#include "pattern_text.h"

namespace etfe {
namespace {

// RFC 4180 quoting for names that hold a separator or a quote.
std::string CsvField(const std::string &t) {
  if (t.find_first_of(",\"\r\n") == std::string::npos) return t;
  std::string s = "\"";
  for (char c : t) s += c == '"' ? std::string("\"\"") : std::string(1, c);
  return s + "\"";
}

bool CheckResult(const FlattenResult &r, const std::string &path, std::string *err) {
  if (r.xy.empty() || r.outline.empty()) {
    if (err) *err = "'" + path + "': the flattening result is empty (FlattenStrip failed?)";
    return false;
  }
  return true;
}

} // namespace

bool WritePatternDxf(const std::string &path, const FlattenResult &r, const std::string &strip_name,
                     const PatternDrawing &drawing, std::string *err) {
  return CheckResult(r, path, err) && WriteSheetDxf(path, PatternSheet(r, strip_name, drawing), err);
}

bool WritePatternSvg(const std::string &path, const FlattenResult &r, const std::string &strip_name,
                     const PatternDrawing &drawing, std::string *err) {
  return CheckResult(r, path, err) && WriteSheetSvg(path, PatternSheet(r, strip_name, drawing), err);
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
  return WriteTextFile(path, s, err);
}

} // namespace etfe
