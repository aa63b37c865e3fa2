// Cutting-pattern driver: strips from element sets, flattening, files and table (see cutpattern.h).
#include "etfe/rank0.h"
#include "etfe/cutpattern.h"

#include <algorithm>
#include <filesystem>
#include <map>

#include "etfe/mesh/gmsh_reader.h"

namespace etfe {

PetscErrorCode CutPatternOptionsFromCommandLine(MPI_Comm comm, CutPatternOptions *o) {
  char strips[512] = "", lines[512] = "";
  PetscBool set_strips = PETSC_FALSE, set_lines = PETSC_FALSE;
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
  PetscOptionsEnd();
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

namespace {

// The sub-mesh of one element set, with every node set restricted to it.
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

} // namespace

PetscErrorCode CutPatternRun(MPI_Comm comm, const MeshData &shape, const CutPatternOptions &o, const std::string &dir,
                             const std::string &stem) {
  PetscMPIInt rank;
  int ok = 1;
  std::string err, report;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  if (rank == 0) {
    std::error_code ec;
    std::filesystem::create_directories(dir, ec);
    std::vector<std::string> names = o.strips;
    if (names.empty())
      for (const auto &kv : shape.element_sets)
        if (kv.first != "all") names.push_back(kv.first);
    std::vector<FlattenResult> results(names.size());
    std::vector<PatternTableEntry> table;
    char line[512];
    for (size_t k = 0; k < names.size() && ok; ++k) {
      auto it = shape.element_sets.find(names[k]);
      if (it == shape.element_sets.end() || it->second.empty()) {
        err = "cutting pattern: the surface has no element set \"" + names[k] + "\" (check -cutpattern_strips)";
        ok = 0;
        break;
      }
      const MeshData strip = ExtractStrip(shape, it->second, names[k]);
      FlattenResult &r = results[k];
      if (!FlattenStrip(strip, o.flatten, &r, &err)) {
        err = "cutting pattern of strip " + names[k] + ": " + err;
        ok = 0;
        break;
      }
      const std::string base = dir + "/" + stem + "_" + names[k];
      MeshData flat = strip;
      for (int n = 0; n < flat.NumNodes(); ++n)
        flat.coords[3 * n] = r.xy[2 * n], flat.coords[3 * n + 1] = r.xy[2 * n + 1], flat.coords[3 * n + 2] = 0.0;
      if (!WritePatternDxf(base + ".dxf", r, names[k], true, &err) ||
          !WritePatternSvg(base + ".svg", r, names[k], true, &err) || !WriteGmshFile(base + ".msh", flat, &err)) {
        ok = 0;
        break;
      }
      table.push_back({names[k], &r});
      std::snprintf(line, sizeof line,
                    "cutpattern: strip %s: %d nodes, %d links, %d iterations (%s start), S = %.3e mm^2, link error "
                    "max %.3e rms %.3e; files %s.{dxf,svg,msh}\n",
                    names[k].c_str(), strip.NumNodes(), (int)r.link_length3d.size(), r.iterations,
                    r.initial_guess.c_str(), r.S, r.max_rel_error, r.rms_rel_error, base.c_str());
      report += line;
      std::snprintf(line, sizeof line, "cutpattern: strip %s outline: 3D %.3f mm, 2D %.3f mm, expansion %.4f %%\n",
                    names[k].c_str(), r.outline_length3d, r.outline_length2d,
                    100.0 * (r.outline_length2d - r.outline_length3d) / r.outline_length3d);
      report += line;
      for (const PatternLine &pl : r.lines) {
        std::snprintf(line, sizeof line, "cutpattern: strip %s line %s: 3D %.3f mm, 2D %.3f mm, expansion %.4f %%\n",
                      names[k].c_str(), pl.name.c_str(), pl.length3d, pl.length2d, pl.expansion_pct);
        report += line;
      }
    }
    if (ok && !WritePatternLineTable(dir + "/" + stem + "_lines.csv", table, &err)) ok = 0;
  }
  PetscCall(Rank0Outcome(comm, ok, err, PETSC_ERR_NOT_CONVERGED));
  PetscCall(PetscPrintf(comm, "%s", report.c_str()));
  PetscFunctionReturn(0);
}

} // namespace etfe
