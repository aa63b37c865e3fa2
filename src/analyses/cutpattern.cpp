// Cutting-pattern driver: strips from element sets, flattening, files and table (see cutpattern.h).
#include "etfe/base/rank0.h"
#include "etfe/analyses/cutpattern.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <memory>

#include "etfe/assembly/input_plausibility.h"
#include "etfe/kernels/compensation.h"
#include "etfe/kernels/plasticity.h"
#include "etfe/kernels/status.h"
#include "etfe/material/material.h"
#include "etfe/mesh/gmsh_reader.h"
#include "etfe/analyses/pattern_errors.h"
#include "etfe/analyses/pattern_sheet.h"

namespace etfe {

namespace {

// The film's first-yield strain S_y1 / E, the limit a fabrication error is warned against: the
// plastic law's first yield stress, or, for a law without one, -material_yield's first value
// (the plastic law's default: ETFE's 13.28 MPa, docs/theory.md §3.2) over its Young's modulus.
PetscErrorCode FirstYieldStrain(MPI_Comm comm, CutPatternOptions *o) {
  std::unique_ptr<Material> m;
  double E = 0, nu = 0;
  PetscReal sy[kMaxHardeningSegments] = {13.28};
  PetscInt n = kMaxHardeningSegments;
  PetscBool set = PETSC_FALSE;
  PetscFunctionBeginUser;
  PetscCall(MaterialCreateFromOptions(comm, &m));
  m->ElasticConstants(&E, &nu);
  const PlasticMaterial *plastic = m->PlasticLaw();
  if (plastic) sy[0] = plastic->yield[0];
  else PetscCall(PetscOptionsGetRealArray(nullptr, nullptr, "-material_yield", sy, &n, &set));
  o->first_yield_strain = E > 0 && sy[0] > 0 ? sy[0] / E : 0.0;
  char src[200];
  std::snprintf(src, sizeof src, "S_y1 %g MPa / E %g MPa, %s", (double)sy[0], E,
                plastic ? "the material's plastic law"
                        : (set ? "-material_yield" : "ETFE's first yield (-material_yield's default)"));
  o->first_yield_source = src;
  PetscFunctionReturn(0);
}

} // namespace

PetscErrorCode CutPatternOptionsFromCommandLine(MPI_Comm comm, CutPatternOptions *o) {
  char strips[512] = "", lines[512] = "";
  PetscBool set_strips = PETSC_FALSE, set_lines = PETSC_FALSE, ps_set = PETSC_FALSE;
  PetscInt nps = 3;
  PetscFunctionBeginUser;
  PetscOptionsBegin(comm, nullptr, "Cutting pattern (after form finding)", "CutPattern");
  PetscCall(PetscOptionsBool("-cutpattern", "Flatten the strips of the surface into cutting patterns", "", o->enabled,
                             &o->enabled, nullptr));
  PetscCall(PetscOptionsString("-cutpattern_strips", "Element sets to flatten, comma separated (default: all sets)",
                               "", strips, strips, sizeof strips, &set_strips));
  PetscCall(PetscOptionsString("-cutpattern_lines", "Node sets measured as lines besides cut_* and weld_*", "", lines,
                               lines, sizeof lines, &set_lines));
  PetscCall(PetscOptionsReal("-cutpattern_boundary_weight", "Weight of boundary links (thesis: 1e12)", "",
                             o->flatten.boundary_weight, &o->flatten.boundary_weight, nullptr));
  PetscCall(PetscOptionsReal("-cutpattern_interior_weight", "Weight of interior links (thesis: 1)", "",
                             o->flatten.interior_weight, &o->flatten.interior_weight, nullptr));
  PetscCall(PetscOptionsInt("-cutpattern_max_iterations", "Gauss-Newton iterations before giving up", "",
                            o->flatten.max_iterations, &o->flatten.max_iterations, nullptr));
  static const char *const comp_kinds[] = {"none", "uniform", "stress"};
  PetscInt comp = (PetscInt)o->compensation;
  PetscCall(PetscOptionsEList("-cutpattern_compensation",
                              "Shrink the patterns so the drawn film reaches its prestress: none, uniform "
                              "(-cutpattern_compensation_md/td) or stress (-cutpattern_prestress and the material)",
                              "", comp_kinds, 3, comp_kinds[comp], &comp, nullptr));
  o->compensation = (Compensation)comp;
  PetscCall(PetscOptionsReal("-cutpattern_compensation_md",
                             "Uniform compensation along the pattern's long axis (MD): the film is drawn by this "
                             "engineering strain, e.g. 0.01 cuts MD lengths 1/1.01 of the design",
                             "", o->comp_md, &o->comp_md, nullptr));
  PetscCall(PetscOptionsReal("-cutpattern_compensation_td", "Uniform compensation across the pattern (TD), as _md",
                             "", o->comp_td, &o->comp_td, nullptr));
  PetscCall(PetscOptionsReal("-cutpattern_seam_allowance",
                             "Weld/seam allowance [mm]: a second outline this far outside each pattern, what the "
                             "fabricator cuts (0: none)",
                             "", o->seam_allowance, &o->seam_allowance, nullptr));
  PetscCall(PetscOptionsBool("-cutpattern_md_mark",
                             "Mark the MD (roll) direction, the pattern's long axis, on each drawing (layer MD; "
                             "-cutpattern_md_mark 0 leaves it out)",
                             "", o->md_mark, &o->md_mark, nullptr));
  PetscCall(PetscOptionsReal("-cutpattern_roll_width",
                             "Nest all strips on a roll this wide [mm] (each turned to its least width, shelves "
                             "along the roll): <stem>_nesting.{dxf,svg,pdf}, the roll length and waste (0: no nesting)",
                             "", o->roll_width, &o->roll_width, nullptr));
  PetscCall(PetscOptionsReal("-cutpattern_roll_gap", "Gap between the strips nested on the roll [mm]", "", o->roll_gap,
                             &o->roll_gap, nullptr));
  PetscCall(PetscOptionsRealArray("-cutpattern_prestress",
                                  "Design prestress S_MD,S_TD[,S_MD-TD] (PK2, MPa) for -cutpattern_compensation "
                                  "stress, MD along the pattern's long axis",
                                  "", o->prestress, &nps, &ps_set));
  PetscOptionsEnd();
  PetscCheck(!ps_set || nps >= 2, comm, PETSC_ERR_ARG_SIZ,
             "-cutpattern_prestress needs S_MD,S_TD (and optionally S_MD-TD) in MPa");
  if (ps_set && nps == 2) o->prestress[2] = 0.0;
  PetscCheck(o->seam_allowance >= 0 && std::isfinite(o->seam_allowance), comm, PETSC_ERR_ARG_OUTOFRANGE,
             "-cutpattern_seam_allowance %g: the allowance is a distance outside the pattern, >= 0 mm",
             o->seam_allowance);
  PetscCheck(o->roll_width >= 0 && std::isfinite(o->roll_width) && o->roll_gap >= 0 && std::isfinite(o->roll_gap),
             comm, PETSC_ERR_ARG_OUTOFRANGE,
             "-cutpattern_roll_width %g / -cutpattern_roll_gap %g: give the roll's width and the gap in mm, >= 0 "
             "(width 0: no nesting)", o->roll_width, o->roll_gap);
  PetscCall(FirstYieldStrain(comm, o));
  PetscCheck(o->comp_md > -1 && o->comp_td > -1 && std::isfinite(o->comp_md) && std::isfinite(o->comp_td), comm,
             PETSC_ERR_ARG_OUTOFRANGE,
             "-cutpattern_compensation_md %g / _td %g: compensation strains must be finite and > -1", o->comp_md,
             o->comp_td);
  PetscCheck(o->compensation != Compensation::Uniform || o->comp_md != 0 || o->comp_td != 0, comm,
             PETSC_ERR_USER_INPUT,
             "-cutpattern_compensation uniform needs -cutpattern_compensation_md and/or _td (e.g. 0.01)");
  if (o->compensation == Compensation::Uniform) {
    PetscCall(ReportPlausibility(comm, CheckCompensation("-cutpattern_compensation_md", o->comp_md)));
    PetscCall(ReportPlausibility(comm, CheckCompensation("-cutpattern_compensation_td", o->comp_td)));
  }
  o->prestress_given = ps_set;
  if (ps_set) {
    // A film carries no compression (it wrinkles): the smaller principal prestress must be >= 0.
    const double *S = o->prestress;
    const double smin = 0.5 * (S[0] + S[1]) - std::sqrt(0.25 * (S[0] - S[1]) * (S[0] - S[1]) + S[2] * S[2]);
    char what[160];  // PETSc's %g writes 10 as "10."
    std::snprintf(what, sizeof what, "%g,%g,%g MPa has the principal stress %g MPa", S[0], S[1], S[2], smin);
    PetscCheck(smin >= 0, comm, PETSC_ERR_ARG_OUTOFRANGE,
               "-cutpattern_prestress %s: a film carries no compression, so no pattern reaches it; give a tensile "
               "(or zero) prestress", what);
    const double smax = 0.5 * (S[0] + S[1]) + std::sqrt(0.25 * (S[0] - S[1]) * (S[0] - S[1]) + S[2] * S[2]);
    PetscCall(ReportPlausibility(comm, CheckPrestress("-cutpattern_prestress", smax)));
  }
  if (o->compensation == Compensation::Stress) {
    // The prestress is reached elastically: the material component's elastic constants.
    std::unique_ptr<Material> m;
    PetscCall(MaterialCreateFromOptions(comm, &m));
    PetscCall(MaterialCheckPlausible(comm, *m));
    m->ElasticConstants(&o->young, &o->nu);
    double E[3], M[3];
    PetscCheck(!ps_set || (CompensationPlaneStressStrain(o->young, o->nu, o->prestress, E) == KERNEL_OK &&
                           CompensationMetricFromStrain(E, M) == KERNEL_OK),
               comm, PETSC_ERR_ARG_OUTOFRANGE,
               "-cutpattern_prestress %g,%g,%g MPa with Young's modulus %g MPa, Poisson's ratio %g: no stretch of a "
               "film reaches this stress (check the values and -material_young/-material_poisson)",
               o->prestress[0], o->prestress[1], o->prestress[2], o->young, o->nu);
  }
  PetscCheck(o->flatten.boundary_weight > 0 && o->flatten.interior_weight > 0, comm, PETSC_ERR_ARG_OUTOFRANGE,
             "-cutpattern_boundary_weight and -cutpattern_interior_weight must be positive");
  auto split = [](const char *s, std::vector<std::string> *v) {
    std::string cur;
    for (const char *p = s;; ++p) {
      if (*p == ',' || *p == 0) {
        if (!cur.empty()) v->push_back(cur);
        cur.clear();
        if (!*p) break;
      } else if (*p != ' ') {
        cur += *p;
      }
    }
  };
  if (set_strips) split(strips, &o->strips);
  if (set_lines) split(lines, &o->flatten.line_sets);
  PetscFunctionReturn(0);
}

MeshData ExtractStrip(const MeshData &m, const std::vector<int> &elements, const std::string &name) {
  MeshData s;
  s.source = m.source + " [" + name + "]";
  std::vector<int> id(m.NumNodes(), -1);
  for (int e : elements)
    for (int a = 0; a < 3; ++a) {
      int &k = id[m.triangles[3 * e + a]];
      if (k < 0) {
        k = s.NumNodes();
        for (int i = 0; i < 3; ++i) s.coords.push_back(m.coords[3 * m.triangles[3 * e + a] + i]);
      }
      s.triangles.push_back(k);
    }
  for (const auto &kv : m.node_sets) {
    std::vector<int> v;
    for (int n : kv.second)
      if (id[n] >= 0) v.push_back(id[n]);
    std::sort(v.begin(), v.end());
    if (!v.empty()) s.node_sets[kv.first] = v;
  }
  return s;
}

namespace {

// Target plane lengths of the compensated pattern of a strip: each link's design (3D) length
// times sqrt(d^T M d) of the rest metric M of its triangles (averaged over its one or two), d its
// direction in the uncompensated pattern r0 (x = MD, y = TD). False with a message for a metric
// no stretch reaches.
bool CompensatedTargets(const MeshData &strip, const std::vector<int> &elements, const FlattenResult &r0,
                        const CutPatternOptions &o, std::vector<double> *target, std::string *err) {
  // The rest metric of each triangle: one for all with uniform factors or a given prestress, or
  // from each element's own (form-finding) stress turned into the pattern's axes.
  const int ne = strip.NumElements();
  std::vector<double> metric(3 * (size_t)ne);
  for (int e = 0; e < ne; ++e) {
    double *M = &metric[3 * (size_t)e], E[3], S[3];
    int st = KERNEL_OK;
    if (o.compensation == Compensation::Uniform) {
      st = CompensationMetricUniform(o.comp_md, o.comp_td, M);
    } else if (o.prestress_given) {
      st = CompensationPlaneStressStrain(o.young, o.nu, o.prestress, E);
      if (st == KERNEL_OK) st = CompensationMetricFromStrain(E, M);
    } else {
      double X[9], xy[6];
      for (int k = 0; k < 3; ++k) {
        const int n = strip.triangles[3 * e + k];
        for (int i = 0; i < 3; ++i) X[3 * k + i] = strip.coords[3 * n + i];
        xy[2 * k] = r0.xy[2 * n], xy[2 * k + 1] = r0.xy[2 * n + 1];
      }
      st = CompensationStressInPattern(X, xy, o.md_axis, &o.element_prestress[3 * (size_t)elements[e]], S);
      if (st == KERNEL_OK) st = CompensationPlaneStressStrain(o.young, o.nu, S, E);
      if (st == KERNEL_OK) st = CompensationMetricFromStrain(E, M);
    }
    if (st != KERNEL_OK) {
      *err = "compensation of element " + std::to_string(elements[e]) + ": " + KernelStatusName(st) +
             " (check the compensation options and the element's stress)";
      return false;
    }
  }
  std::map<std::pair<int, int>, int> link_of;
  const int nl = (int)r0.links.size() / 2;
  for (int i = 0; i < nl; ++i) link_of[{r0.links[2 * i], r0.links[2 * i + 1]}] = i;
  std::vector<double> sum(nl, 0.0);
  std::vector<int> count(nl, 0);
  for (int e = 0; e < strip.NumElements(); ++e)
    for (int k = 0; k < 3; ++k) {
      int a = strip.triangles[3 * e + k], b = strip.triangles[3 * e + (k + 1) % 3];
      if (a > b) std::swap(a, b);
      const int i = link_of.at({a, b});
      const double d[2] = {r0.xy[2 * b] - r0.xy[2 * a], r0.xy[2 * b + 1] - r0.xy[2 * a + 1]};
      const double *pa = &strip.coords[3 * a], *pb = &strip.coords[3 * b];
      const double L = std::sqrt((pb[0] - pa[0]) * (pb[0] - pa[0]) + (pb[1] - pa[1]) * (pb[1] - pa[1]) +
                                 (pb[2] - pa[2]) * (pb[2] - pa[2]));
      const double l = CompensatedLength(&metric[3 * (size_t)e], L, d);
      if (!(l > 0)) {
        *err = "compensation: link " + std::to_string(a) + "-" + std::to_string(b) + " collapsed in the pattern";
        return false;
      }
      sum[i] += l;
      ++count[i];
    }
  target->resize(nl);
  for (int i = 0; i < nl; ++i) (*target)[i] = sum[i] / std::max(1, count[i]);
  return true;
}

} // namespace

const char *CompensationName(Compensation c) {
  return c == Compensation::Uniform ? "uniform" : c == Compensation::Stress ? "stress" : "none";
}

// Flattens the strip `name` of shape into *r (*strip: the strip as a mesh of its own), or takes
// its flattening from *flattened when that has it. With
// compensation, the design pattern first (its axes define MD/TD) into *design, then the pattern
// of the compensated link lengths, started again from the strip's own layouts.
bool FlattenNamedStrip(const MeshData &shape, const std::string &name, const CutPatternOptions &o,
                       const std::map<std::string, FlattenResult> *flattened, MeshData *strip, FlattenResult *r,
                       FlattenResult *design, std::string *err) {
  auto it = shape.element_sets.find(name);
  if (it == shape.element_sets.end() || it->second.empty()) {
    *err = "cutting pattern: the surface has no element set \"" + name + "\" (check -cutpattern_strips)";
    return false;
  }
  *strip = ExtractStrip(shape, it->second, name);
  const FlattenResult *done = nullptr;
  if (flattened && flattened->count(name)) done = &flattened->at(name);
  if (done) {
    *r = *done;  // the same strip, flattened with the same options
  } else if (!FlattenStrip(*strip, o.flatten, r, err)) {
    *err = "cutting pattern of strip " + name + ": " + *err;
    return false;
  }
  if (o.compensation != Compensation::None) {
    *design = *r;
    FlattenOptions fo = o.flatten;
    if (!CompensatedTargets(*strip, it->second, *design, o, &fo.link_target, err) || !FlattenStrip(*strip, fo, r, err)) {
      *err = "compensated cutting pattern of strip " + name + ": " + *err;
      return false;
    }
  }
  return true;
}

namespace {

// The pattern's files <base>.dxf, <base>.svg, <base>.pdf and <base>.msh (the plane layout as a mesh).
bool WriteStripFiles(const std::string &base, const std::string &name, const MeshData &strip, const FlattenResult &r,
                     const PatternDrawing &drawing, std::string *err) {
  MeshData flat = strip;
  for (int n = 0; n < flat.NumNodes(); ++n)
    flat.coords[3 * n] = r.xy[2 * n], flat.coords[3 * n + 1] = r.xy[2 * n + 1], flat.coords[3 * n + 2] = 0.0;
  return WritePatternDxf(base + ".dxf", r, name, drawing, err) && WritePatternSvg(base + ".svg", r, name, drawing, err) &&
         WriteSheetPdf(base + ".pdf", PatternSheet(r, name, drawing), err) && WriteGmshFile(base + ".msh", flat, err);
}

// The printed lines of one strip: the fit, the outline, each cutting line and, with compensation
// (design != nullptr), the compensated outline against the design one.
std::string StripReport(const std::string &name, const std::string &base, const MeshData &strip, const FlattenResult &r,
                        const FlattenResult *design, Compensation compensation) {
  std::string report;
  char line[512];
  std::snprintf(line, sizeof line,
                "cutpattern: strip %s: %d nodes, %d links, %d iterations (%s start%s), S = %.3e mm^2, link error "
                "max %.3e rms %.3e; files %s.{dxf,svg,pdf,msh}\n",
                name.c_str(), strip.NumNodes(), (int)r.link_length3d.size(), r.iterations, r.initial_guess.c_str(),
                r.gauss_newton_retry ? "; Gauss-Newton, the second-order step having failed or folded" : "",
                r.S, r.max_rel_error, r.rms_rel_error, base.c_str());
  report += line;
  std::snprintf(line, sizeof line, "cutpattern: strip %s outline: 3D %.3f mm, 2D %.3f mm, expansion %.4f %%\n",
                name.c_str(), r.outline_length3d, r.outline_length2d,
                100.0 * (r.outline_length2d - r.outline_length3d) / r.outline_length3d);
  report += line;
  for (const PatternLine &pl : r.lines) {
    std::snprintf(line, sizeof line, "cutpattern: strip %s line %s: 3D %.3f mm, 2D %.3f mm, expansion %.4f %%\n",
                  name.c_str(), pl.name.c_str(), pl.length3d, pl.length2d, pl.expansion_pct);
    report += line;
  }
  if (design) {
    const FlattenResult &d = *design;
    std::snprintf(line, sizeof line,
                  "cutpattern: strip %s compensation %s: outline 2D %.6f mm (uncompensated %.6f mm, %+.4f %%), "
                  "fit to the compensated lengths max %.3e\n",
                  name.c_str(), CompensationName(compensation), r.outline_length2d, d.outline_length2d,
                  100.0 * (r.outline_length2d - d.outline_length2d) / d.outline_length2d, r.max_rel_error);
    report += line;
  }
  return report;
}

} // namespace

PetscErrorCode CutPatternRun(MPI_Comm comm, const MeshData &shape, const CutPatternOptions &o, const std::string &dir,
                             const std::string &stem, const std::map<std::string, FlattenResult> *flattened) {
  PetscMPIInt rank;
  int ok = 1;
  std::string err, report;
  PetscFunctionBeginUser;
  PetscCheck(o.compensation != Compensation::Stress || o.prestress_given || o.element_stress, comm,
             PETSC_ERR_USER_INPUT,
             "-cutpattern_compensation stress needs the design prestress: -cutpattern_prestress S_MD,S_TD (MPa) "
             "(form finding gives its own stress)");
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  if (rank == 0) {
    std::error_code ec;
    std::filesystem::create_directories(dir, ec);
    std::vector<std::string> names = o.strips;
    if (names.empty())
      for (const auto &kv : shape.element_sets)
        if (kv.first != "all") names.push_back(kv.first);
    std::vector<FlattenResult> results(names.size()), design(names.size());
    std::vector<PatternTableEntry> table;
    std::vector<PatternStripErrors> errors;
    const bool compensated = o.compensation != Compensation::None;
    PatternDrawing drawing;
    drawing.seam_allowance = o.seam_allowance, drawing.md_mark = o.md_mark;
    for (size_t k = 0; k < names.size() && ok; ++k) {
      MeshData strip;
      const std::string base = dir + "/" + stem + "_" + names[k];
      if (!FlattenNamedStrip(shape, names[k], o, flattened, &strip, &results[k], &design[k], &err) ||
          !WriteStripFiles(base, names[k], strip, results[k], drawing, &err)) {
        ok = 0;
        break;
      }
      table.push_back({names[k], &results[k], compensated ? &design[k] : nullptr});
      report += StripReport(names[k], base, strip, results[k], compensated ? &design[k] : nullptr, o.compensation);
      errors.push_back(PatternErrors(strip, results[k], names[k]));
      report += PatternErrorReport(errors.back(), o.first_yield_strain, o.first_yield_source);
    }
    if (ok && !WritePatternLineTable(dir + "/" + stem + "_lines.csv", table, &err)) ok = 0;
    if (ok && !WritePatternErrors(dir + "/" + stem + "_errors.csv", errors, o.first_yield_strain, &err)) ok = 0;
    if (ok) report += "cutpattern: fabrication errors per edge and strip: " + dir + "/" + stem + "_errors.csv\n";
    if (ok && o.roll_width > 0) {
      std::vector<NestItem> items;
      for (size_t k = 0; k < names.size(); ++k) items.push_back({names[k], &results[k]});
      NestResult nest;
      Sheet sheet;
      const std::string base = dir + "/" + stem + "_nesting";
      ok = NestOnRoll(items, drawing, o.roll_width, o.roll_gap, &nest, &sheet, &err) &&
           WriteSheetDxf(base + ".dxf", sheet, &err) && WriteSheetSvg(base + ".svg", sheet, &err) &&
           WriteSheetPdf(base + ".pdf", sheet, &err);
      if (ok) report += NestReport(nest, o.roll_width, base);
    }
  }
  PetscCall(Rank0Outcome(comm, ok, err, PETSC_ERR_NOT_CONVERGED));
  PetscCall(PetscPrintf(comm, "%s", report.c_str()));
  PetscFunctionReturn(0);
}

} // namespace etfe
