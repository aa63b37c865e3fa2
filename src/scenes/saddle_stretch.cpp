// Stretch fabrication of the saddle (docs/theory.md §13, thesis ch. 4-5): the film, stress free on
// its initial shape, rests on the arch (friction contact) and its frame edges are drawn outward at
// a (X = 2000, Y = 0; in X), b (the corner; in X and Y), c (Y = 1000, X = 1000; in Y) and
// d (Y = 1000, X = 0; in Y), linearly interpolated in between (thesis Fig. 3.4), stage by stage;
// optionally followed by an internal-pressure cycle (§5.4). Probes: parts A and B (mean GL
// strains and Mises), elements I and II (minimum principal stress and strain: wrinkling), the
// slide of the arch nodes I-V; one CSV line per increment.
#include <petscsys.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "etfe/assembly/assembly.h"
#include "etfe/contact/contact.h"
#include "etfe/base/csv_history.h"
#include "etfe/kernels/plasticity.h"
#include "pattern_reference.h"
#include "real_array_option.h"
#include "saddle_geometry.h"

namespace etfe {

namespace {

struct Box {
  double x0, y0, x1, y1;
  bool Contains(double x, double y) const { return x >= x0 && x <= x1 && y >= y0 && y <= y1; }
};

struct StretchContext {
  SaddleGeometry g;
  Box part_a{0, 0, 400, 400}, part_b{1300, 0, 1700, 400};
  double elem_i_at[2] = {200, 200}, elem_ii_at[2] = {500, 700};  // probe positions (plan)
  std::vector<double> slide_at;        // Y of the slide points I..V on the arch
  // Found in setup (StretchSetup) on the distributed mesh:
  PetscInt elem_i = -1, elem_ii = -1;  // scene element ids
  std::vector<PetscInt> slide_nodes;   // arch nodes I..V
  std::vector<double> slide_y;         // their Y on the initial surface
  std::vector<char> in_a, in_b;        // per local element
  std::string history;                 // -saddle_history ("": beside the results)
  PetscInt drawing_stages = 0;
  SaddleShapeNodes shape;              // heights h1, h2 and the middle cutting line (saddle.cpp)
};

// The probes on the distributed mesh: parts A and B (by element centroid), elements I and II
// (centroid nearest to their positions), the slide nodes (nearest to the arch line's points).
PetscErrorCode StretchSetup(Problem *P, void *vctx) {
  auto *c = (StretchContext *)vctx;
  const LocalMesh &m = P->mesh;
  PetscFunctionBeginUser;
  c->in_a.assign(m.num_elements, 0);
  c->in_b.assign(m.num_elements, 0);
  for (PetscInt e = 0; e < m.num_elements; ++e) {
    double cx = 0, cy = 0;
    for (int a = 0; a < 3; ++a) cx += m.X[3 * m.tri[3 * e + a]] / 3, cy += m.X[3 * m.tri[3 * e + a] + 1] / 3;
    c->in_a[e] = c->part_a.Contains(cx, cy);
    c->in_b[e] = c->part_b.Contains(cx, cy);
  }
  PetscCall(ProblemNearestElement(P, c->elem_i_at[0], c->elem_i_at[1], &c->elem_i));
  PetscCall(ProblemNearestElement(P, c->elem_ii_at[0], c->elem_ii_at[1], &c->elem_ii));
  c->slide_nodes.clear(), c->slide_y.clear();
  for (double y : c->slide_at) {
    PetscInt node;
    double x[3];
    PetscCall(ProblemNearestNode(P, c->g.arch_x, y, &node));
    PetscCall(ProblemGetNodePosition(P, nullptr, node, x));
    c->slide_nodes.push_back(node);
    c->slide_y.push_back(x[1]);
  }
  PetscCall(SaddleShapeNodesFind(P, c->g, &c->shape));
  PetscFunctionReturn(0);
}

// Collective: per-probe numbers at the committed state.
struct ProbeValues {
  double a[4], b[4];             // mean Exx, Eyy, Exy, Mises
  double i_smin, i_emin, ii_smin, ii_emin;
  std::vector<double> slide;     // X and Y per slide node
};

PetscErrorCode Measure(Problem *P, StretchContext *c, const CellFields &f, ProbeValues *v) {
  const LocalMesh &m = P->mesh;
  double loc[14] = {0}, glob[14];
  PetscFunctionBeginUser;
  for (PetscInt e = 0; e < m.num_elements; ++e) {
    const PetscInt id = m.element_natural[e];
    for (int part = 0; part < 2; ++part) {
      if (!(part == 0 ? c->in_a : c->in_b)[e]) continue;
      double *acc = &loc[5 * part];
      acc[0] += f.strain[3 * e], acc[1] += f.strain[3 * e + 1], acc[2] += f.strain[3 * e + 2];
      acc[3] += f.mises[e], acc[4] += 1.0;
    }
    if (id == c->elem_i) loc[10] = f.smin[e], loc[11] = f.emin[e];
    if (id == c->elem_ii) loc[12] = f.smin[e], loc[13] = f.emin[e];
  }
  PetscCallMPI(MPI_Allreduce(loc, glob, 14, MPI_DOUBLE, MPI_SUM, P->comm));
  for (int i = 0; i < 4; ++i) {
    v->a[i] = glob[4] > 0 ? glob[i] / glob[4] : 0.0;
    v->b[i] = glob[9] > 0 ? glob[5 + i] / glob[9] : 0.0;
  }
  v->i_smin = glob[10], v->i_emin = glob[11], v->ii_smin = glob[12], v->ii_emin = glob[13];
  std::vector<double> sl(2 * c->slide_nodes.size(), 0.0);
  if (const ContactSet *contact = FindTerm<ContactSet>(*P))
    for (const ContactPair &pr : contact->pairs)
      for (size_t k = 0; k < c->slide_nodes.size(); ++k)
        if (pr.natural_node == c->slide_nodes[k]) {
          const ContactPairReport r = ContactReport(*contact, pr);
          sl[2 * k] = r.slide_global[0];
          sl[2 * k + 1] = r.slide_global[1];
        }
  v->slide.resize(sl.size());
  PetscCallMPI(MPI_Allreduce(sl.data(), v->slide.data(), (int)sl.size(), MPI_DOUBLE, MPI_SUM, P->comm));
  PetscFunctionReturn(0);
}

PetscErrorCode StretchStep(Problem *P, void *vctx, PetscInt step, double t, PetscInt) {
  auto *c = (StretchContext *)vctx;
  CellFields f;
  ProbeValues v;
  PetscFunctionBeginUser;
  const std::string path = CsvHistoryPath(c->history, P->observer.results_stem, "_history.csv");
  if (path.empty()) PetscFunctionReturn(0);
  PetscCall(ComputeCellFields(P, P->U, &f, false));
  PetscCall(Measure(P, c, f, &v));
  // Arch pairs open / sticking / slipping after this increment (the lagged law's stick-slip;
  // the progress line prints the same counts).
  PetscInt status[3] = {0, 0, 0}, status_all[3];
  if (const ContactSet *contact = FindTerm<ContactSet>(*P))
    for (const ContactPair &pr : contact->pairs) status[pr.committed.status]++;
  PetscCallMPI(MPI_Allreduce(status, status_all, 3, MPIU_INT, MPI_SUM, P->comm));
  if (P->rank == 0) {
    std::string header = "step,time,A_Exx,A_Eyy,A_Exy,A_mises,B_Exx,B_Eyy,B_Exy,B_mises,I_smin,I_emin,II_smin,II_emin";
    for (size_t k = 0; k < c->slide_nodes.size(); ++k)
      header += ",slide" + std::to_string(k + 1) + "_X,slide" + std::to_string(k + 1) + "_Y";
    header += ",pairs_open,pairs_stick,pairs_slip,work,shift_work";
    if (P->clock.Active()) header += ",seconds";  // physical time (-load_stage_duration, -load_hold_*)
    FILE *out = CsvHistoryOpen(path, step, header.c_str());
    PetscCheck(out, PETSC_COMM_SELF, PETSC_ERR_FILE_OPEN, "cannot write %s", path.c_str());
    std::fprintf(out, "%lld,%.10g", (long long)step, t);
    for (double x : v.a) std::fprintf(out, ",%.8e", x);
    for (double x : v.b) std::fprintf(out, ",%.8e", x);
    std::fprintf(out, ",%.8e,%.8e,%.8e,%.8e", v.i_smin, v.i_emin, v.ii_smin, v.ii_emin);
    for (double x : v.slide) std::fprintf(out, ",%.8e", x);
    std::fprintf(out, ",%lld,%lld,%lld", (long long)status_all[0], (long long)status_all[1], (long long)status_all[2]);
    // The increment's work on the film and what the tangent shift would dissipate (N mm).
    std::fprintf(out, ",%.8e,%.8e", P->diagnostics.increment_work, P->diagnostics.increment_shift_work);
    if (P->clock.Active()) std::fprintf(out, ",%.10g", P->clock.Seconds(t));
    std::fprintf(out, "\n");
    std::fclose(out);
  }
  PetscFunctionReturn(0);
}

// The PK2 Mises distribution over all elements, sorted on rank 0 (every other rank holds its own
// elements only) and sent to every rank: [0..2] min, median, max of the PK2 Mises, [3..5] of the
// true (Cauchy) Mises, [6] the elements within 10 % of first_yield, [7] their number.
PetscErrorCode MisesDistribution(Problem *P, const CellFields &f, double first_yield, double dist[8]) {
  PetscFunctionBeginUser;
  for (int k = 0; k < 8; ++k) dist[k] = 0.0;
  int n = (int)f.mises.size();
  std::vector<int> counts(P->size), displs(P->size, 0);
  PetscCallMPI(MPI_Gather(&n, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, P->comm));
  for (int r = 1; r < P->size; ++r) displs[r] = displs[r - 1] + counts[r - 1];
  const int N = P->rank == 0 ? displs[P->size - 1] + counts[P->size - 1] : 0;
  std::vector<double> all(N);
  // PK2 Mises (the yield table's measure) and the true (Cauchy) Mises that gauges and other codes
  // report.
  for (int k = 0; k < 2; ++k) {
    const std::vector<double> &mine = k == 0 ? f.mises : f.cauchy_mises;
    PetscCallMPI(MPI_Gatherv(mine.data(), n, MPI_DOUBLE, all.data(), counts.data(), displs.data(), MPI_DOUBLE, 0,
                             P->comm));
    if (P->rank != 0 || all.empty()) continue;
    std::sort(all.begin(), all.end());
    dist[3 * k] = all.front(), dist[3 * k + 1] = all[all.size() / 2], dist[3 * k + 2] = all.back();
    if (k == 0 && first_yield > 0)
      for (double s : all) dist[6] += std::fabs(s - first_yield) <= 0.1 * first_yield;
  }
  dist[7] = N;
  PetscCallMPI(MPI_Bcast(dist, 8, MPI_DOUBLE, 0, P->comm));
  PetscFunctionReturn(0);
}

PetscErrorCode StretchReport(Problem *P, void *vctx) {
  auto *c = (StretchContext *)vctx;
  CellFields f;
  ProbeValues v;
  PetscFunctionBeginUser;
  PetscCall(ComputeCellFields(P, P->U, &f));
  PetscCall(Measure(P, c, f, &v));
  // The film's first yield stress S_y1 (-material_yield's first value); an elastic film has none.
  const PlasticMaterial *plastic = P->material->PlasticLaw();
  const double first_yield = plastic ? plastic->yield[0] : 0.0;
  double dist[8];
  PetscCall(MisesDistribution(P, f, first_yield, dist));
  const int N = (int)dist[7];
  char near[96];  // snprintf: PETSc's %g would write 16 as "16."
  if (plastic)
    std::snprintf(near, sizeof near, "within 10%% of S_y1 = %g: %.1f %%", first_yield, 100.0 * dist[6] / N);
  else
    std::snprintf(near, sizeof near, "no yield stress (elastic film)");
  double loc[4] = {0, 0, 0, 0}, glob[4];  // wrinkled elements (strain, stress) in the middle part, max ep, max |slide|
  for (PetscInt e = 0; e < P->mesh.num_elements; ++e) {
    loc[0] += f.emin[e] < 0;
    loc[1] += f.smin[e] <= 0;
    if (!f.ep_bar.empty()) loc[2] = std::max(loc[2], f.ep_bar[e]);
  }
  // The largest slide of a film node on the arch since the start, measured in the arch's tangent
  // plane (along and across the arch), not its projection on the plan.
  if (const ContactSet *contact = FindTerm<ContactSet>(*P))
    for (const ContactPair &pr : contact->pairs)
    {
      const ContactPairReport r = ContactReport(*contact, pr);
      loc[3] = std::max(loc[3], std::hypot(r.slide_local[0], r.slide_local[1]));
    }
  PetscCallMPI(MPI_Allreduce(loc, glob, 2, MPI_DOUBLE, MPI_SUM, P->comm));
  PetscCallMPI(MPI_Allreduce(loc + 2, glob + 2, 2, MPI_DOUBLE, MPI_MAX, P->comm));
  PetscCall(PetscPrintf(P->comm,
                        "saddle: mises_min = %.4f, mises_median = %.4f, mises_max = %.4f MPa over %d elements; "
                        "%s (2nd Piola-Kirchhoff, the measure of the yield table)\n"
                        "saddle: cauchy_mises_min = %.4f, cauchy_mises_median = %.4f, cauchy_mises_max = %.4f MPa "
                        "(true stress)\n"
                        "saddle: part_A mises = %.4f MPa (PK2; Exx %.5f, Eyy %.5f, Exy %.5f); part_B mises = %.4f MPa "
                        "(Exx %.5f, Eyy %.5f, Exy %.5f)\n"
                        "saddle: element_I emin = %.4e smin = %.4f MPa; element_II emin = %.4e smin = %.4f MPa\n"
                        "saddle: wrinkled elements: strain-based = %.0f, stress-based = %.0f; max plastic_strain_eq = "
                        "%.5f; max arch slide = %.4f mm (along the arch: in its tangent plane, not in plan)\n",
                        dist[0], dist[1], dist[2], N, near, dist[3], dist[4], dist[5], v.a[3], v.a[0], v.a[1],
                        v.a[2], v.b[3], v.b[0], v.b[1], v.b[2], v.i_emin, v.i_smin, v.ii_emin, v.ii_smin, glob[0],
                        glob[1], glob[2], glob[3]));
  if (!f.wrinkle_state.empty()) {
    // -membrane_wrinkling tension_field: the states the relaxed law decided (kernels/wrinkling.h).
    double cnt[3] = {0, 0, 0}, gcnt[3];
    for (double s : f.wrinkle_state) cnt[(int)s] += 1;
    PetscCallMPI(MPI_Allreduce(cnt, gcnt, 3, MPI_DOUBLE, MPI_SUM, P->comm));
    PetscCall(PetscPrintf(P->comm, "saddle: tension_field taut = %.0f, wrinkled = %.0f, slack = %.0f elements\n",
                          gcnt[0], gcnt[1], gcnt[2]));
  }
  for (size_t k = 0; k < c->slide_nodes.size(); ++k)
    PetscCall(PetscPrintf(P->comm, "saddle: slide_%zu (Y = %.0f) X = %.4f mm, Y = %.4f mm\n", k + 1,
                          c->slide_y[k], v.slide[2 * k], v.slide[2 * k + 1]));
  PetscCall(SaddleShapeReport(P, c->g, c->shape, true));  // the saddle heights of thesis L1866-1875
  PetscFunctionReturn(0);
}

// What the stretch options give, defaults included: thesis Table 5.5, DD1511 (the PD schedules
// were only in lost figures: the same by default).
struct StretchInputs {
  std::vector<double> draw[4] = {{10, 20, 30, 40}, {10, 15, 20, 30}, {10, 20, 30, 40}, {10, 20, 30, 40}};  // a, b, c, d
  std::vector<double> gain = {1, 1, 1, 1}, intercept = {0, 0, 0, 0}, pressure;
  std::vector<double> part_a = {0, 0, 400, 400}, part_b = {1300, 0, 1700, 400};
  std::vector<double> elem_i = {200, 200}, elem_ii = {500, 700}, slides = {0, 250, 500, 750, 950};
  PetscInt reference = 0;  // 0: the surface, 1: the flat patterns
  std::string history;
};

// A per-stage option: read (so -help lists it and it counts as used), then replaced by the
// caller's override when there is one (the drawing planner's trial schedule).
PetscErrorCode ReadStageArray(PetscOptionItems *PetscOptionsObject, const StageValues &overrides, const char *name,
                              const char *help, std::vector<double> *v) {
  PetscFunctionBeginUser;
  PetscCall(OptionsRealArray(PetscOptionsObject, name, help, v, nullptr));
  const auto it = overrides.find(name + 1);
  if (it != overrides.end()) *v = it->second;
  PetscFunctionReturn(0);
}

PetscErrorCode ReadStretchOptions(MPI_Comm comm, const StageValues &overrides, StretchInputs *in) {
  static const char *const points[4] = {"a (X = 2000, Y = 0; drawn in X)", "b (the frame corner; in X and Y)",
                                        "c (Y = 1000, X = 1000, the arch's end; in Y)", "d (Y = 1000, X = 0; in Y)"};
  static const char *const names[4] = {"-saddle_draw_a", "-saddle_draw_b", "-saddle_draw_c", "-saddle_draw_d"};
  const char *references[] = {"surface", "pattern"};
  char history[PETSC_MAX_PATH_LEN] = "";
  PetscFunctionBeginUser;
  PetscOptionsBegin(comm, nullptr, "Saddle stretch fabrication", "Scene");
  for (int k = 0; k < 4; ++k) {
    const std::string help = std::string("Drawing at ") + points[k] +
                             " [mm], cumulative: the frame's total drawing there at the end of each stage (stage 1 "
                             "first; 10,20 draws 10 mm in each of two stages)";
    PetscCall(ReadStageArray(PetscOptionsObject, overrides, names[k], help.c_str(), &in->draw[k]));
  }
  PetscCall(ReadStageArray(PetscOptionsObject, overrides, "-saddle_pressure_cycle",
                           "Internal pressure after drawing, one stage per value, the drawing held [kPa] (none by "
                           "default)",
                           &in->pressure));
  // The drawing map and the probes: parts A and B, elements I and II, the slide points.
  const struct {
    const char *name, *help;
    std::vector<double> *v;
  } arrays[] = {
      {"-saddle_gain", "Drawing map slope at a,b,c,d: boundary motion = max(0, gain*draw + intercept)", &in->gain},
      {"-saddle_draw_intercept",
       "Drawing map intercept at a,b,c,d [mm] (thesis Fig. 3.17's regression lines; 0: motion = gain*draw)",
       &in->intercept},
      {"-saddle_part_A",
       "Part A, box x0,y0,x1,y1 in plan [mm]: the middle part's centre (the film between the symmetry plane X = 0 "
       "and the arch); its elements' mean GL strains and PK2 Mises are reported",
       &in->part_a},
      {"-saddle_part_B",
       "Part B, box x0,y0,x1,y1 in plan [mm]: the corner part's centre (the film between the arch at X = 1000 and "
       "the frame); reported as part A",
       &in->part_b},
      {"-saddle_element_I",
       "Element I, x,y in plan [mm]: the element nearest this point (in part A by default); its minimum principal "
       "strain and stress tell whether the middle part wrinkles",
       &in->elem_i},
      {"-saddle_element_II",
       "Element II, x,y in plan [mm]: a second wrinkling probe, in the middle part towards the frame edge c-d by "
       "default",
       &in->elem_ii},
      {"-saddle_slide_points",
       "Y of the arch slide points I..V [mm]: the film nodes on the arch nearest these, whose slide in plan (X, Y) "
       "is reported",
       &in->slides},
  };
  for (const auto &a : arrays) PetscCall(OptionsRealArray(PetscOptionsObject, a.name, a.help, a.v, nullptr));
  PetscCall(PetscOptionsEList("-saddle_reference",
                              "Stress-free state: surface (the form-found shape, as the thesis's analysis) or pattern "
                              "(the flat cutting patterns of the strips, laid on during the first drawing step)",
                              "", references, 2, references[in->reference], &in->reference, nullptr));
  PetscCall(PetscOptionsString("-saddle_history", "Probe history CSV (default beside -output_file)", "", history,
                               history, sizeof history, nullptr));
  PetscOptionsEnd();
  in->history = history;
  const size_t ns = in->draw[0].size();
  PetscCheck(ns >= 1 && in->draw[1].size() == ns && in->draw[2].size() == ns && in->draw[3].size() == ns, comm,
             PETSC_ERR_ARG_SIZ, "-saddle_draw_a/b/c/d must have the same number of stages (now %zu, %zu, %zu, %zu)",
             in->draw[0].size(), in->draw[1].size(), in->draw[2].size(), in->draw[3].size());
  PetscCheck(in->gain.size() == 4 && in->intercept.size() == 4 && in->part_a.size() == 4 && in->part_b.size() == 4 &&
                 in->elem_i.size() == 2 && in->elem_ii.size() == 2,
             comm, PETSC_ERR_ARG_SIZ,
             "-saddle_gain and -saddle_draw_intercept need 4 values (a,b,c,d), -saddle_part_A/B 4 "
             "(x0,y0,x1,y1), -saddle_element_I/II 2 (x,y)");
  for (const auto *arr : {&in->draw[0], &in->draw[1], &in->draw[2], &in->draw[3], &in->gain, &in->intercept,
                          &in->pressure})
    for (double x : *arr)
      PetscCheck(std::isfinite(x), comm, PETSC_ERR_ARG_OUTOFRANGE, "saddle: drawing, gain and pressure values must be finite");
  PetscFunctionReturn(0);
}

// Schedules: the drawing stages, then the pressure cycle with the drawing held; the lay-on of the
// flat patterns with -saddle_reference pattern. ids: the schedules of a, b, c, d.
void AddStretchSchedules(const StretchInputs &in, SceneSpec *scene, int ids[4]) {
  const size_t ns = in.draw[0].size(), np = in.pressure.size(), stages = ns + np;
  // The drawing value is what the frame's screws are turned by; the model's boundary is the line
  // of offset points, which the thesis maps from the drawing value through regression lines
  // (L914, Fig. 3.17; used for the predictions, L1689-1691). The lines themselves are lost with the
  // figures, so slope and intercept are options; the clamp keeps a line with a negative intercept
  // (slack taken up before the film moves) from pushing the boundary inward at small drawings.
  auto extend = [&](const std::vector<double> &v, int k_pos) {
    std::vector<double> out;
    for (size_t k = 0; k < stages; ++k) {
      const double draw = v[std::min(k, ns - 1)];
      const double mag = std::max(0.0, in.gain[k_pos] * std::fabs(draw) + in.intercept[k_pos]);
      out.push_back(draw == 0.0 ? 0.0 : std::copysign(mag, draw));
    }
    return out;
  };
  static const char *const names[4] = {"draw_a", "draw_b", "draw_c", "draw_d"};
  for (int k = 0; k < 4; ++k) ids[k] = scene->AddSchedule({names[k], 0.0, extend(in.draw[k], k), "mm"});
  if (in.reference == 1) {  // not element_reference.empty(): that list is on rank 0 only
    // The film is laid on in the first drawing step: the reference goes from the surface to the
    // flat pattern while the frame draws (pattern_reference.cpp says why not before it).
    const int sl = scene->AddSchedule({"lay_on", 0.0, std::vector<double>(stages, 1.0), ""});
    scene->reference_blend = {{1.0, 0.0}, {sl, -1}};
  }
  if (np > 0) {
    std::vector<double> p(ns, 0.0);
    for (double x : in.pressure) p.push_back(1e-3 * x);  // kPa -> MPa
    const int sp = scene->AddSchedule({"pressure", 0.0, p, "kPa", 1e3});
    scene->pressures.push_back({{}, {{1.0, 0.0}, {sp, -1}}});
  }
}

// Supports of the frame: drawn in plan (a, b, c, d interpolated along the edges), held in Z;
// symmetry planes. on_frame: per scene node.
void AddFrameSupports(const SaddleGeometry &g, const int ids[4], const std::vector<char> &on_frame, SceneSpec *scene) {
  const MeshData &m = scene->mesh;
  const int sa = ids[0], sb = ids[1], sc = ids[2], sd = ids[3];
  const double L = g.half_length, W = g.half_span, A = g.arch_x, tol = 1e-6 * L;
  for (int k = 0; k < m.NumNodes(); ++k) {
    const double x = m.coords[3 * k], y = m.coords[3 * k + 1];
    if (!on_frame[k]) {
      if (std::fabs(x) < tol) scene->constraints.push_back({k, 0, {}});
      if (std::fabs(y) < tol) scene->constraints.push_back({k, 1, {}});
      continue;
    }
    ScheduledValue ux, uy;
    if (std::fabs(x - L) < tol) {  // X-edge: a at Y = 0 to b at the corner
      const double eta = y / W;
      ux = {{1.0 - eta, eta}, {sa, sb}};
      uy = {{eta, 0.0}, {sb, -1}};
    } else if (x <= A) {  // Y-edge, middle part: d at X = 0 to c at the arch
      const double xi = x / A;
      ux = {{0.0, 0.0}, {-1, -1}};
      uy = {{1.0 - xi, xi}, {sd, sc}};
    } else {  // Y-edge, corner part: c at the arch to b at the corner
      const double xi = (x - A) / (L - A);
      ux = {{xi, 0.0}, {sb, -1}};
      uy = {{1.0 - xi, xi}, {sc, sb}};
    }
    if (std::fabs(y) < tol) uy = {};  // on the symmetry plane Y = 0
    scene->constraints.push_back({k, 0, ux});
    scene->constraints.push_back({k, 1, uy});
    scene->constraints.push_back({k, 2, {}});
  }
}

// The arch: a circle in the plane X = 1000 through (Y = +-W, z = 0) and (0, H), friction contact
// with the film's arch nodes off the frame.
void AddArchContact(const SaddleGeometry &g, const std::vector<char> &on_frame, SceneSpec *scene) {
  MeshData &m = scene->mesh;
  SupportSpec arch;
  arch.name = "arch";
  arch.type = "arch";
  arch.radius = g.ArchRadius();
  arch.centre[0] = g.arch_x, arch.centre[1] = 0.0, arch.centre[2] = g.rise - arch.radius;
  arch.axis[0] = 1.0, arch.axis[1] = 0.0, arch.axis[2] = 0.0;
  scene->contact.active = true;
  scene->contact.supports.push_back(arch);
  scene->contact.node_set = "arch_contact";
  for (int k : m.node_sets["arch"])
    if (!on_frame[k]) m.node_sets["arch_contact"].push_back(k);
  scene->contact.search_tol = 1e-3 * g.rise;
}

} // namespace

PetscErrorCode SaddleStretchSetup(MPI_Comm comm, const SaddleGeometry &g, SceneSpec *scene, SceneObserver *observer) {
  StretchInputs in;
  PetscFunctionBeginUser;
  PetscCall(ReadStretchOptions(comm, scene->stage_overrides, &in));
  auto *c = new StretchContext();
  c->g = g;
  c->part_a = {in.part_a[0], in.part_a[1], in.part_a[2], in.part_a[3]};
  c->part_b = {in.part_b[0], in.part_b[1], in.part_b[2], in.part_b[3]};
  c->elem_i_at[0] = in.elem_i[0], c->elem_i_at[1] = in.elem_i[1];
  c->elem_ii_at[0] = in.elem_ii[0], c->elem_ii_at[1] = in.elem_ii[1];
  c->slide_at = in.slides;
  c->drawing_stages = (PetscInt)in.draw[0].size();
  c->history = in.history;
  if (in.reference == 1) {
    const PatternStrips strips{{"middle", "corner"},
                               "-saddle_reference pattern",
                               "saddle",
                               "the flat pattern needs the strips of a form-found surface (-mesh_file written by "
                               "options/saddle/ff_*.opts), not the PD start"};
    PetscCall(PatternReference(comm, scene->mesh, strips, &scene->element_reference));
  }
  scene->stage_options = {{"saddle_draw_a", in.draw[0]}, {"saddle_draw_b", in.draw[1]}, {"saddle_draw_c", in.draw[2]},
                          {"saddle_draw_d", in.draw[3]}, {"saddle_pressure_cycle", in.pressure}};
  // What the figures and reports read back from the results (defaults included).
  scene->result_attributes = {{"saddle_drawing_stages", {(double)in.draw[0].size()}},
                              {"saddle_part_A", in.part_a},
                              {"saddle_part_B", in.part_b},
                              {"saddle_arch_x", {g.arch_x}},
                              {"saddle_element_I", in.elem_i},
                              {"saddle_element_II", in.elem_ii},
                              {"saddle_slide_points", in.slides},
                              {"saddle_pressure_cycle", in.pressure}};
  int ids[4];
  AddStretchSchedules(in, scene, ids);
  std::vector<char> on_frame(scene->mesh.NumNodes(), 0);
  for (int k : scene->mesh.node_sets["frame"]) on_frame[k] = 1;
  AddFrameSupports(g, ids, on_frame, scene);
  AddArchContact(g, on_frame, scene);
  observer->setup = StretchSetup;
  observer->step_monitor = StretchStep;
  observer->report = StretchReport;
  observer->ctx = c;
  observer->destroy = [](void *x) { delete (StretchContext *)x; };
  PetscFunctionReturn(0);
}

} // namespace etfe
