// What the general scene reports (structure_inputs.h): per surface group and region the mean GL
// strains and PK2 Mises, the largest Mises (PK2 and Cauchy) and plastic strain and the wrinkled
// elements and their (reference) area; the probes' smallest principal stress and strain
// (elements) and displacement and slide (nodes); the reaction on every supported node group; the rigid supports' pairs and largest slide. One CSV
// line per increment (the history), the same figures in the report after the last one. A probe
// node is named in the report by its scene id, reference position and surface groups, since
// several nodes can share a plan point (a cushion's foils at its centre: the lowest id wins).
#include <petscsys.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "etfe/assembly/assembly.h"
#include "etfe/assembly/chamber.h"
#include "etfe/contact/contact.h"
#include "etfe/base/csv_history.h"
#include "etfe/assembly/layer_contact.h"
#include "structure_inputs.h"

namespace etfe {

namespace {

struct StructureContext {
  std::vector<std::string> items;               // reported element sets
  std::vector<std::string> supports;            // node groups with a prescribed component
  std::vector<double> probe_element_at, probe_node_at;
  std::string history;
  StructureCheckFn check;                       // -structure_check: its step line and report, its state
  CheckInput check_input;
  // Found in setup on the distributed problem:
  std::vector<std::vector<char>> in_item;       // per item, per local element
  std::vector<std::vector<char>> in_support;    // per support group, per local node
  std::vector<PetscInt> probe_elements, probe_nodes;
  std::vector<double> probe_node_X;             // reference X, Y, Z per probe node
  std::vector<std::string> probe_node_groups;   // the surface groups of its elements, comma separated
  std::vector<PetscInt> support_shared;         // per support group: its nodes in another one too
};

// Where a probe node is and which surface groups (element sets but "all") its elements are in.
PetscErrorCode ProbeNodeWhere(Problem *P, PetscInt node, double X[3], std::string *groups) {
  const LocalMesh &m = P->mesh;
  std::vector<double> x(3, 0.0);
  std::vector<int> in(m.element_sets.size(), 0);  // the same names, in the same order, on every rank
  PetscFunctionBeginUser;
  for (PetscInt l = 0; l < m.num_owned; ++l)
    if (m.natural_id[l] == node)
      for (int i = 0; i < 3; ++i) x[i] = m.X[3 * l + i];
  size_t k = 0;
  for (const auto &set : m.element_sets) {
    for (PetscInt e : set.second)
      for (int a = 0; a < 3 && !in[k]; ++a) in[k] = m.natural_id[m.tri[3 * e + a]] == node;
    ++k;
  }
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, x.data(), 3, MPI_DOUBLE, MPI_SUM, P->comm));
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, in.data(), (int)in.size(), MPI_INT, MPI_MAX, P->comm));
  for (int i = 0; i < 3; ++i) X[i] = x[i];
  groups->clear();
  k = 0;
  for (const auto &set : m.element_sets) {
    if (in[k++] && set.first != "all") *groups += (groups->empty() ? "" : ",") + set.first;
  }
  if (groups->empty()) *groups = "all";
  PetscFunctionReturn(0);
}

// Per item: sums of Exx, Eyy, Exy, Mises, count; maxima of Mises, ep; wrinkled count and area.
struct Figures {
  std::vector<double> mean;     // 4 per item
  std::vector<double> peak;     // 4 per item (PK2 Mises, plastic strain, largest displacement, Cauchy Mises)
  std::vector<double> count;    // 3 per item (elements, wrinkled, wrinkled area [m^2])
  std::vector<double> probe_e;  // smin, emin per probe element
  std::vector<double> probe_n;  // uX, uY, uZ, slide X, slide Y per probe node
  std::vector<double> reaction; // 3 per support group
  std::vector<double> chamber;  // gauge pressure [kPa] and volume [m^3] per gas chamber
  PetscInt pairs[3] = {0, 0, 0};
};

PetscErrorCode Setup(Problem *P, void *vctx) {
  auto *c = (StructureContext *)vctx;
  const LocalMesh &m = P->mesh;
  PetscFunctionBeginUser;
  if (c->check.setup) PetscCall(c->check.setup(P, c->check_input));
  if (c->check.replaces_report) PetscFunctionReturn(0);
  c->in_item.assign(c->items.size(), std::vector<char>(m.num_elements, 0));
  for (size_t k = 0; k < c->items.size(); ++k) {
    const auto it = m.element_sets.find(c->items[k]);
    if (it != m.element_sets.end())
      for (PetscInt e : it->second) c->in_item[k][e] = 1;
  }
  c->in_support.resize(c->supports.size());
  for (size_t k = 0; k < c->supports.size(); ++k)
    PetscCall(ProblemNodeSetFlags(P, c->supports[k].c_str(), &c->in_support[k]));
  c->probe_elements.clear(), c->probe_nodes.clear();
  for (size_t k = 0; k + 1 < c->probe_element_at.size(); k += 2) {
    PetscInt e;
    PetscCall(ProblemNearestElement(P, c->probe_element_at[k], c->probe_element_at[k + 1], &e));
    c->probe_elements.push_back(e);
  }
  c->probe_node_X.clear(), c->probe_node_groups.clear();
  for (size_t k = 0; k + 1 < c->probe_node_at.size(); k += 2) {
    PetscInt n;
    double X[3];
    std::string groups;
    PetscCall(ProblemNearestNode(P, c->probe_node_at[k], c->probe_node_at[k + 1], &n));
    PetscCall(ProbeNodeWhere(P, n, X, &groups));
    c->probe_nodes.push_back(n);
    c->probe_node_X.insert(c->probe_node_X.end(), X, X + 3);
    c->probe_node_groups.push_back(groups);
  }
  // A node in two support groups (a corner of two held edges) adds its reaction to both sums.
  c->support_shared.assign(c->supports.size(), 0);
  for (size_t k = 0; k < c->supports.size(); ++k)
    for (PetscInt l = 0; l < m.num_owned; ++l)
      if (c->in_support[k][l])
        for (size_t j = 0; j < c->supports.size(); ++j)
          if (j != k && c->in_support[j][l]) {
            c->support_shared[k]++;
            break;
          }
  if (!c->support_shared.empty())
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, c->support_shared.data(), (int)c->support_shared.size(), MPIU_INT,
                               MPI_SUM, P->comm));
  PetscFunctionReturn(0);
}

PetscErrorCode Measure(Problem *P, StructureContext *c, const CellFields &f, Figures *v) {
  const LocalMesh &m = P->mesh;
  const size_t ni = c->items.size(), npe = c->probe_elements.size(), npn = c->probe_nodes.size();
  PetscFunctionBeginUser;
  // sums: 5 per item, then per item the wrinkled elements and their area, then the probes.
  const size_t probes = 7 * ni;
  std::vector<double> sums(probes + 2 * npe + 5 * npn + 3 * c->supports.size(), 0.0), peaks(4 * ni, 0.0);
  // Displacements of the elements' nodes (ghosts included): each group's largest.
  Vec Ul;
  const PetscScalar *ul;
  PetscCall(GetLocalArray(P->U, P->U_work, &Ul, &ul));
  for (PetscInt e = 0; e < m.num_elements; ++e) {
    double umax = 0.0;  // the element's largest nodal displacement, once for all its groups
    for (int a = 0; a < 3; ++a) {
      const PetscScalar *d = &ul[3 * m.tri[3 * e + a]];
      umax = std::max(umax, (double)std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]));
    }
    for (size_t k = 0; k < ni; ++k) {
      if (!c->in_item[k][e]) continue;
      double *acc = &sums[5 * k];
      acc[0] += f.strain[3 * e], acc[1] += f.strain[3 * e + 1], acc[2] += f.strain[3 * e + 2];
      acc[3] += f.mises[e], acc[4] += 1.0;
      // Wrinkled: the tension field's state where it is on, else a compressive principal stress.
      const bool wrinkled = f.wrinkle_state.empty() ? f.smin[e] <= 0 : f.wrinkle_state[e] != 0;
      sums[5 * ni + k] += wrinkled, sums[6 * ni + k] += wrinkled ? 1e-6 * m.ref[e].area : 0.0;
      peaks[4 * k] = std::max(peaks[4 * k], f.mises[e]);
      if (!f.ep_bar.empty()) peaks[4 * k + 1] = std::max(peaks[4 * k + 1], f.ep_bar[e]);
      peaks[4 * k + 2] = std::max(peaks[4 * k + 2], umax);
      peaks[4 * k + 3] = std::max(peaks[4 * k + 3], f.cauchy_mises[e]);
    }
    for (size_t k = 0; k < npe; ++k)
      if (m.element_natural[e] == c->probe_elements[k]) sums[probes + 2 * k] = f.smin[e], sums[probes + 2 * k + 1] = f.emin[e];
  }
  PetscCall(RestoreLocalArray(P->U_work, &Ul, &ul));
  double *probe_n = &sums[probes + 2 * npe];
  const PetscScalar *u, *r;
  PetscCall(VecGetArrayRead(P->U, &u));
  PetscCall(VecGetArrayRead(P->reaction, &r));
  for (PetscInt l = 0; l < m.num_owned; ++l) {
    for (size_t k = 0; k < npn; ++k)
      if (m.natural_id[l] == c->probe_nodes[k])
        for (int i = 0; i < 3; ++i) probe_n[5 * k + i] = u[3 * l + i];
    for (size_t k = 0; k < c->supports.size(); ++k)
      if (c->in_support[k][l])
        for (int i = 0; i < 3; ++i) probe_n[5 * npn + 3 * k + i] += r[3 * l + i];
  }
  PetscCall(VecRestoreArrayRead(P->reaction, &r));
  PetscCall(VecRestoreArrayRead(P->U, &u));
  PetscInt pairs[3] = {0, 0, 0};
  if (const ContactSet *contact = FindTerm<ContactSet>(*P))
    for (const ContactPair &pr : contact->pairs) {
      pairs[pr.committed.status]++;
      for (size_t k = 0; k < npn; ++k)
        if (pr.natural_node == c->probe_nodes[k]) {
          const ContactPairReport rep = ContactReport(*contact, pr);
          probe_n[5 * k + 3] = rep.slide_global[0], probe_n[5 * k + 4] = rep.slide_global[1];
        }
    }
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, sums.data(), (int)sums.size(), MPI_DOUBLE, MPI_SUM, P->comm));
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, peaks.data(), (int)peaks.size(), MPI_DOUBLE, MPI_MAX, P->comm));
  PetscCallMPI(MPI_Allreduce(pairs, v->pairs, 3, MPIU_INT, MPI_SUM, P->comm));
  v->mean.assign(4 * ni, 0.0), v->count.assign(3 * ni, 0.0);
  for (size_t k = 0; k < ni; ++k) {
    const double n = sums[5 * k + 4];
    for (int i = 0; i < 4; ++i) v->mean[4 * k + i] = n > 0 ? sums[5 * k + i] / n : 0.0;
    v->count[3 * k] = n, v->count[3 * k + 1] = sums[5 * ni + k], v->count[3 * k + 2] = sums[6 * ni + k];
  }
  v->peak = peaks;
  v->probe_e.assign(sums.begin() + probes, sums.begin() + probes + 2 * npe);
  v->probe_n.assign(probe_n, probe_n + 5 * npn);
  v->reaction.assign(probe_n + 5 * npn, probe_n + 5 * npn + 3 * c->supports.size());
  v->chamber.clear();
  if (const ChamberSet *chambers = FindTerm<ChamberSet>(*P)) {
    PetscCall(ChamberUpdate(P, P->U));
    for (size_t k = 0; k < chambers->volume.size(); ++k)
      v->chamber.push_back(1e3 * chambers->gauge[k]), v->chamber.push_back(1e-9 * chambers->volume[k]);
  }
  PetscFunctionReturn(0);
}

std::string Header(const Problem *P, const StructureContext *c, bool contact) {
  std::string h = P->clock.Active() ? "step,time,seconds" : "step,time";  // seconds: -load_stage_duration, holds
  for (const std::string &g : c->items)
    for (const char *k : {"_Exx", "_Eyy", "_Exy", "_mises", "_mises_max", "_ep_max", "_u_max", "_wrinkled",
                          "_cauchy_max", "_wrinkled_m2"})
      h += "," + g + k;
  for (size_t k = 1; k <= c->probe_elements.size(); ++k)
    h += ",element" + std::to_string(k) + "_smin,element" + std::to_string(k) + "_emin";
  for (size_t k = 1; k <= c->probe_nodes.size(); ++k) {
    const std::string n = ",node" + std::to_string(k);
    h += n + "_uX" + n + "_uY" + n + "_uZ";
    if (contact) h += n + "_slide_X" + n + "_slide_Y";
  }
  for (const std::string &g : c->supports) h += "," + g + "_RX," + g + "_RY," + g + "_RZ";
  for (const ChamberSpec &s : P->scene.chambers) h += "," + s.name + "_p_kPa," + s.name + "_V_m3";
  for (const auto &term : P->terms) {  // the physics terms' columns
    std::vector<TermColumn> cols;
    term->Columns(*P, &cols);
    for (const TermColumn &col : cols) h += "," + col.name;
  }
  if (contact) h += ",pairs_open,pairs_stick,pairs_slip";
  return h + ",work,shift_work";
}

PetscErrorCode Step(Problem *P, void *vctx, PetscInt step, double t, PetscInt print_every) {
  auto *c = (StructureContext *)vctx;
  CellFields f;
  Figures v;
  PetscFunctionBeginUser;
  if (c->check.step) PetscCall(c->check.step(P, c->check_input, &c->check.state, step, t, print_every));
  if (c->check.replaces_report) PetscFunctionReturn(0);
  const std::string path = CsvHistoryPath(c->history, P->observer.results_stem, "_history.csv");
  if (path.empty()) PetscFunctionReturn(0);
  PetscCall(ComputeCellFields(P, P->U, &f));
  PetscCall(Measure(P, c, f, &v));
  std::vector<TermColumn> term_columns;  // the physics terms' columns
  if (TermsReportLastEvaluation(*P)) PetscCall(ProblemUpdateReactions(P, P->U));
  for (const auto &term : P->terms) PetscCall(term->Columns(*P, &term_columns));
  if (P->rank != 0) PetscFunctionReturn(0);
  const bool contact = FindTerm<ContactSet>(*P) != nullptr;
  FILE *out = CsvHistoryOpen(path, step, Header(P, c, contact).c_str());
  PetscCheck(out, PETSC_COMM_SELF, PETSC_ERR_FILE_OPEN, "cannot write %s (-structure_history)", path.c_str());
  std::fprintf(out, "%lld,%.10g", (long long)step, t);
  if (P->clock.Active()) std::fprintf(out, ",%.10g", P->clock.Seconds(t));
  for (size_t k = 0; k < c->items.size(); ++k) {
    for (int i = 0; i < 4; ++i) std::fprintf(out, ",%.8e", v.mean[4 * k + i]);
    std::fprintf(out, ",%.8e,%.8e,%.8e,%.0f,%.8e,%.8e", v.peak[4 * k], v.peak[4 * k + 1], v.peak[4 * k + 2],
                 v.count[3 * k + 1], v.peak[4 * k + 3], v.count[3 * k + 2]);
  }
  for (double x : v.probe_e) std::fprintf(out, ",%.8e", x);
  for (size_t k = 0; k < c->probe_nodes.size(); ++k)
    for (int i = 0; i < (contact ? 5 : 3); ++i) std::fprintf(out, ",%.8e", v.probe_n[5 * k + i]);
  for (double x : v.reaction) std::fprintf(out, ",%.8e", x);
  for (double x : v.chamber) std::fprintf(out, ",%.8e", x);
  for (const TermColumn &col : term_columns) std::fprintf(out, ",%.8e", col.value);
  if (contact) std::fprintf(out, ",%lld,%lld,%lld", (long long)v.pairs[0], (long long)v.pairs[1], (long long)v.pairs[2]);
  std::fprintf(out, ",%.8e,%.8e\n", P->diagnostics.increment_work, P->diagnostics.increment_shift_work);
  std::fclose(out);
  PetscFunctionReturn(0);
}

PetscErrorCode Report(Problem *P, void *vctx) {
  auto *c = (StructureContext *)vctx;
  CellFields f;
  Figures v;
  PetscFunctionBeginUser;
  if (c->check.replaces_report) {
    PetscCall(c->check.report(P, c->check_input, &c->check.state));
    PetscFunctionReturn(0);
  }
  PetscCall(ComputeCellFields(P, P->U, &f));
  PetscCall(Measure(P, c, f, &v));
  double cauchy = 0.0, umax = 0.0;
  for (double s : f.cauchy_mises) cauchy = std::max(cauchy, s);
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &cauchy, 1, MPI_DOUBLE, MPI_MAX, P->comm));
  PetscCall(VecMaxNodalNorm(P->U, &umax));
  PetscCall(PetscPrintf(P->comm, "structure: largest displacement %.4f mm, largest true (Cauchy) Mises %.4f MPa\n", umax,
                        cauchy));
  for (size_t k = 0; k < c->items.size(); ++k)
    PetscCall(PetscPrintf(P->comm,
                          "structure: %s (%.0f elements): mean mises = %.4f MPa (PK2; Exx %.5f, Eyy %.5f, Exy %.5f), "
                          "mises_max = %.4f MPa (Cauchy %.4f), plastic_strain_max = %.5f, largest displacement %.4f "
                          "mm, wrinkled = %.0f elements (%.4f m^2)\n",
                          c->items[k].c_str(), v.count[3 * k], v.mean[4 * k + 3], v.mean[4 * k], v.mean[4 * k + 1],
                          v.mean[4 * k + 2], v.peak[4 * k], v.peak[4 * k + 3], v.peak[4 * k + 1], v.peak[4 * k + 2],
                          v.count[3 * k + 1], v.count[3 * k + 2]));
  for (size_t k = 0; k < c->supports.size(); ++k) {
    char shared[160] = "";
    if (c->support_shared[k])
      std::snprintf(shared, sizeof shared,
                    " (%" PetscInt_FMT " of its nodes are in another support group too: nodes shared by two "
                    "groups count in each)", c->support_shared[k]);
    PetscCall(PetscPrintf(P->comm, "structure: support %s reaction = (%.6e, %.6e, %.6e) N%s\n", c->supports[k].c_str(),
                          v.reaction[3 * k], v.reaction[3 * k + 1], v.reaction[3 * k + 2], shared));
  }
  const ContactSet *contact = FindTerm<ContactSet>(*P);
  if (const LayerContactSet *layers = FindTerm<LayerContactSet>(*P))
    PetscCall(PetscPrintf(P->comm,
                          "structure: layer contact: %" PetscInt_FMT " of %" PetscInt_FMT
                          " paired nodes touching the layer below, deepest penetration %.4f mm\n",
                          layers->active, layers->paired, layers->deepest));
  for (size_t k = 0; k < P->scene.chambers.size(); ++k)
    PetscCall(PetscPrintf(P->comm, "structure: chamber %s: gauge pressure %.6f kPa, volume %.6f m^3 (%s)\n",
                          P->scene.chambers[k].name.c_str(), v.chamber[2 * k], v.chamber[2 * k + 1],
                          FindTerm<ChamberSet>(*P)->sealed[k] ? "sealed" : "supplied"));
  {
    std::vector<std::string> lines;  // the physics terms' own lines (the cables': forces, lengths, anchors)
    if (TermsReportLastEvaluation(*P)) PetscCall(ProblemUpdateReactions(P, P->U));  // at the converged state
    for (const auto &term : P->terms) PetscCall(term->Report(*P, &lines));
    for (const std::string &l : lines) PetscCall(PetscPrintf(P->comm, "structure: %s\n", l.c_str()));
  }
  if (contact) {
    double slide = 0.0;
    for (const ContactPair &pr : contact->pairs) {
      const ContactPairReport r = ContactReport(*contact, pr);
      slide = std::max(slide, std::hypot(r.slide_local[0], r.slide_local[1]));
    }
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &slide, 1, MPI_DOUBLE, MPI_MAX, P->comm));
    PetscCall(PetscPrintf(P->comm,
                          "structure: rigid supports: %" PetscInt_FMT " pairs open, %" PetscInt_FMT " sticking, %" PetscInt_FMT
                          " slipping; largest slide %.4f mm (in the support's tangent plane)\n",
                          v.pairs[0], v.pairs[1], v.pairs[2], slide));
  }
  for (size_t k = 0; k < c->probe_elements.size(); ++k)
    PetscCall(PetscPrintf(P->comm,
                          "structure: probe element %zu (nearest plan %.10g, %.10g): scene element %" PetscInt_FMT
                          ", smin = %.4f MPa, emin = %.4e\n",
                          k + 1, c->probe_element_at[2 * k], c->probe_element_at[2 * k + 1], c->probe_elements[k],
                          v.probe_e[2 * k], v.probe_e[2 * k + 1]));
  for (size_t k = 0; k < c->probe_nodes.size(); ++k) {
    char slide[96] = "";
    if (contact) std::snprintf(slide, sizeof slide, ", slide (%.4f, %.4f) mm", v.probe_n[5 * k + 3], v.probe_n[5 * k + 4]);
    const double *X = &c->probe_node_X[3 * k];
    PetscCall(PetscPrintf(P->comm,
                          "structure: probe node %zu (nearest plan %.10g, %.10g): scene node %" PetscInt_FMT
                          " at (%.17g, %.17g, %.17g) mm in %s, u = (%.4f, %.4f, %.4f) mm%s\n",
                          k + 1, c->probe_node_at[2 * k], c->probe_node_at[2 * k + 1], c->probe_nodes[k], X[0], X[1],
                          X[2], c->probe_node_groups[k].c_str(), v.probe_n[5 * k], v.probe_n[5 * k + 1],
                          v.probe_n[5 * k + 2], slide));
  }
  if (c->check.report) PetscCall(c->check.report(P, c->check_input, &c->check.state));
  PetscFunctionReturn(0);
}

} // namespace

PetscErrorCode StructureObserverCreate(const StructureInputs &in, StructureCheckFn check, SceneObserver *observer) {
  PetscFunctionBeginUser;
  auto *c = new StructureContext();
  c->check = check, c->check_input = in.check;
  c->items = in.report;
  if (c->items.empty()) {
    c->items = in.element_groups;
    for (const RegionInput &r : in.regions) c->items.push_back(r.name);
  }
  for (const BcInput &bc : in.bcs)
    if (!bc.fix.empty() || bc.move[0].Given() || bc.move[1].Given() || bc.move[2].Given() || !bc.gradient.empty() ||
        bc.rotation != 0.0)
      c->supports.push_back(bc.group);
  c->probe_element_at = in.probe_elements;
  c->probe_node_at = in.probe_nodes;
  c->history = in.history;
  observer->setup = Setup;
  observer->step_monitor = Step;
  observer->report = Report;
  observer->ctx = c;
  observer->destroy = [](void *x) { delete (StructureContext *)x; };
  if (!check.state.empty()) {
    observer->state_get = [](void *x, std::vector<double> *v) { *v = ((StructureContext *)x)->check.state; };
    observer->state_set = [](void *x, const std::vector<double> &v) { ((StructureContext *)x)->check.state = v; };
  }
  PetscFunctionReturn(0);
}

PetscErrorCode StructureCheckObserverCreate(const StructureInputs &in, StructureCheckFn check, SceneObserver *observer) {
  PetscFunctionBeginUser;
  auto *c = new StructureContext();
  c->check = check, c->check_input = in.check;
  observer->report = [](Problem *P, void *x) {
    auto *ctx = (StructureContext *)x;
    return ctx->check.report(P, ctx->check_input, &ctx->check.state);
  };
  observer->ctx = c;
  observer->destroy = [](void *x) { delete (StructureContext *)x; };
  PetscFunctionReturn(0);
}

} // namespace etfe
