// Cutting-pattern flattening (docs/theory.md §9, thesis §2.3, eqs. 2.23-2.33) and its DXF/SVG/CSV
// export. Needs PETSc (FlattenStrip solves K dx = R on PETSC_COMM_SELF): link with etfe_core.
//  * kernel: the link gradient (eq. 2.33) against central differences; zero length and NaN guards;
//  * developable strips (polyhedral cylinder and cone) flatten isometrically: every link to
//    1e-8 relative, the rectangle / the sector angle of the exact development;
//  * doubly curved strips (sphere, saddle) leave link errors that shrink ~ width^2;
//  * a flat (tilted, irregular) strip comes back congruent;
//  * degenerate input is rejected with a message;
//  * the DXF pairs group codes with values, has HEADER/TABLES/ENTITIES and EOF, and its
//    outline POLYLINE holds the outline's vertices (layers OUTLINE, WELD, TEXT and one per
//    named line); the SVG holds one path per outline loop with the same vertices in its group
//    "outline" and one polyline per named line piece.
#include <petscsys.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

#include "check.h"
#include "fd_tangent.h"
#include "etfe/analyses/flatten_strip.h"
#include "etfe/kernels/flatten_link.h"
#include "etfe/kernels/status.h"
#include "etfe/mesh/generators.h"

using namespace etfe;

namespace {

const double kPi = 3.14159265358979323846;

// A unit-square rectangle mesh (alternating diagonals) mapped through f(u, v) -> 3D, with the
// sides named as cutting lines (u = 0, 1) and weld lines (v = 0, 1) and, for even ny, the
// interior centre line v = 1/2 as "centre".
MeshData MapStrip(int nx, int ny, const std::function<void(double, double, double *)> &f,
                  const std::string &name) {
  MeshData m = MakeRectangleMesh(0.0, 0.0, 1.0, 1.0, nx, ny, DiagonalPattern::Alternate, 0.0, 1);
  std::vector<int> centre;
  for (int i = 0; i < m.NumNodes(); ++i) {
    const double u = m.coords[3 * i], v = m.coords[3 * i + 1];
    if (ny % 2 == 0 && std::fabs(v - 0.5) < 1e-12) centre.push_back(i);
    f(u, v, &m.coords[3 * i]);
  }
  std::map<std::string, std::vector<int>> sets;
  sets["cut_start"] = m.node_sets["left"];
  sets["cut_end"] = m.node_sets["right"];
  sets["weld_bottom"] = m.node_sets["bottom"];
  sets["weld_top"] = m.node_sets["top"];
  if (!centre.empty()) sets["centre"] = centre;
  m.node_sets = sets;
  m.source = name;
  return m;
}

const PatternLine *FindLine(const FlattenResult &r, const std::string &name) {
  for (const PatternLine &l : r.lines)
    if (l.name == name) return &l;
  return nullptr;
}

double Len2(const FlattenResult &r, int a, int b) {
  return std::hypot(r.xy[2 * b] - r.xy[2 * a], r.xy[2 * b + 1] - r.xy[2 * a + 1]);
}

double Len3(const MeshData &m, int a, int b) {
  const double *p = &m.coords[3 * a], *q = &m.coords[3 * b];
  return std::sqrt((p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) +
                   (p[2] - q[2]) * (p[2] - q[2]));
}

void Summary(const char *what, const FlattenResult &r) {
  std::printf("  %-28s init %-10s it %2d (%d stages)  S %.3e -> %.3e  link err max %.3e rms "
              "%.3e (boundary max %.3e, interior max %.3e)\n",
              what, r.initial_guess.c_str(), r.iterations, r.stages, r.S_initial, r.S,
              r.max_rel_error, r.rms_rel_error, r.max_rel_error_boundary,
              r.max_rel_error_interior);
}

void TestKernel() {
  const double p[2] = {1.3, -0.4}, q[2] = {-2.1, 3.7}, L = 4.2;
  double c, g[4];
  CHECK(FlattenLink(p, q, L, 1e-12, &c, g) == KERNEL_OK, "kernel status");
  CHECK_CLOSE(c, std::hypot(q[0] - p[0], q[1] - p[1]) - L, 1e-15, 0.0);
  double x[4] = {p[0], p[1], q[0], q[1]};
  const double h = 1e-6;
  double gfd[4];
  etfe_test::CentralDifferenceJacobian([&](const double *y, double *cy) { FlattenLink(y, y + 2, L, 0.0, cy, nullptr); },
                                       x, 4, 1, h, gfd);
  for (int k = 0; k < 4; ++k) CHECK_CLOSE(g[k], gfd[k], 1e-8, 1e-10);
  double K[16], R[4];
  FlattenLinkSystem(7.0, c, g, 0.0, K, R);
  for (int a = 0; a < 4; ++a) {
    CHECK_CLOSE(R[a], -7.0 * c * g[a], 1e-15, 0.0);
    for (int b = 0; b < 4; ++b) CHECK_CLOSE(K[4 * a + b], K[4 * b + a], 0.0, 0.0);
  }
  // K is the truss stiffness along the link: a rigid translation has no "force".
  double t[4] = {0, 0, 0, 0};
  for (int a = 0; a < 4; ++a)
    for (int b = 0; b < 4; ++b) t[a] += K[4 * a + b] * (b % 2 == 0 ? 1.0 : 0.5);
  for (int a = 0; a < 4; ++a) CHECK_CLOSE(t[a], 0.0, 0.0, 1e-12);
  // With the current length the matrix is the exact derivative -dR/dx (Newton).
  double KN[16], RN[4];
  FlattenLinkSystem(7.0, c, g, c + L, KN, RN);
  const auto residual = [&](const double *y, double *Ry) {
    double cy, gy[4], Kt[16];
    FlattenLink(y, y + 2, L, 0.0, &cy, gy);
    FlattenLinkSystem(7.0, cy, gy, 0.0, Kt, Ry);
  };
  double dRdx[16];
  etfe_test::CentralDifferenceJacobian(residual, x, 4, 4, h, dRdx);
  for (int k = 0; k < 4; ++k)
    for (int a = 0; a < 4; ++a) CHECK_CLOSE(KN[4 * a + k], -dRdx[4 * a + k], 1e-7, 1e-8);
  CHECK(FlattenLink(p, p, L, 0.0, &c, g) == KERNEL_DEGENERATE, "zero length guard");
  const double tiny[2] = {p[0] + 1e-14, p[1]};
  CHECK(FlattenLink(p, tiny, L, 1e-12, &c, g) == KERNEL_DEGENERATE, "min length guard");
  const double bad[2] = {NAN, 0.0};
  CHECK(FlattenLink(p, bad, L, 0.0, &c, g) == KERNEL_NONFINITE, "NaN guard");
  CHECK(FlattenLink(p, q, INFINITY, 0.0, &c, g) == KERNEL_NONFINITE, "Inf length guard");
}

// Every link of a developable strip keeps its length; triangles stay counter-clockwise.
void CheckDevelopable(const MeshData &m, const FlattenResult &r) {
  CHECK(r.converged, "converged");
  CHECK(r.max_rel_error < 1e-8, "max link error %.3e", r.max_rel_error);
  for (int e = 0; e < m.NumElements(); ++e) {
    const int *t = &m.triangles[3 * e];
    const double *a = &r.xy[2 * t[0]], *b = &r.xy[2 * t[1]], *c = &r.xy[2 * t[2]];
    const double area = 0.5 * ((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]));
    CHECK(area > 0, "element %d has 2D area %g (should be counter-clockwise)", e, area);
  }
  for (const PatternLine &l : r.lines)
    CHECK(std::fabs(l.expansion_pct) < 1e-6, "%s %g %%", l.name.c_str(), l.expansion_pct);
}

void TestDevelopable() {
  std::string err;
  FlattenOptions opt;
  opt.line_sets = {"centre"};
  // Cylinder R = 500, 60 degrees, width 300, 12 x 6 cells. Each cell is a plane rectangle, so
  // the development is exact: a rectangle of the chord polygon's length by 300.
  const double R = 500.0, ang = kPi / 3;
  MeshData cyl = MapStrip(12, 6, [&](double u, double v, double *X) {
    const double th = (u - 0.5) * ang;
    X[0] = R * std::sin(th);
    X[1] = (v - 0.5) * 300.0;
    X[2] = R * std::cos(th) - R;
  }, "cylinder strip");
  FlattenResult r;
  const bool ok = FlattenStrip(cyl, opt, &r, &err);
  CHECK(ok, "cylinder: %s", err.c_str());
  if (!ok) return;
  Summary("cylinder R500 60deg x 300", r);
  CheckDevelopable(cyl, r);
  double hi[2] = {0, 0};
  for (size_t i = 0; i < r.xy.size(); i += 2) {
    hi[0] = std::max(hi[0], r.xy[i]);
    hi[1] = std::max(hi[1], r.xy[i + 1]);
  }
  const double chord_len = 12 * 2 * R * std::sin(ang / 24);
  std::printf("    bounding box %.10f x %.10f (chord polygon %.10f x 300)\n", hi[0], hi[1],
              chord_len);
  CHECK_CLOSE(hi[0], chord_len, 1e-8, 0.0);
  CHECK_CLOSE(hi[1], 300.0, 1e-8, 0.0);
  CHECK(r.outline.size() == 1 && r.outline[0].size() == 2 * (12 + 6), "outline %zu loops",
        r.outline.size());
  CHECK_CLOSE(r.outline_length2d, r.outline_length3d, 1e-10, 0.0);
  const PatternLine *centre = FindLine(r, "centre");
  CHECK(centre && !centre->on_boundary && centre->segments == 12 && centre->paths.size() == 1,
        "centre line");
  if (centre) std::printf("    centre line 3D %.6f 2D %.6f expansion %+.3e %%\n", centre->length3d,
                          centre->length2d, centre->expansion_pct);
  const PatternLine *weld = FindLine(r, "weld_top");
  CHECK(weld && weld->on_boundary && weld->segments == 12 && weld->paths[0].size() == 13,
        "weld_top line");
  CHECK(r.lines.size() == 5, "5 named lines (4 by prefix + centre): %zu", r.lines.size());

  // Cone: half-angle 30 deg, slant 400..700, 90 deg around. The cells lie in planes through
  // the apex, so the development is an annular sector of angle 12 * 2 asin(sin a sin(dphi/2)).
  const double alpha = kPi / 6, phi = kPi / 2;
  MeshData cone = MapStrip(12, 6, [&](double u, double v, double *X) {
    const double s = 400.0 + 300.0 * v, p = u * phi;
    X[0] = s * std::sin(alpha) * std::cos(p);
    X[1] = s * std::sin(alpha) * std::sin(p);
    X[2] = -s * std::cos(alpha);
  }, "cone strip");
  const bool okc = FlattenStrip(cone, opt, &r, &err);
  CHECK(okc, "cone: %s", err.c_str());
  if (!okc) return;
  Summary("cone 30deg s400-700 90deg", r);
  CheckDevelopable(cone, r);
  // The two radial cut lines (u = 0: nodes 0 and 7*13... ) meet at the sector angle.
  auto node = [](int i, int j) { return j * 13 + i; };
  double d0[2], d1[2];
  for (int k = 0; k < 2; ++k) {
    d0[k] = r.xy[2 * node(0, 6) + k] - r.xy[2 * node(0, 0) + k];
    d1[k] = r.xy[2 * node(12, 6) + k] - r.xy[2 * node(12, 0) + k];
  }
  const double sector = std::acos((d0[0] * d1[0] + d0[1] * d1[1]) /
                                  (std::hypot(d0[0], d0[1]) * std::hypot(d1[0], d1[1])));
  const double expect = 12 * 2 * std::asin(std::sin(alpha) * std::sin(phi / 24));
  std::printf("    sector angle %.12f deg (exact development %.12f deg)\n", sector * 180 / kPi,
              expect * 180 / kPi);
  CHECK_CLOSE(sector, expect, 1e-8, 0.0);
}

struct CurvedRow {
  double width, max_err, rms_err, S, centre_pct, weld_pct, outline_pct;
  int iterations;
};

// A doubly curved strip 1200 mm long at mesh size 25 mm for widths 400, 200, 100.
// centre_sign: the sign the centre line's expansion must have at every width.
void TestDoublyCurved(const char *what, double centre_sign,
                      const std::function<void(double, double, double, double *)> &f) {
  std::vector<CurvedRow> rows;
  FlattenOptions opt;
  opt.line_sets = {"centre"};
  for (double w : {400.0, 200.0, 100.0}) {
    const int ny = (int)std::lround(w / 25.0);
    MeshData m = MapStrip(48, ny, [&](double u, double v, double *X) { f(w, u, v, X); }, what);
    FlattenResult r;
    std::string err;
    const bool ok = FlattenStrip(m, opt, &r, &err);
    CHECK(ok, "%s width %g: %s", what, w, err.c_str());
    if (!ok) return;
    char label[64];
    std::snprintf(label, sizeof label, "%s w %g", what, w);
    Summary(label, r);
    // S (eq. 2.23) is what the link errors say it is.
    double S = 0.0;
    for (size_t i = 0; i < r.link_error.size(); ++i) {
      const double d = r.link_error[i] * r.link_length3d[i];
      S += (r.link_on_boundary[i] ? opt.boundary_weight : opt.interior_weight) * d * d;
    }
    CHECK_CLOSE(S, r.S, 1e-6, 1e-20);
    CHECK(r.converged && r.max_rel_error > 1e-7, "%s: doubly curved, so links cannot all keep "
          "their length (max %.3e)", label, r.max_rel_error);
    // The 1e12 boundary weight keeps the cut and weld lines (thesis §2.4.2).
    CHECK(r.max_rel_error_boundary < 1e-7, "%s boundary links %.3e", label,
          r.max_rel_error_boundary);
    const PatternLine *c = FindLine(r, "centre"), *wt = FindLine(r, "weld_top");
    const PatternLine *cs = FindLine(r, "cut_start");
    CHECK(c && wt && cs, "lines");
    if (!c || !wt || !cs) return;
    std::printf("    lines: centre 3D %.4f 2D %.4f (%+.5f %%), weld_top %+.3e %%, cut_start "
                "%+.3e %%, outline %+.3e %%\n", c->length3d, c->length2d, c->expansion_pct,
                wt->expansion_pct, cs->expansion_pct,
                (r.outline_length2d - r.outline_length3d) / r.outline_length3d * 100);
    // The thesis' plain Gauss-Newton at 1e12 from the start reaches the same minimum.
    FlattenOptions plain = opt;
    plain.second_order = 0;
    plain.weight_growth = 0.0;
    FlattenResult g;
    const bool okg = FlattenStrip(m, plain, &g, &err);
    CHECK(okg, "%s plain Gauss-Newton: %s", label, err.c_str());
    if (okg) {
      std::printf("    plain Gauss-Newton: it %d, S %.10e (default %.10e), max link err %.6e\n",
                  g.iterations, g.S, r.S, g.max_rel_error);
      CHECK_CLOSE(g.S, r.S, 1e-6, 0.0);
      CHECK_CLOSE(g.max_rel_error, r.max_rel_error, 1e-5, 0.0);
      const PatternLine *gc = FindLine(g, "centre");
      CHECK(gc != nullptr, "centre");
      if (gc) CHECK_CLOSE(gc->expansion_pct, c->expansion_pct, 1e-5, 1e-12);
    }
    rows.push_back({w, r.max_rel_error, r.rms_rel_error, r.S, c->expansion_pct, wt->expansion_pct,
                    (r.outline_length2d - r.outline_length3d) / r.outline_length3d * 100,
                    r.iterations});
  }
  std::printf("  %s: width  max link err  rms link err  S  centre expansion %%  iterations\n",
              what);
  for (const CurvedRow &row : rows)
    std::printf("    %5.0f  %.4e  %.4e  %.4e  %+.6f  %d\n", row.width, row.max_err, row.rms_err,
                row.S, row.centre_pct, row.iterations);
  for (const CurvedRow &row : rows)
    CHECK(row.centre_pct * centre_sign > 0, "%s width %g: centre expansion %+.6f %%", what,
          row.width, row.centre_pct);
  for (size_t k = 1; k < rows.size(); ++k) {
    const double ratio = rows[k - 1].max_err / rows[k].max_err;
    const double cratio = rows[k - 1].centre_pct / rows[k].centre_pct;
    std::printf("    width %g -> %g: max error / %.3f, centre expansion / %.3f\n",
                rows[k - 1].width, rows[k].width, ratio, cratio);
    // Length distortion of a developed patch grows with Gaussian curvature times width^2.
    CHECK(ratio > 2.5 && ratio < 6.0, "%s: max error ratio %.3f for half the width", what, ratio);
    CHECK(cratio > 2.5 && cratio < 6.0, "%s: centre expansion ratio %.3f", what, cratio);
  }
}

void TestFlat() {
  // A regular rectangle: the initial layout is already exact.
  MeshData rect = MakeRectangleMesh(0, 0, 100, 50, 4, 2, DiagonalPattern::Right, 0.0, 1);
  FlattenResult q;
  std::string e;
  CHECK(FlattenStrip(rect, FlattenOptions(), &q, &e), "flat rectangle: %s", e.c_str());
  Summary("flat rectangle 100 x 50", q);
  CHECK(q.max_rel_error < 1e-14, "rectangle link error %.3e", q.max_rel_error);

  // Irregular mesh in a tilted plane: the pattern must be congruent (every node distance, not
  // only the links).
  MeshData m = MakeRectangleMesh(0, 0, 800, 200, 16, 4, DiagonalPattern::Alternate, 0.3, 7);
  const double a = 0.7, b = -0.4;
  const double Rx[9] = {1, 0, 0, 0, std::cos(a), -std::sin(a), 0, std::sin(a), std::cos(a)};
  const double Rz[9] = {std::cos(b), -std::sin(b), 0, std::sin(b), std::cos(b), 0, 0, 0, 1};
  MeshData flat = m;
  for (int i = 0; i < m.NumNodes(); ++i) {
    double t[3] = {0, 0, 0}, y[3] = {0, 0, 0};
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) t[r] += Rx[3 * r + c] * m.coords[3 * i + c];
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) y[r] += Rz[3 * r + c] * t[c];
    for (int r = 0; r < 3; ++r) flat.coords[3 * i + r] = y[r] + 100.0 * (r + 1);
  }
  flat.source = "flat strip";
  FlattenResult r;
  std::string err;
  const bool ok = FlattenStrip(flat, FlattenOptions(), &r, &err);
  CHECK(ok, "flat: %s", err.c_str());
  if (!ok) return;
  Summary("flat tilted irregular", r);
  double worst = 0.0;
  for (int i = 0; i < flat.NumNodes(); ++i)
    for (int j = i + 1; j < flat.NumNodes(); ++j) {
      const double L = Len3(flat, i, j);
      worst = std::max(worst, std::fabs(Len2(r, i, j) - L) / L);
    }
  std::printf("    all node pairs: max relative distance error %.3e\n", worst);
  CHECK(worst < 1e-10, "flat strip not congruent: %.3e", worst);
  CHECK(r.max_rel_error < 1e-12, "flat link error %.3e", r.max_rel_error);
  // Exact from the start: one step per boundary weight stage.
  CHECK(r.iterations <= r.stages, "flat strip took %d iterations in %d stages", r.iterations,
        r.stages);
}

void ExpectReject(const MeshData &m, const FlattenOptions &opt, const char *needle,
                  const char *what) {
  FlattenResult r;
  std::string err;
  const bool ok = FlattenStrip(m, opt, &r, &err);
  CHECK(!ok, "%s accepted", what);
  CHECK(err.find(needle) != std::string::npos, "%s: message '%s' lacks '%s'", what, err.c_str(),
        needle);
  std::printf("  rejected %-16s: %s\n", what, err.c_str());
}

void TestDegenerate() {
  MeshData base = MakeRectangleMesh(0, 0, 100, 50, 4, 2, DiagonalPattern::Right, 0.0, 1);
  base.source = "bad strip";
  FlattenOptions opt;
  MeshData zero = base;
  for (int k = 0; k < 3; ++k) zero.coords[3 * 6 + k] = zero.coords[3 * 7 + k];  // nodes 6, 7 meet
  ExpectReject(zero, opt, "coincide", "zero-length edge");
  MeshData nan = base;
  nan.coords[3 * 4 + 2] = NAN;
  ExpectReject(nan, opt, "non-finite", "NaN coordinate");
  MeshData two = base;
  const int nn = base.NumNodes();
  for (int i = 0; i < nn; ++i)
    for (int k = 0; k < 3; ++k) two.coords.push_back(base.coords[3 * i + k] + (k == 0 ? 500 : 0));
  for (int v : base.triangles) two.triangles.push_back(v + nn);
  ExpectReject(two, opt, "falls apart", "two pieces");
  MeshData fin = base;
  fin.coords.insert(fin.coords.end(), {30.0, 20.0, 40.0});
  fin.triangles.insert(fin.triangles.end(), {6, 7, nn});  // a fin on an interior edge
  ExpectReject(fin, opt, "three or more", "non-manifold");
  FlattenOptions missing;
  missing.line_sets = {"cut_nowhere"};
  ExpectReject(base, missing, "cut_nowhere", "missing line set");
}

std::vector<std::string> ReadLines(const std::string &path) {
  std::ifstream in(path);
  std::vector<std::string> v;
  std::string s;
  while (std::getline(in, s)) {
    if (!s.empty() && s.back() == '\r') s.pop_back();
    v.push_back(s);
  }
  return v;
}

std::string Trim(const std::string &s) {
  const size_t a = s.find_first_not_of(' '), b = s.find_last_not_of(' ');
  return a == std::string::npos ? "" : s.substr(a, b - a + 1);
}

size_t Count(const std::string &s, const std::string &what) {
  size_t n = 0;
  for (size_t p = s.find(what); p != std::string::npos; p = s.find(what, p + what.size())) ++n;
  return n;
}

void TestExport(const std::string &dir) {
  MeshData m = MapStrip(12, 6, [](double u, double v, double *X) {
    const double th = (u - 0.5) * kPi / 3;
    X[0] = 500 * std::sin(th);
    X[1] = (v - 0.5) * 300.0 + 20 * std::sin(3 * th);  // not developable: non-trivial pattern
    X[2] = 500 * std::cos(th) - 500 + 30 * (v - 0.5) * (v - 0.5);
  }, "export strip");
  FlattenOptions opt;
  opt.line_sets = {"centre"};
  FlattenResult r;
  std::string err;
  const bool ok = FlattenStrip(m, opt, &r, &err);
  CHECK(ok, "export strip: %s", err.c_str());
  if (!ok) return;
  const std::string stem = dir + "/etfe_test_flatten_" + std::to_string((long)getpid());
  CHECK(WritePatternDxf(stem + ".dxf", r, "export strip", true, &err), "%s", err.c_str());
  CHECK(WritePatternSvg(stem + ".svg", r, "export strip", true, &err), "%s", err.c_str());
  CHECK(WritePatternLineTable(stem + ".csv", {{"export strip", &r}, {"again", &r}}, &err), "%s",
        err.c_str());
  CHECK(!WritePatternDxf("/nonexistent-dir/x.dxf", r, "x", true, &err) &&
        err.find("cannot open") != std::string::npos, "unwritable path: %s", err.c_str());

  // DXF: code/value pairs, sections, entities.
  const std::vector<std::string> d = ReadLines(stem + ".dxf");
  CHECK(d.size() % 2 == 0 && d.size() > 10, "DXF has %zu lines", d.size());
  std::vector<std::pair<int, std::string>> pairs;
  bool codes_ok = true, values_ok = true;
  for (size_t k = 0; k + 1 < d.size(); k += 2) {
    char *end;
    const std::string c = Trim(d[k]);
    const long code = std::strtol(c.c_str(), &end, 10);
    if (c.empty() || *end != '\0' || code < 0 || code > 1071) codes_ok = false;
    const std::string v = Trim(d[k + 1]);
    if ((code >= 10 && code <= 59) || (code >= 60 && code <= 79)) {
      std::strtod(v.c_str(), &end);
      if (v.empty() || *end != '\0') values_ok = false;
    }
    pairs.push_back({(int)code, v});
  }
  CHECK(codes_ok, "DXF group codes");
  CHECK(values_ok, "DXF numeric values");
  CHECK(!pairs.empty() && pairs.back() == std::make_pair(0, std::string("EOF")), "DXF ends in EOF");
  std::vector<std::string> sections;
  bool nesting_ok = true, in_section = false, in_entities = false;
  int outline_polylines = 0, weld_polylines = 0, line_polylines = 0, texts = 0;
  std::vector<std::string> text_values;
  std::vector<int> outline_vertices;
  std::vector<std::vector<double>> outline_xy;
  std::string layer;
  for (size_t k = 0; k < pairs.size(); ++k) {
    const auto &p = pairs[k];
    if (p.first != 0) continue;
    if (p.second == "SECTION") {
      if (in_section || k + 1 >= pairs.size() || pairs[k + 1].first != 2) nesting_ok = false;
      in_section = true;
      sections.push_back(k + 1 < pairs.size() ? pairs[k + 1].second : "");
      in_entities = sections.back() == "ENTITIES";
    } else if (p.second == "ENDSEC") {
      if (!in_section) nesting_ok = false;
      in_section = in_entities = false;
    } else if (p.second == "EOF") {
      if (in_section || k + 1 != pairs.size()) nesting_ok = false;
    } else if (in_entities) {
      std::string ly;
      int flag = -1;
      double x = NAN, y = NAN;
      for (size_t j = k + 1; j < pairs.size() && pairs[j].first != 0; ++j) {
        if (pairs[j].first == 8) ly = pairs[j].second;
        if (pairs[j].first == 70) flag = std::atoi(pairs[j].second.c_str());
        if (pairs[j].first == 10) x = std::atof(pairs[j].second.c_str());
        if (pairs[j].first == 20) y = std::atof(pairs[j].second.c_str());
      }
      if (p.second == "POLYLINE") {
        layer = ly;
        if (ly == "OUTLINE") {
          ++outline_polylines;
          outline_vertices.push_back(0);
          outline_xy.emplace_back();
          CHECK(flag == 1, "outline POLYLINE closed flag %d", flag);
        } else if (ly == "WELD") {  // the net pattern edge (the same as OUTLINE without an allowance)
          ++weld_polylines;
          CHECK(flag == 1, "weld POLYLINE closed flag %d", flag);
        } else {
          ++line_polylines;
        }
      } else if (p.second == "VERTEX" && ly == "OUTLINE" && !outline_vertices.empty()) {
        ++outline_vertices.back();
        outline_xy.back().push_back(x);
        outline_xy.back().push_back(y);
      } else if (p.second == "TEXT") {
        ++texts;
        for (size_t j = k + 1; j < pairs.size() && pairs[j].first != 0; ++j)
          if (pairs[j].first == 1) text_values.push_back(pairs[j].second);
      } else if (p.second != "VERTEX" && p.second != "SEQEND") {
        CHECK(false, "unexpected DXF entity %s", p.second.c_str());
      }
    }
  }
  CHECK(nesting_ok, "DXF SECTION/ENDSEC/EOF structure");
  CHECK(sections == std::vector<std::string>({"HEADER", "TABLES", "ENTITIES"}), "DXF sections");
  size_t pieces = 0;
  for (const PatternLine &l : r.lines) pieces += l.paths.size();
  CHECK(outline_polylines == (int)r.outline.size(), "DXF outline polylines %d", outline_polylines);
  CHECK(line_polylines == (int)pieces, "DXF line polylines %d vs %zu", line_polylines, pieces);
  CHECK(weld_polylines == (int)r.outline.size(), "DXF weld polylines %d", weld_polylines);
  // Labels: the strip's name, dimensions, corner letters and one label per named line.
  auto labelled = [&](const std::string &start) {
    for (const std::string &t : text_values)
      if (t.rfind(start, 0) == 0) return true;
    return false;
  };
  CHECK(texts >= 1 + (int)r.lines.size() && labelled("export strip "), "DXF labels %d", texts);
  for (const PatternLine &l : r.lines) CHECK(labelled(l.name + " "), "DXF label of line %s", l.name.c_str());
  if (outline_polylines == 1) {
    CHECK(outline_vertices[0] == (int)r.outline[0].size(), "DXF outline vertices %d vs %zu",
          outline_vertices[0], r.outline[0].size());
    double dev = 0.0;
    for (size_t k = 0; k < r.outline[0].size() && 2 * k + 1 < outline_xy[0].size(); ++k)
      for (int c = 0; c < 2; ++c)
        dev = std::max(dev, std::fabs(outline_xy[0][2 * k + c] - r.xy[2 * r.outline[0][k] + c]));
    CHECK(dev < 1e-6, "DXF outline coordinates off by %g", dev);
  }
  for (const char *lay : {"CUT_START", "CUT_END", "WELD_TOP", "WELD_BOTTOM", "CENTRE", "OUTLINE", "WELD", "TEXT"}) {
    bool found = false;
    for (size_t k = 0; k + 1 < pairs.size(); ++k)
      found = found || (pairs[k] == std::make_pair(0, std::string("LAYER")) &&
                        pairs[k + 1] == std::make_pair(2, std::string(lay)));
    CHECK(found, "DXF layer %s in the LAYER table", lay);
  }
  std::printf("  DXF: %zu lines, sections HEADER/TABLES/ENTITIES, %d outline polyline with %d "
              "vertices, %d line polylines, %d labels\n",
              d.size(), outline_polylines, outline_vertices.empty() ? 0 : outline_vertices[0],
              line_polylines, texts);

  // SVG: root with mm size and viewBox, one path per outline loop with its vertices.
  std::ifstream sin(stem + ".svg");
  std::stringstream ss;
  ss << sin.rdbuf();
  const std::string svg = ss.str();
  CHECK(svg.rfind("<?xml", 0) == 0, "SVG XML declaration");
  CHECK(svg.find("<svg xmlns=\"http://www.w3.org/2000/svg\"") != std::string::npos, "SVG root");
  CHECK(svg.find("viewBox=\"0 0 ") != std::string::npos &&
        svg.find("mm\" height=") != std::string::npos,
        "SVG mm size and viewBox");
  CHECK(Count(svg, "</svg>") == 1 && svg.find("</svg>") + 7 == svg.size(), "SVG closes");
  CHECK(Count(svg, "<g ") == Count(svg, "</g>"), "SVG groups balanced");
  // Closed paths: OUTLINE and WELD per loop, the scale bar's bar and 3 ticks.
  CHECK(Count(svg, "<path ") == 2 * r.outline.size() + 4, "SVG outline paths");
  const size_t p0 = svg.find("<path d=\"", svg.find("<g id=\"outline\""));
  if (p0 != std::string::npos) {
    const std::string dattr = svg.substr(p0 + 9, svg.find('"', p0 + 9) - p0 - 9);
    CHECK(Count(dattr, ",") == r.outline[0].size(), "SVG outline vertices %zu vs %zu",
          Count(dattr, ","), r.outline[0].size());
    CHECK(dattr.rfind("M ", 0) == 0 && dattr.back() == 'Z', "SVG path M ... Z");
    std::printf("  SVG: %zu bytes, %zu outline path with %zu vertices, %zu polylines, %zu texts\n",
                svg.size(), Count(svg, "<path "), Count(dattr, ","), Count(svg, "<polyline "),
                Count(svg, "<text "));
  }
  CHECK(Count(svg, "<polyline ") == pieces, "SVG polylines");
  CHECK(Count(svg, "<text ") == (size_t)texts + 2, "SVG labels (the DXF's and the scale bar's 2)");
  // One group per layer: cut_* red, weld_* and WELD blue.
  CHECK(Count(svg, "stroke=\"#d00000\"") == 2 && Count(svg, "stroke=\"#0040d0\"") == 3,
        "SVG colours of cut and weld lines");

  const std::vector<std::string> csv = ReadLines(stem + ".csv");
  CHECK(csv.size() == 1 + 2 * (1 + r.lines.size()), "CSV rows %zu", csv.size());
  if (!csv.empty())
    CHECK(csv[0] == "strip,line,on_boundary,pieces,segments,length3d_mm,length2d_mm,expansion_pct,"
                    "length2d_uncompensated_mm,compensation_pct",
          "CSV header");
  for (const std::string &l : csv) std::printf("    csv| %s\n", l.c_str());
  if (!std::getenv("ETFE_KEEP_TEST_FILES")) {
    std::remove((stem + ".dxf").c_str());
    std::remove((stem + ".svg").c_str());
    std::remove((stem + ".csv").c_str());
  } else {
    std::printf("  kept %s.{dxf,svg,csv}\n", stem.c_str());
  }
}

} // namespace

int main(int argc, char **argv) {
  if (PetscInitialize(&argc, &argv, nullptr, nullptr)) return 2;
  std::printf("kernel\n");
  TestKernel();
  std::printf("developable strips\n");
  TestDevelopable();
  std::printf("doubly curved strips (1200 mm long, 25 mm mesh)\n");
  const double Rs = 2000.0;
  // Sphere (K > 0): with the boundary parallels kept, the centre (equator) comes out shorter.
  TestDoublyCurved("sphere R2000", -1.0, [&](double w, double u, double v, double *X) {
    const double th = (u - 0.5) * 1200.0 / Rs, ph = (v - 0.5) * w / Rs;
    X[0] = Rs * std::cos(ph) * std::sin(th);
    X[1] = Rs * std::sin(ph);
    X[2] = Rs * std::cos(ph) * std::cos(th) - Rs;
  });
  // Saddle (K < 0): the centre line comes out longer.
  TestDoublyCurved("saddle R2000", +1.0, [&](double w, double u, double v, double *X) {
    X[0] = (u - 0.5) * 1200.0;
    X[1] = (v - 0.5) * w;
    X[2] = (X[0] * X[0] - X[1] * X[1]) / (2 * Rs);
  });
  std::printf("flat strip\n");
  TestFlat();
  std::printf("degenerate input\n");
  TestDegenerate();
  std::printf("export\n");
  TestExport(std::filesystem::temp_directory_path().string());
  PetscFinalize();
  TEST_MAIN_END();
}
