// Fabrication errors of a cutting pattern (see etfe/analyses/pattern_errors.h).
#include "etfe/analyses/pattern_errors.h"

#include <algorithm>
#include <cmath>
#include <map>

#include "etfe/analyses/pattern_sheet.h"
#include "pattern_text.h"

namespace etfe {
namespace {

double Dist3(const MeshData &m, int a, int b) {
  const double *p = &m.coords[3 * (size_t)a], *q = &m.coords[3 * (size_t)b];
  return std::sqrt((q[0] - p[0]) * (q[0] - p[0]) + (q[1] - p[1]) * (q[1] - p[1]) + (q[2] - p[2]) * (q[2] - p[2]));
}

std::string CsvField(const std::string &t) {
  if (t.find_first_of(",\"\r\n") == std::string::npos) return t;
  std::string s = "\"";
  for (char c : t) s += c == '"' ? std::string("\"\"") : std::string(1, c);
  return s + "\"";
}

} // namespace

PatternStripErrors PatternErrors(const MeshData &strip, const FlattenResult &r, const std::string &name) {
  PatternStripErrors out;
  out.strip = name;
  std::map<std::pair<int, int>, size_t> link_of;
  for (size_t i = 0; 2 * i + 1 < r.links.size(); ++i) link_of[{r.links[2 * i], r.links[2 * i + 1]}] = i;
  const std::vector<int> corners = PatternCorners(r);
  const std::vector<std::vector<int>> edges = PatternEdges(r, corners);
  for (size_t k = 0; k < edges.size(); ++k) {
    PatternEdgeError e;
    e.name = corners.empty() ? std::string("outline")
                             : CornerName((int)k) + "-" + CornerName((int)((k + 1) % corners.size()));
    for (size_t j = 0; j + 1 < edges[k].size(); ++j) {
      const int a = edges[k][j], b = edges[k][j + 1];
      const auto it = link_of.find({std::min(a, b), std::max(a, b)});
      if (it == link_of.end()) continue;  // not a link (cannot happen on an outline)
      e.length3d += Dist3(strip, a, b);
      e.target += r.link_length3d[it->second];
      e.length2d += std::hypot(r.xy[2 * (size_t)b] - r.xy[2 * (size_t)a], r.xy[2 * (size_t)b + 1] - r.xy[2 * (size_t)a + 1]);
      e.max_link_error = std::max(e.max_link_error, std::fabs(r.link_error[it->second]));
    }
    e.compensation = e.length3d > 0 ? (e.target - e.length3d) / e.length3d : 0.0;
    e.error = e.target > 0 ? (e.length2d - e.target) / e.target : 0.0;
    out.edges.push_back(e);
  }
  for (int t = 0; t < strip.NumElements(); ++t) {
    const int a = strip.triangles[3 * t], b = strip.triangles[3 * t + 1], c = strip.triangles[3 * t + 2];
    const double *p = &strip.coords[3 * (size_t)a], *q = &strip.coords[3 * (size_t)b], *s = &strip.coords[3 * (size_t)c];
    const double u[3] = {q[0] - p[0], q[1] - p[1], q[2] - p[2]}, v[3] = {s[0] - p[0], s[1] - p[1], s[2] - p[2]};
    const double n[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
    out.area3d += 0.5 * std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    const double *x = &r.xy[2 * (size_t)a], *y = &r.xy[2 * (size_t)b], *z = &r.xy[2 * (size_t)c];
    out.area2d += 0.5 * std::fabs((y[0] - x[0]) * (z[1] - x[1]) - (y[1] - x[1]) * (z[0] - x[0]));
  }
  out.area_strain = out.area3d > 0 ? (out.area2d - out.area3d) / out.area3d : 0.0;
  out.max_interior_error = r.max_rel_error_interior;
  out.rms_interior_error = r.rms_rel_error_interior;
  out.max_link_error = r.max_rel_error;
  return out;
}

std::string PatternErrorReport(const PatternStripErrors &p, double yield, const std::string &source) {
  std::string s;
  const char *st = p.strip.c_str();
  auto warn = [&](const std::string &what, double e) {
    if (yield > 0 && std::fabs(e) > yield)
      Append(&s,
             "cutpattern: WARNING: strip %s %s: fabrication error %.3f %% exceeds the first-yield strain %.3f %% (%s): "
             "the film drawn onto the surface there yields; cut narrower strips or add a cutting line\n",
             st, what.c_str(), 100 * std::fabs(e), 100 * yield, source.c_str());
  };
  for (const PatternEdgeError &e : p.edges) {
    Append(&s,
           "cutpattern: strip %s edge %s: 3D %.3f mm, target %.3f mm (compensation %+.4f %%), 2D %.3f mm, error "
           "%+.3e, largest link error %.3e\n",
           st, e.name.c_str(), e.length3d, e.target, 100 * e.compensation, e.length2d, e.error, e.max_link_error);
    warn("edge " + e.name, std::max(std::fabs(e.error), e.max_link_error));
  }
  Append(&s,
         "cutpattern: strip %s area: 3D %.1f mm^2, 2D %.1f mm^2, area strain %+.3e; interior link error max %.3e "
         "rms %.3e\n",
         st, p.area3d, p.area2d, p.area_strain, p.max_interior_error, p.rms_interior_error);
  warn("interior", p.max_interior_error);
  return s;
}

bool WritePatternErrors(const std::string &path, const std::vector<PatternStripErrors> &strips,
                        double first_yield_strain, std::string *err) {
  auto over = [&](double a, double b) {
    return first_yield_strain > 0 && (std::fabs(a) > first_yield_strain || std::fabs(b) > first_yield_strain) ? 1 : 0;
  };
  std::string s = "strip,kind,name,value3d,target,value2d,compensation,error,max_link_error,exceeds_first_yield\n";
  for (const PatternStripErrors &p : strips) {
    const std::string name = CsvField(p.strip);
    for (const PatternEdgeError &e : p.edges)
      Append(&s, "%s,edge,%s,%.4f,%.4f,%.4f,%.6e,%.6e,%.6e,%d\n", name.c_str(), e.name.c_str(), e.length3d, e.target,
             e.length2d, e.compensation, e.error, e.max_link_error, over(e.error, e.max_link_error));
    // An area strain is not a length strain: no yield verdict on it.
    Append(&s, "%s,area,area,%.2f,,%.2f,,%.6e,%.6e,\n", name.c_str(), p.area3d, p.area2d, p.area_strain,
           p.max_link_error);
    Append(&s, "%s,interior,interior links,,,,,%.6e,%.6e,%d\n", name.c_str(), p.rms_interior_error,
           p.max_interior_error, over(p.rms_interior_error, p.max_interior_error));
  }
  return WriteTextFile(path, s, err);
}

} // namespace etfe
