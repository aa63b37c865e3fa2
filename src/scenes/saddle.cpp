// The saddle structure of the thesis (docs/theory.md §13), quarter model X in [0, 2000], Y in [0,
// 1000]: outside frame at z = 0 (X = 2000 and Y = 1000), symmetry on X = 0 (u_X = 0) and Y = 0
// (u_Y = 0), the arch at X = 1000: a circular arc through (Y = +-1000, z = 0) and (0, H).
// Middle part X < 1000 (centre at X = 0), corner part X > 1000.
//
// Form finding (-analysis formfind), a case of the general scene (-bc_frame_fix xyz, ...,
// -film_middle_stress_ratio, -structure_check saddle): the arch line and the frame are prescribed,
// the middle part carries MD:TD = -saddle_ratio_middle, the corners -saddle_ratio_corner (thesis
// Table 2.1). The initial shape is the arch extruded along X in the middle and ruled from the
// arch down to the frame in the corners (the PD specimens' shape). The report gives the saddle
// heights h1 (middle part centre) and h2 (corner part centre), the sag and curvature of the
// middle part's centre line (docs/theory.md §8: kappa = 8h/(L^2 + 4h^2)) and the middle cutting line length
// (X = 0).
#include <petscsys.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "etfe/assembly/assembly.h"
#include "etfe/mesh/generators.h"
#include "etfe/mesh/mesh_options.h"
#include "etfe/base/rank0.h"
#include "etfe/scenes/scene_registry.h"
#include "saddle_geometry.h"
#include "structure_inputs.h"

namespace etfe {

PetscErrorCode SaddleShapeNodesFind(Problem *P, const SaddleGeometry &g, SaddleShapeNodes *n) {
  double x[3];
  PetscFunctionBeginUser;
  PetscCall(ProblemNearestNode(P, 0.0, 0.0, &n->centre));
  PetscCall(ProblemNearestNode(P, 0.5 * (g.arch_x + g.half_length), 0.0, &n->corner));
  PetscCall(ProblemGetNodePosition(P, nullptr, n->centre, x));
  n->h1_start = x[2];
  PetscCall(ProblemGetNodePosition(P, nullptr, n->corner, x));
  n->h2_start = x[2];
  // The middle cutting line by Y (its nodes are few: one look-up each).
  PetscCall(ProblemNodeSetIds(P, "sym_x", &n->cut_line));
  std::vector<std::pair<double, PetscInt>> by_y;
  for (PetscInt k : n->cut_line) {
    PetscCall(ProblemGetNodePosition(P, nullptr, k, x));
    by_y.emplace_back(x[1], k);
  }
  std::sort(by_y.begin(), by_y.end());
  for (size_t k = 0; k < by_y.size(); ++k) n->cut_line[k] = by_y[k].second;
  PetscFunctionReturn(0);
}

PetscErrorCode SaddleShapeReport(Problem *P, const SaddleGeometry &g, const SaddleShapeNodes &n, bool start) {
  double xc[3], xk[3];
  PetscFunctionBeginUser;
  PetscCall(ProblemGetNodePosition(P, P->U, n.centre, xc));
  PetscCall(ProblemGetNodePosition(P, P->U, n.corner, xk));
  double len = 0.0, prev[3];
  for (size_t k = 0; k < n.cut_line.size(); ++k) {
    double x[3];
    PetscCall(ProblemGetNodePosition(P, P->U, n.cut_line[k], x));
    if (k) len += std::sqrt((x[0] - prev[0]) * (x[0] - prev[0]) + (x[1] - prev[1]) * (x[1] - prev[1]) +
                            (x[2] - prev[2]) * (x[2] - prev[2]));
    for (int i = 0; i < 3; ++i) prev[i] = x[i];
  }
  const double H = g.rise, L = 2.0 * g.arch_x, sag = H - xc[2];
  const double kappa = 8.0 * sag / (L * L + 4.0 * sag * sag);
  PetscCall(PetscPrintf(P->comm,
                        "saddle: rise H = %.1f mm (r = %.1f %%), h1 = %.3f mm (middle part centre), h2 = %.3f mm (corner part centre)\n"
                        "saddle: middle sag = %.3f mm over %.0f mm, curvature = %.6e 1/mm (radius %.1f mm)\n"
                        "saddle: middle_cutting_line = %.3f mm (full length over Y = -1000..1000)\n",
                        H, 100.0 * H / (2.0 * g.half_span), xc[2], xk[2], sag, L, kappa, 1.0 / kappa, 2.0 * len));
  if (start) {
    // The initial surface: for the DD cases the form-found (minimal-surface) target of thesis
    // Fig. 5.23, for the PD cases the arch extruded and ruled.
    const double h1_0 = n.h1_start, h2_0 = n.h2_start;
    PetscCall(PetscPrintf(P->comm,
                          "saddle: initial surface h1_start = %.3f mm, h2_start = %.3f mm; drawn - start: dh1 = %+.3f mm, dh2 = %+.3f mm\n",
                          h1_0, h2_0, xc[2] - h1_0, xk[2] - h2_0));
  }
  PetscFunctionReturn(0);
}

namespace {

struct SaddleFormFind {
  SaddleGeometry g;
  double ratio_mid, ratio_corner;
};

// Form finding as the general scene's inputs: the frame and the arch line held, the symmetry
// planes X = 0 and Y = 0 on rollers, the middle and corner parts' MD:TD ratios, the shape report.
PetscErrorCode SaddleFormFindPreset(MPI_Comm, StructureInputs *in, void *vctx) {
  const auto *f = (const SaddleFormFind *)vctx;
  PetscFunctionBeginUser;
  for (const auto &gf : {std::make_pair("frame", "xyz"), std::make_pair("arch", "xyz"), std::make_pair("sym_x", "x"),
                         std::make_pair("sym_y", "y")}) {
    in->bcs.push_back(BcInput());
    in->bcs.back().group = gf.first, in->bcs.back().fix = gf.second;
  }
  for (FilmInput &film : in->films) {
    if (film.group == "middle") film.stress_ratio = f->ratio_mid, film.stress_ratio_given = true;
    if (film.group == "corner") film.stress_ratio = f->ratio_corner, film.stress_ratio_given = true;
  }
  in->check.name = "saddle", in->check.rise = f->g.rise, in->check.given = true;
  PetscFunctionReturn(0);
}

} // namespace

PetscErrorCode SceneBuild_Saddle(MPI_Comm comm, SceneSpec *scene, SceneObserver *observer) {
  PetscReal ratio_r = 0.15, ratio_mid = 1.0, ratio_corner = 3.0;
  PetscFunctionBeginUser;
  PetscOptionsBegin(comm, nullptr, "Saddle scene (quarter model of the thesis's saddle)", "Scene");
  PetscCall(PetscOptionsReal("-saddle_rise_ratio", "Arch rise / span r (thesis: 0.10, 0.15, 0.20)", "", ratio_r, &ratio_r, nullptr));
  PetscCall(PetscOptionsReal("-saddle_ratio_middle", "Form finding: MD:TD stress ratio of the middle part", "", ratio_mid,
                             &ratio_mid, nullptr));
  PetscCall(PetscOptionsReal("-saddle_ratio_corner", "Form finding: MD:TD stress ratio of the corner parts", "",
                             ratio_corner, &ratio_corner, nullptr));
  PetscOptionsEnd();
  MeshOptions mesh;
  mesh.keys = kMeshPerQuarter | kMeshRefine | kMeshFile, mesh.n = 10;
  PetscCall(MeshOptionsFromCommandLine(comm, "saddle scene (default: the PD initial shape)", &mesh));
  PetscInt n = mesh.n;
  const PetscInt refine = mesh.refine;
  const bool from_file = !mesh.file.empty();
  const char *mesh_file = mesh.file.c_str();
  PetscCheck(ratio_r > 0 && ratio_r <= 0.5, comm, PETSC_ERR_ARG_OUTOFRANGE,
             "-saddle_rise_ratio %g: the arch rise ratio must lie in (0, 0.5]", ratio_r);
  PetscCheck(ratio_mid > 0 && ratio_corner > 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "saddle: stress ratios must be positive");
  PetscCheck(n >= 2 && refine >= 0 && refine < 8, comm, PETSC_ERR_ARG_OUTOFRANGE,
             "saddle: need -mesh_n >= 2 and 0 <= -mesh_refine < 8");
  PetscCheck(GeneratedTriangles(2 * n, n, 8, refine) <= kMaxGeneratedTriangles, comm, PETSC_ERR_ARG_OUTOFRANGE,
             "-mesh_n %" PetscInt_FMT " -mesh_refine %" PetscInt_FMT ": %.3g triangles, more than the %.3g a generated "
             "mesh may have", n, refine, GeneratedTriangles(2 * n, n, 8, refine), kMaxGeneratedTriangles);
  n <<= refine;
  SaddleGeometry g;
  g.rise = ratio_r * 2.0 * g.half_span;
  MeshData &m = scene->mesh;
  if (from_file) {
    PetscCall(SceneReadMesh(comm, mesh_file, &m));
  } else if (SceneHoldsMesh(comm)) {
    m = MakeRectangleMesh(0.0, 0.0, g.half_length, g.half_span, (int)(2 * n), (int)n, DiagonalPattern::Alternate,
                          0.0, 0u);
    m.source = "saddle quarter " + std::to_string(2 * n) + "x" + std::to_string(n) + " (PD initial shape)";
    for (int k = 0; k < m.NumNodes(); ++k) m.coords[3 * k + 2] = g.InitialHeight(m.coords[3 * k], m.coords[3 * k + 1]);
  }
  // Sets by position (plan coordinates), so a form-found mesh needs no groups of its own.
  const double tol = 1e-6 * g.half_length;
  for (const char *set : {"arch", "sym_x", "sym_y", "frame"}) m.node_sets[set].clear();
  m.element_sets["middle"].clear();
  m.element_sets["corner"].clear();
  for (int k = 0; k < m.NumNodes(); ++k) {
    const double *x = &m.coords[3 * k];
    if (std::fabs(x[0] - g.arch_x) < tol) m.node_sets["arch"].push_back(k);
    if (std::fabs(x[0]) < tol) m.node_sets["sym_x"].push_back(k);
    if (std::fabs(x[1]) < tol) m.node_sets["sym_y"].push_back(k);
    if (std::fabs(x[0] - g.half_length) < tol || std::fabs(x[1] - g.half_span) < tol) m.node_sets["frame"].push_back(k);
  }
  // Named lines of the cutting pattern: the cutting line on X = 0, the weld line over the arch.
  m.node_sets["cut_middle"] = m.node_sets["sym_x"];
  m.node_sets["weld_arch"] = m.node_sets["arch"];
  {
    char err[256];
    std::snprintf(err, sizeof err,
                  "%s: no nodes on the arch line X = %g or on the frame; the saddle needs the quarter model X in "
                  "[0, %g], Y in [0, %g]", m.source.c_str(), g.arch_x, g.half_length, g.half_span);
    const bool ok = !SceneHoldsMesh(comm) || (!m.node_sets["arch"].empty() && !m.node_sets["frame"].empty());
    PetscCall(Rank0Outcome(comm, ok ? 1 : 0, err, PETSC_ERR_ARG_WRONG));
  }
  for (int e = 0; e < m.NumElements(); ++e) {
    double xc = 0;
    for (int a = 0; a < 3; ++a) xc += m.coords[3 * m.triangles[3 * e + a]] / 3.0;
    m.element_sets[xc < g.arch_x ? "middle" : "corner"].push_back(e);
  }
  if (!scene->form_finding) {
    PetscCall(SaddleStretchSetup(comm, g, scene, observer));
    PetscFunctionReturn(0);
  }
  SaddleFormFind ff{g, ratio_mid, ratio_corner};
  PetscCall(StructureBuild(comm, scene, observer, true, SaddleFormFindPreset, &ff));
  PetscFunctionReturn(0);
}

} // namespace etfe
