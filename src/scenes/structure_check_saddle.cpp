// The saddle's stretch-fabrication report (-structure_check saddle_stretch; the saddle scene's
// -analysis stretch gives it, options/structure/verify_dd1511_stretch.opts asks for it): parts A
// and B (mean GL strains and PK2 Mises), elements I and II (minimum principal stress and strain:
// wrinkling), the slide of the arch nodes I-V, the Mises distribution and the heights h1, h2; one
// history CSV line per increment. Its lines and columns are read by scripts and tests, so they
// stand in for the structure report (StructureCheckFns::replaces_report).
#include <petscsys.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>

#include "etfe/assembly/assembly.h"
#include "etfe/base/csv_history.h"
#include "etfe/contact/contact.h"
#include "etfe/kernels/plasticity.h"
#include "saddle_geometry.h"
#include "structure_inputs.h"

namespace etfe {

namespace {

// The probes on the distributed mesh: parts A and B (by element centroid), elements I and II
// (centroid nearest to their positions), the slide nodes (nearest to the arch line's points).
PetscErrorCode StretchSetup(Problem *P, SaddleStretchProbes *c) {
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

PetscErrorCode Measure(Problem *P, SaddleStretchProbes *c, const CellFields &f, ProbeValues *v) {
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

PetscErrorCode StretchStep(Problem *P, SaddleStretchProbes *c, PetscInt step, double t) {
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

PetscErrorCode StretchReport(Problem *P, SaddleStretchProbes *c) {
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

} // namespace

PetscErrorCode SaddleStretchCheckSetup(Problem *P, const CheckInput &check) {
  PetscFunctionBeginUser;
  PetscCall(StretchSetup(P, check.saddle.get()));
  PetscFunctionReturn(0);
}

PetscErrorCode SaddleStretchCheckStep(Problem *P, const CheckInput &check, std::vector<double> *, PetscInt step,
                                      double t, PetscInt) {
  PetscFunctionBeginUser;
  PetscCall(StretchStep(P, check.saddle.get(), step, t));
  PetscFunctionReturn(0);
}

PetscErrorCode SaddleStretchCheckReport(Problem *P, const CheckInput &check, std::vector<double> *) {
  PetscFunctionBeginUser;
  PetscCall(StretchReport(P, check.saddle.get()));
  PetscFunctionReturn(0);
}

std::shared_ptr<SaddleStretchProbes> SaddleStretchProbesDefault(double rise, const std::string &history) {
  auto c = std::make_shared<SaddleStretchProbes>();
  c->g.rise = rise;
  c->history = history;
  return c;
}

} // namespace etfe
