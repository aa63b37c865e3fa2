// -analysis cutpattern: cutting patterns of any surface mesh, with no scene and no
// form finding. The strips are the surface's physical groups (element sets); the cutting lines
// between them are the edges two groups share, measured as node sets cut_<a>_<b> (besides any
// named curve groups: cut_*, weld_* and -cutpattern_lines). Each strip must be a disc: connected,
// manifold (no edge in three triangles, no node where the strip touches itself) with one
// boundary loop, since only a disc lies flat without a further cut. Then the cutting-pattern
// driver (cutpattern.cpp) flattens, compensates and writes the DXF/SVG/msh files and the CSV.
#include <petscsys.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "etfe/analyses/cutpattern.h"
#include "etfe/analyses/flatten_strip.h"
#include "etfe/assembly/input_plausibility.h"
#include "etfe/mesh/cad_reader.h"
#include "etfe/mesh/gmsh_reader.h"
#include "etfe/mesh/mesh_options.h"
#include "etfe/io/output.h"
#include "etfe/base/rank0.h"

namespace etfe {

namespace {

std::string NodeName(const MeshData &m, int n) {
  return "node " + std::to_string(n < (int)m.node_tags.size() ? m.node_tags[n] : (long long)n);
}

// Disc topology of one strip (its triangle ids in m): false with a message saying what it is.
bool CheckDisc(const MeshData &m, const std::string &name, const std::vector<int> &tris, std::string *err) {
  std::map<std::pair<int, int>, int> edge_count;
  std::map<int, std::vector<int>> node_tris;
  for (int e : tris)
    for (int k = 0; k < 3; ++k) {
      const int a = m.triangles[3 * e + k], b = m.triangles[3 * e + (k + 1) % 3];
      ++edge_count[{std::min(a, b), std::max(a, b)}];
      node_tris[a].push_back(e);
    }
  const std::string what = m.source + ": strip (physical surface) \"" + name + "\"";
  // Vertex manifold: the triangles around each node form one fan (joined across edges that
  // hold the node).
  for (const auto &kv : node_tris) {
    const int n = kv.first;
    const std::vector<int> &ts = kv.second;
    std::vector<int> fan(ts.size(), -1);
    int fans = 0;
    for (size_t s = 0; s < ts.size(); ++s) {
      if (fan[s] >= 0) continue;
      std::vector<size_t> stack{s};
      fan[s] = fans;
      while (!stack.empty()) {
        const int e = ts[stack.back()];
        stack.pop_back();
        for (size_t u = 0; u < ts.size(); ++u) {
          if (fan[u] >= 0) continue;
          int shared = 0;  // nodes shared with e besides n
          for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j)
              shared += m.triangles[3 * e + i] != n && m.triangles[3 * e + i] == m.triangles[3 * ts[u] + j];
          if (shared > 0) fan[u] = fans, stack.push_back(u);
        }
      }
      ++fans;
    }
    if (fans > 1) {
      *err = what + " touches itself at " + NodeName(m, n) + " (" + std::to_string(fans) +
             " separate fans of triangles meet there): a strip must be a manifold surface; split the group there";
      return false;
    }
  }
  // Euler characteristic and boundary loops: a disc has V - E + F = 1 and one loop.
  const long long V = (long long)node_tris.size(), E = (long long)edge_count.size(), F = (long long)tris.size();
  std::map<int, std::vector<int>> bnd;
  for (const auto &kv : edge_count) {
    if (kv.second > 2) {
      *err = what + ": the edge between " + NodeName(m, kv.first.first) + " and " + NodeName(m, kv.first.second) +
             " belongs to " + std::to_string(kv.second) + " triangles: a strip must be a manifold surface";
      return false;
    }
    if (kv.second == 1) bnd[kv.first.first].push_back(kv.first.second), bnd[kv.first.second].push_back(kv.first.first);
  }
  int loops = 0;
  std::set<int> seen;
  for (const auto &kv : bnd) {
    if (seen.count(kv.first)) continue;
    ++loops;
    std::vector<int> stack{kv.first};
    seen.insert(kv.first);
    while (!stack.empty()) {
      const int v = stack.back();
      stack.pop_back();
      for (int w : bnd[v])
        if (seen.insert(w).second) stack.push_back(w);
    }
  }
  const long long chi = V - E + F;
  if (chi == 1 && loops == 1) return true;
  std::string kind;
  if (loops == 0) kind = "a closed surface (no boundary to cut from)";
  else if (chi == 2 - loops) kind = std::to_string(loops) + " boundary loops (a tube or a strip with holes)";
  else kind = "a surface with " + std::to_string(loops) + " boundary loops and handles or separate pieces";
  char num[160];
  std::snprintf(num, sizeof num, " (V - E + F = %lld - %lld + %lld = %lld; a disc has 1 and one boundary loop)", V, E,
                F, chi);
  *err = what + " is not a disc but " + kind + num +
         ": it cannot lie flat without another cut; split it into disc-like strips with more physical groups";
  return false;
}

} // namespace

bool CutPatternPrepareSurface(MeshData *m, const std::vector<std::string> &only, std::vector<std::string> *notes,
                              std::string *err) {
  if (m->element_sets.empty()) {
    *err = m->source + ": the mesh has no physical surface groups, so no strips to flatten: name each strip "
                       "with Physical Surface(\"name\") = {...} in Gmsh";
    return false;
  }
  const int ne = m->NumElements();
  std::vector<int> strip_of(ne, -1);
  std::vector<std::string> names;
  for (const auto &kv : m->element_sets) {
    // Sets not chosen as strips (-cutpattern_strips) may overlap them: a group of the whole film.
    const bool chosen = only.empty() || std::find(only.begin(), only.end(), kv.first) != only.end();
    if (!chosen) continue;
    const int s = (int)names.size();
    names.push_back(kv.first);
    for (int e : kv.second) {
      if (strip_of[e] >= 0) {
        *err = m->source + ": triangle " +
               std::to_string(e < (int)m->element_tags.size() ? m->element_tags[e] : (long long)e) +
               " is in the strips \"" + names[strip_of[e]] + "\" and \"" + kv.first +
               "\": strips must not overlap; keep each triangle in one physical surface";
        return false;
      }
      strip_of[e] = s;
    }
    if (!CheckDisc(*m, kv.first, kv.second, err)) return false;
  }
  const int loose = (int)std::count(strip_of.begin(), strip_of.end(), -1);
  if (loose) notes->push_back(std::to_string(loose) + " triangles in no physical surface group are in no strip");
  // Cutting lines: edges whose two triangles lie in different strips.
  std::map<std::pair<int, int>, std::vector<int>> edge_tris;
  for (int e = 0; e < ne; ++e)
    for (int k = 0; k < 3; ++k) {
      const int a = m->triangles[3 * e + k], b = m->triangles[3 * e + (k + 1) % 3];
      edge_tris[{std::min(a, b), std::max(a, b)}].push_back(e);
    }
  std::map<std::string, std::set<int>> cuts;
  for (const auto &kv : edge_tris)
    for (size_t i = 0; i < kv.second.size(); ++i)
      for (size_t j = i + 1; j < kv.second.size(); ++j) {
        const int s = strip_of[kv.second[i]], t = strip_of[kv.second[j]];
        if (s < 0 || t < 0 || s == t) continue;
        const std::string name = "cut_" + names[std::min(s, t)] + "_" + names[std::max(s, t)];
        cuts[name].insert(kv.first.first);
        cuts[name].insert(kv.first.second);
      }
  for (const auto &kv : cuts) {
    if (m->node_sets.count(kv.first)) {
      notes->push_back("the node set " + kv.first + " of the file is kept as that cutting line");
      continue;
    }
    m->node_sets[kv.first] = std::vector<int>(kv.second.begin(), kv.second.end());
    notes->push_back("cutting line " + kv.first + ": " + std::to_string(kv.second.size()) + " nodes");
  }
  return true;
}

double PatternLeastWidth(const std::vector<double> &xy) {
  std::vector<std::pair<double, double>> p, h;
  for (size_t k = 0; k + 1 < xy.size(); k += 2) p.push_back({xy[k], xy[k + 1]});
  std::sort(p.begin(), p.end());
  p.erase(std::unique(p.begin(), p.end()), p.end());
  if (p.size() < 3) return 0.0;
  auto cross = [](const std::pair<double, double> &o, const std::pair<double, double> &a,
                  const std::pair<double, double> &b) {
    return (a.first - o.first) * (b.second - o.second) - (a.second - o.second) * (b.first - o.first);
  };
  for (int pass = 0; pass < 2; ++pass) {  // Andrew's monotone chain: lower, then upper hull
    const size_t start = h.size();
    for (size_t i = 0; i < p.size(); ++i) {
      const auto &q = pass == 0 ? p[i] : p[p.size() - 1 - i];
      while (h.size() >= start + 2 && cross(h[h.size() - 2], h.back(), q) <= 0) h.pop_back();
      h.push_back(q);
    }
    h.pop_back();
  }
  double best = std::numeric_limits<double>::infinity();
  for (size_t i = 0; i < h.size(); ++i) {
    const auto &a = h[i], &b = h[(i + 1) % h.size()];
    const double L = std::hypot(b.first - a.first, b.second - a.second);
    if (L <= 0) continue;
    double far = 0;
    for (const auto &q : h) far = std::max(far, std::fabs(cross(a, b, q)) / L);
    best = std::min(best, far);
  }
  return best;
}

namespace {

// The widest of the flattened strips of m (least width, mm) into *widest / *which, each strip's
// flattening into *flat. False with *err; *folded names a strip that folds over when flattened
// (too strongly curved for one piece), which is not an error here.
bool WidestFlattened(const MeshData &m, const FlattenOptions &fo, std::map<std::string, FlattenResult> *flat,
                     double *widest, std::string *which, std::string *folded, std::string *err) {
  *widest = 0;
  flat->clear();
  for (const auto &kv : m.element_sets) {
    FlattenResult &r = (*flat)[kv.first];
    if (!FlattenStrip(ExtractStrip(m, kv.second, kv.first), fo, &r, err)) {
      if (err->find("folds over") != std::string::npos) {
        *folded = kv.first;
        return true;
      }
      *err = "-cutpattern_strip_fit_roll: strip " + kv.first + ": " + *err;
      return false;
    }
    const double w = PatternLeastWidth(r.xy);
    if (w > *widest) *widest = w, *which = kv.first;
  }
  return true;
}

// -cutpattern_strip_fit_roll: cuts a copy of *mesh at the width W, prepares its strips
// (CutPatternPrepareSurface: the cut_* lines they share) and measures the least width of each
// flattened strip; while the widest one is wider than the roll's usable width (roll width less
// the seam allowance on both sides), W shrinks by their ratio (and 2 % more) and the surface is
// cut again; a strip that folds over when flattened (too strongly curved for one piece) shrinks W
// by 0.8. Notes say each try.
//
// A try first estimates the widths from a quick flattening (every link weighted alike, one
// stage, loose tolerance: a few Gauss-Newton steps instead of the weight stages), scaled by the
// ratio of the true to the estimated widest strip of the last full flattening; only a try whose
// estimate fits is flattened in full, which decides. Why: at 10^5 triangles a full flattening of
// all strips takes most of a try. The kept try's flattenings go to *flat, by strip (the same
// strips with the same lines), which the pattern files then use instead of flattening again.
bool CutToFitRoll(MeshData *mesh, const CutPatternSurfaceOptions &o, std::map<std::string, FlattenResult> *flat,
                  std::vector<std::string> *notes, std::string *err) {
  const double usable = o.cutpattern.roll_width - 2 * o.cutpattern.seam_allowance;
  GeodesicCutOptions g = o.geodesic;
  g.whole_if_narrow = true;
  g.equal = true;
  if (!o.width_given) g.width = usable;
  FlattenOptions quick = o.cutpattern.flatten;
  quick.boundary_weight = quick.interior_weight;
  quick.weight_growth = 0.0;
  quick.step_rtol = quick.stage_step_rtol;
  quick.s_rtol = 1e-8;
  double scale = 1.0;  // true / estimated width of the widest strip, from the last full flattening
  char line[400];
  for (int attempt = 1; attempt <= 8; ++attempt) {
    MeshData m = *mesh;
    std::vector<std::string> n;
    if (!GeodesicCutStrips(&m, g, &n, err) || !CutPatternPrepareSurface(&m, o.cutpattern.strips, &n, err)) {
      *err = "-cutpattern_strip_fit_roll (try " + std::to_string(attempt) + "): " + *err;
      return false;
    }
    double widest = 0, estimate = 0;
    std::string which, folded;
    std::string qerr;
    // A quick flattening that fails says nothing: the full one decides.
    if (WidestFlattened(m, quick, flat, &estimate, &which, &folded, &qerr) && folded.empty() &&
        estimate * scale > usable) {
      std::snprintf(line, sizeof line,
                    "roll fit, try %d: strip width %.1f mm, %zu strips, the widest quickly flattened strip %s "
                    "%.1f mm across (an estimate; usable width of the roll %.1f mm)",
                    attempt, g.width, m.element_sets.size(), which.c_str(), estimate * scale, usable);
      notes->push_back(line);
      g.width *= 0.98 * usable / (estimate * scale);
      continue;
    }
    folded.clear();
    if (!WidestFlattened(m, o.cutpattern.flatten, flat, &widest, &which, &folded, err)) return false;
    if (!folded.empty()) {
      std::snprintf(line, sizeof line,
                    "roll fit, try %d: strip width %.1f mm, %zu strips, strip %s folds over when flattened: "
                    "narrower strips (0.8 x)", attempt, g.width, m.element_sets.size(), folded.c_str());
      notes->push_back(line);
      g.width *= 0.8;
      continue;
    }
    if (estimate > 0 && flat->count(which)) scale = std::max(1.0, widest / estimate);
    std::snprintf(line, sizeof line,
                  "roll fit, try %d: strip width %.1f mm, %zu strips, the widest flattened strip %s %.1f mm across "
                  "(usable width of the roll %.1f mm: %.1f mm less twice the seam allowance %.1f mm)",
                  attempt, g.width, m.element_sets.size(), which.c_str(), widest, usable, o.cutpattern.roll_width,
                  o.cutpattern.seam_allowance);
    notes->push_back(line);
    if (widest <= usable) {
      notes->insert(notes->end(), n.begin(), n.end());
      *mesh = m;
      return true;
    }
    g.width *= 0.98 * usable / widest;
  }
  flat->clear();
  *err = "-cutpattern_strip_fit_roll: after 8 tries the widest flattened strip is still wider than the roll's usable "
         "width (see the notes); give a smaller -cutpattern_strip_width to start from, or a wider roll";
  for (const auto &n : *notes) *err += "\n  " + n;
  return false;
}

} // namespace

PetscErrorCode CutPatternSurfaceOptionsFromCommandLine(MPI_Comm comm, CutPatternSurfaceOptions *o) {
  MeshOptions mesh;
  char start[256] = "";
  PetscBool start_set = PETSC_FALSE;
  PetscBool width_set = PETSC_FALSE, direction_set = PETSC_FALSE, snap_set = PETSC_FALSE, layout_set = PETSC_FALSE;
  PetscFunctionBeginUser;
  mesh.keys = kMeshFile;
  PetscCall(MeshOptionsFromCommandLine(comm, "surface (-analysis cutpattern)", &mesh));
  PetscOptionsBegin(comm, nullptr, "Cutting patterns of a surface mesh (-analysis cutpattern)", "CutPattern");
  PetscCall(PetscOptionsReal("-cutpattern_strip_width",
                             "Cut each physical surface (or the whole mesh when it has none) into strips this wide "
                             "(mm) by seams (-cutpattern_strip_layout), the first through its middle (default: the "
                             "physical surfaces are the strips)",
                             "", o->geodesic.width, &o->geodesic.width, &width_set));
  static const char *const axes[] = {"x", "y", "z"};
  PetscInt axis = o->geodesic.direction;
  PetscCall(PetscOptionsEList("-cutpattern_strip_direction",
                              "Direction of the geodesic cutting lines at the surface's middle (the strips' long "
                              "axis), with -cutpattern_strip_width",
                              "", axes, 3, axes[axis], &axis, &direction_set));
  o->geodesic.direction = (int)axis;
  PetscCall(PetscOptionsReal("-cutpattern_strip_snap",
                             "With -cutpattern_strip_width: a mesh node within this fraction of an edge's length "
                             "from a seam is moved onto it (the seam stays where it was traced; children of split "
                             "triangles keep about this fraction of their parent's quality); a node that cannot "
                             "move (boundary corner, named line) takes the seam to it instead",
                             "", o->geodesic.snap, &o->geodesic.snap, &snap_set));
  static const char *const layouts[] = {"geodesic", "parallel", "radial"};
  PetscInt layout = o->geodesic.layout;
  PetscCall(PetscOptionsEList("-cutpattern_strip_layout",
                              "The seams of -cutpattern_strip_width: geodesic (straightest lines started across the "
                              "surface's middle), parallel (sections by planes parallel to the strip direction "
                              "and the surface normal at the middle, W apart along the surface) or radial (gores: "
                              "sections by planes through the middle along its normal, rim arcs at most W)",
                              "", layouts, 3, layouts[layout], &layout, &layout_set));
  o->geodesic.layout = (int)layout;
  PetscCall(PetscOptionsString("-cutpattern_strip_start",
                               "With -cutpattern_strip_width and the geodesic layout: a 1-D physical group of the "
                               "mesh whose middle node and direction there start the first seam (a geodesic), the "
                               "others W apart across it (default: the surface's middle along "
                               "-cutpattern_strip_direction)",
                               "", start, start, sizeof start, &start_set));
  if (start_set) o->geodesic.start_line = start;
  PetscCall(PetscOptionsBool("-cutpattern_strip_fit_roll",
                             "Choose the strip width so that every flattened strip plus the seam allowance on both "
                             "sides fits -cutpattern_roll_width (iterated from -cutpattern_strip_width, or from the "
                             "usable width); every physical surface is cut, one narrower than that is one strip",
                             "", o->fit_roll, &o->fit_roll, nullptr));
  PetscOptionsEnd();
  o->width_given = width_set;
  // Without a width nothing is cut: a direction or snap alone would be silently ignored.
  PetscCheck(width_set || o->fit_roll || !(direction_set || snap_set || layout_set), comm, PETSC_ERR_ARG_INCOMP,
             "%s only shapes geodesic strips: give -cutpattern_strip_width W too, or leave it out to flatten the "
             "physical surfaces as the strips",
             direction_set ? "-cutpattern_strip_direction" : snap_set ? "-cutpattern_strip_snap" : "-cutpattern_strip_layout");
  PetscCheck(!start_set || (width_set && o->geodesic.layout == 0 && !o->fit_roll), comm, PETSC_ERR_ARG_INCOMP,
             "-cutpattern_strip_start %s starts geodesic seams: give -cutpattern_strip_width W with "
             "-cutpattern_strip_layout geodesic (the default), without -cutpattern_strip_fit_roll",
             o->geodesic.start_line.c_str());
  PetscCheck(o->geodesic.snap >= 0 && o->geodesic.snap < 0.5, comm, PETSC_ERR_ARG_OUTOFRANGE,
             "-cutpattern_strip_snap %g: give a fraction of an edge's length in [0, 0.5)", (double)o->geodesic.snap);
  PetscCheck(!width_set || (o->geodesic.width > 0 && std::isfinite(o->geodesic.width)), comm,
             PETSC_ERR_ARG_OUTOFRANGE,
             "-cutpattern_strip_width %g: a strip width must be a positive length in mm (leave the option out to "
             "flatten the physical surfaces as the strips)", (double)o->geodesic.width);
  PetscCall(CutPatternOptionsFromCommandLine(comm, &o->cutpattern));
  PetscCheck(!o->fit_roll || o->cutpattern.roll_width > 2 * o->cutpattern.seam_allowance, comm, PETSC_ERR_USER_INPUT,
             "-cutpattern_strip_fit_roll needs the roll: -cutpattern_roll_width W (mm) wider than twice "
             "-cutpattern_seam_allowance (%g mm)", o->cutpattern.seam_allowance);
  o->mesh_file = mesh.file;
  PetscCall(MeshCadSizeFromOptions(comm, mesh.file.c_str(), &o->cad_size));
  const std::string stem = mesh.file.empty() ? std::string("surface") : std::filesystem::path(mesh.file).stem().string();
  OutputOptions oo;
  PetscCall(OutputOptionsFromCommandLine(comm, stem.c_str(), &oo));
  o->results_path = oo.path;
  PetscFunctionReturn(0);
}

PetscErrorCode CutPatternSurfaceRun(MPI_Comm comm, const CutPatternSurfaceOptions &o) {
  PetscMPIInt rank;
  MeshData mesh;
  std::vector<std::string> notes;
  std::map<std::string, FlattenResult> flat;  // the roll fit's flattenings, by strip
  std::string err;
  int ok = 1;
  PetscFunctionBeginUser;
  PetscCheck(!o.mesh_file.empty(), comm, PETSC_ERR_USER_INPUT,
             "-analysis cutpattern needs the surface: -mesh_file surface.msh (Gmsh; its physical surfaces are the "
             "strips)");
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  // The pattern files go beside the results path: <dir>/<stem>_<strip>.{dxf,svg,pdf,msh}, <stem>_lines.csv.
  const std::filesystem::path out(o.results_path);
  const std::string dir = out.parent_path().empty() ? "." : out.parent_path().string();
  // With geodesic strips the cut 3D surface (strips as physical surfaces, cutting lines as point
  // groups) is written as <stem>_cut.msh, to see the lines on the surface.
  const std::string cut_file = dir + "/" + out.stem().string() + "_cut.msh";
  const bool cutting = o.geodesic.width > 0 || o.fit_roll;
  if (rank == 0) {
    std::error_code ec;
    if (cutting) std::filesystem::create_directories(dir, ec);
    ok = ReadMeshFile(o.mesh_file, o.cad_size, &mesh, &err) && MeshOrient(&mesh, &err) && MeshCheck(mesh, 0.0, &err) &&
         (o.fit_roll ? CutToFitRoll(&mesh, o, &flat, &notes, &err)  // prepares the strips itself
                     : (o.geodesic.width <= 0 || GeodesicCutStrips(&mesh, o.geodesic, &notes, &err)) &&
                           CutPatternPrepareSurface(&mesh, o.cutpattern.strips, &notes, &err)) &&
         (!cutting || WriteGmshFile(cut_file, mesh, &err));
  }
  PetscCall(Rank0Outcome(comm, ok, err, PETSC_ERR_FILE_READ));
  for (const std::string &n : mesh.notes) PetscCall(PetscPrintf(comm, "mesh %s: %s\n", o.mesh_file.c_str(), n.c_str()));
  if (rank == 0) PetscCall(ReportPlausibility(PETSC_COMM_SELF, CheckMeshExtent(mesh.coords.data(), mesh.NumNodes(), o.mesh_file)));
  for (const std::string &n : notes) PetscCall(PetscPrintf(comm, "cutpattern: %s\n", n.c_str()));
  if (cutting) PetscCall(PetscPrintf(comm, "cutpattern: the cut surface: %s\n", cut_file.c_str()));
  if (!flat.empty())
    PetscCall(PetscPrintf(comm, "cutpattern: the patterns are the roll fit's flattenings of its last try (%zu strips, "
                                "not flattened again)\n", flat.size()));
  PetscCall(CutPatternRun(comm, mesh, o.cutpattern, dir, out.stem().string(), flat.empty() ? nullptr : &flat));
  PetscFunctionReturn(0);
}

} // namespace etfe
