// Friction contact between film nodes and rigid supports (docs/theory.md §5, thesis §4.2.2): pair
// creation by distance to the support, evaluation through the pure contact laws of
// kernels/contact_law.h in the pair's frozen frame, and the commit between load steps.
#include <petscsys.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>
#include <string>

#include "etfe/assembly/assembly.h"
#include "etfe/contact/contact.h"
#include "etfe/base/gather.h"
#include "etfe/base/csv_history.h"
#include "etfe/kernels/contact_frame.h"
#include "etfe/assembly/problem.h"

namespace etfe {

namespace {

// Signed distance of p to the support surface, and the pair's master point and frame.
double SupportProject(const SupportSpec &s, const double p[3], double M[3], double R[9]) {
  if (s.type == "plane") return ContactPlaneFrame(s.centre, s.axis, p, M, R);
  return ContactSupportFrame(s.centre, s.axis, s.radius, p, M, R);
}

} // namespace

namespace {

// Stage s (0-based) covers load times (s, s+1]; the tolerance keeps a stage end that the
// increments reach with round-off above it in its own stage.
size_t StageOf(double time) {
  const double s = std::ceil(time - 1e-9) - 1.0;
  return s <= 0.0 ? 0 : (size_t)s;
}

// Whether a fixed law holds a support's pairs where they touched at t0 (one law throughout), not
// where the last commit left them (a fixed stage after another law).
bool HeldSinceStart(const ContactSet &c, int support) {
  if (c.support_laws.empty() || c.support_laws[support].empty()) return c.stage_laws.empty();
  const std::vector<FrictionLaw> &laws = c.support_laws[support];
  return std::all_of(laws.begin(), laws.end(), [&](FrictionLaw l) { return l == laws[0]; });
}

} // namespace

FrictionLaw ContactLawAt(const ContactSet &c, double time) {
  if (c.stage_laws.empty()) return c.law;
  return c.stage_laws[std::min(StageOf(time), c.stage_laws.size() - 1)];
}

FrictionLaw ContactLawAt(const ContactSet &c, int support, double time) {
  if (c.support_laws.empty() || c.support_laws[support].empty()) return ContactLawAt(c, time);
  const std::vector<FrictionLaw> &laws = c.support_laws[support];
  return laws[std::min(StageOf(time), laws.size() - 1)];
}

// The laws named in names[0..n) (freed here), checked by the option's name.
static PetscErrorCode ParseFrictionLaws(MPI_Comm comm, const std::string &option, char **names, PetscInt n,
                                        std::vector<FrictionLaw> *out) {
  PetscFunctionBeginUser;
  out->clear();
  PetscErrorCode bad = 0;
  for (PetscInt i = 0; i < n; ++i) {
    PetscInt k = 0;
    while (k < kFrictionLawCount && std::strcmp(names[i], kFrictionLawNames[k]) != 0) ++k;
    if (k == kFrictionLawCount && !bad) bad = (PetscErrorCode)(i + 1);
    out->push_back(k < kFrictionLawCount ? (FrictionLaw)k : FrictionLaw::Implicit);
  }
  std::string bad_name = bad ? names[bad - 1] : "";
  for (PetscInt i = 0; i < n; ++i) PetscCall(PetscFree(names[i]));
  PetscCheck(!bad, comm, PETSC_ERR_ARG_WRONG,
             "%s: \"%s\" (entry %d) is not a friction law; use lagged, implicit, none or fixed, one "
             "value or one per stage separated by commas",
             option.c_str(), bad_name.c_str(), (int)bad);
  PetscFunctionReturn(0);
}

PetscErrorCode ContactOptionsFromCommandLine(MPI_Comm comm, double default_kn, double default_search_tol,
                                             ContactOptions *o) {
  static const char *const frames[] = {"frozen", "follow"};
  PetscInt frame = 0;
  PetscInt probes[64] = {0}, nprobe = 64;
  char *law_names[64] = {nullptr};
  PetscInt nlaw = 64;
  PetscBool law_set = PETSC_FALSE;
  PetscFunctionBeginUser;
  o->params.kn = default_kn;
  o->params.kt = -1.0;
  o->params.mu = 0.3;
  o->search_tol = default_search_tol;
  PetscOptionsBegin(comm, nullptr, "Friction contact with rigid supports", "Contact");
  PetscCall(PetscOptionsStringArray("-contact_friction",
                                    "Friction law (default implicit): lagged (thesis), implicit (return map), none, fixed (glued); "
                                    "a comma list gives each stage its law, the last holding for the stages after "
                                    "it (e.g. implicit,fixed: the arch slides while drawing, then holds the film)",
                                    "", law_names, &nlaw, &law_set));
  PetscCall(PetscOptionsReal("-contact_mu", "Coulomb friction coefficient", "", o->params.mu, &o->params.mu, nullptr));
  PetscCall(PetscOptionsReal("-contact_kn", "Normal penalty [N/mm] (default 1e3 E h)", "", o->params.kn,
                             &o->params.kn, nullptr));
  PetscCall(PetscOptionsReal("-contact_kt", "Tangential penalty [N/mm] (default = kn)", "", o->params.kt,
                             &o->params.kt, nullptr));
  PetscCall(PetscOptionsEList("-contact_normal", "Contact frame: frozen (thesis) or follow (large slide)", "",
                              frames, 2, frames[frame], &frame, nullptr));
  PetscCall(PetscOptionsReal("-contact_frictionless_until",
                             "Load time (in stages) up to which the pairs are frictionless (tensioning)", "",
                             o->frictionless_until, &o->frictionless_until, nullptr));
  PetscCall(PetscOptionsReal("-contact_search_tol",
                             "A film node within this distance of a support surface gets a pair [mm]", "",
                             o->search_tol, &o->search_tol, nullptr));
  PetscCall(PetscOptionsReal("-contact_penalty_length",
                             "Penalties per unit length of the contact line: kn, kt hold for a pair whose tributary length "
                             "along its line is this [mm] and scale with it, so refining the mesh keeps the interface's "
                             "stiffness (0: the same kn, kt for every pair, the thesis's)",
                             "", o->penalty_length, &o->penalty_length, nullptr));
  PetscCall(PetscOptionsInt("-contact_lagged_repeat",
                            "Lagged law solved to a status fixed point: an increment is solved again, at most this many "
                            "times, while the stick/slip statuses its commit finds differ from those it was solved with "
                            "(a pair that changes twice slips), and a slipping pair keeps its direction; converges in the "
                            "increment count (20 is ample; 0: the thesis's algorithm, each increment solved once with the "
                            "statuses of its start)",
                            "", o->lagged_repeat, &o->lagged_repeat, nullptr));
  PetscCall(PetscOptionsIntArray("-contact_probe_nodes",
                                 "Film node ids whose contact history is written as CSV beside the results (none by default)",
                                 "", probes, &nprobe, nullptr));
  PetscOptionsEnd();
  PetscCheck(o->lagged_repeat >= 0, comm, PETSC_ERR_ARG_OUTOFRANGE,
             "-contact_lagged_repeat %" PetscInt_FMT ": use 0 (the thesis's lagged law) or a positive limit",
             o->lagged_repeat);
  o->probe_nodes.assign(probes, probes + nprobe);
  if (!law_set) nlaw = 0;
  PetscCall(ParseFrictionLaws(comm, "-contact_friction", law_names, nlaw, &o->stage_laws));
  o->law = o->stage_laws.empty() ? FrictionLaw::Implicit : o->stage_laws[0];
  const bool one_law =
      std::all_of(o->stage_laws.begin(), o->stage_laws.end(), [&](FrictionLaw l) { return l == o->law; });
  o->follow = frame == 1;
  if (o->params.kt < 0) o->params.kt = o->params.kn;
  // Range checks on what was given, before "none" sets mu to zero.
  PetscCheck(o->params.mu >= 0 && std::isfinite(o->params.mu), comm, PETSC_ERR_ARG_OUTOFRANGE,
             "-contact_mu %g: the friction coefficient must be >= 0", o->params.mu);
  PetscCheck(o->params.kn > 0 && o->params.kt > 0 && std::isfinite(o->params.kn) && std::isfinite(o->params.kt),
             comm, PETSC_ERR_ARG_OUTOFRANGE, "-contact_kn %g / -contact_kt %g: penalties must be positive",
             o->params.kn, o->params.kt);
  PetscCheck(o->search_tol > 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "-contact_search_tol %g must be positive",
             o->search_tol);
  PetscCheck(o->penalty_length >= 0 && std::isfinite(o->penalty_length), comm, PETSC_ERR_ARG_OUTOFRANGE,
             "-contact_penalty_length %g must be >= 0 (mm; 0: the same penalties for every pair)", o->penalty_length);
  const bool any_lagged = o->law == FrictionLaw::Lagged ||
                          std::count(o->stage_laws.begin(), o->stage_laws.end(), FrictionLaw::Lagged) > 0;
  PetscCheck(!(o->follow && any_lagged), comm, PETSC_ERR_SUP,
             "-contact_normal follow works with -contact_friction implicit, none or fixed; the lagged "
             "(thesis) law keeps the thesis's frozen frame");
  // A single "none" makes the whole run frictionless; in a list only its stages are (ContactEvaluate).
  o->mu_given = o->params.mu;
  if (one_law && o->law == FrictionLaw::None) o->params.mu = 0.0;
  PetscFunctionReturn(0);
}

// -contact_penalty_length: a pair's tributary length is half the length of the mesh edges that
// join it to other pair nodes. Each rank finds such edges among its own elements (pair_local
// flags its local nodes, ghosts included, that make pairs); the edges, a few per pair, are then
// gathered everywhere and counted once. The pair nodes must form lines (an arch's crown): a node
// with more than two such edges lies in a contact area, where a length means nothing.
static PetscErrorCode ScalePenaltiesByLength(Problem *P, const std::vector<PetscInt> &pair_nodes,
                                             const std::vector<char> &pair_local, ContactSet *c) {
  const LocalMesh &m = P->mesh;
  PetscFunctionBeginUser;
  struct Edge {
    PetscInt a, b;
    double len;
  };
  std::vector<Edge> mine;
  for (PetscInt e = 0; e < m.num_elements; ++e)
    for (int k = 0; k < 3; ++k) {
      const int u = m.tri[3 * e + k], v = m.tri[3 * e + (k + 1) % 3];
      if (!pair_local[u] || !pair_local[v]) continue;
      const double *x = &m.X[3 * u], *y = &m.X[3 * v];
      const double len = std::sqrt((x[0] - y[0]) * (x[0] - y[0]) + (x[1] - y[1]) * (x[1] - y[1]) + (x[2] - y[2]) * (x[2] - y[2]));
      mine.push_back({std::min(m.natural_id[u], m.natural_id[v]), std::max(m.natural_id[u], m.natural_id[v]), len});
    }
  std::vector<Edge> edges;
  PetscCall(AllGatherConcat(P->comm, mine, &edges));
  std::sort(edges.begin(), edges.end(), [](const Edge &x, const Edge &y) { return x.a < y.a || (x.a == y.a && x.b < y.b); });
  edges.erase(std::unique(edges.begin(), edges.end(), [](const Edge &x, const Edge &y) { return x.a == y.a && x.b == y.b; }),
              edges.end());
  std::vector<double> length(pair_nodes.size(), 0.0);
  std::vector<int> degree(pair_nodes.size(), 0);
  for (const Edge &ed : edges)
    for (PetscInt v : {ed.a, ed.b}) {
      const size_t k = std::lower_bound(pair_nodes.begin(), pair_nodes.end(), v) - pair_nodes.begin();
      length[k] += 0.5 * ed.len;
      degree[k]++;
    }
  for (size_t k = 0; k < pair_nodes.size(); ++k)
    PetscCheck(degree[k] >= 1 && degree[k] <= 2, P->comm, PETSC_ERR_ARG_WRONG,
               "-contact_penalty_length: contact node %" PetscInt_FMT " has %d mesh edges to other contact nodes; "
               "penalties per unit length need the contact nodes to form lines (1 or 2 such edges each, as on an "
               "arch's crown line): drop the option for a contact area",
               pair_nodes[k], degree[k]);
  for (ContactPair &pr : c->pairs) pr.k_scale = length[pr.id] / c->penalty_length;
  const auto [shortest, longest] = std::minmax_element(length.begin(), length.end());
  c->k_scale_min = *shortest / c->penalty_length;
  c->k_scale_max = *longest / c->penalty_length;
  PetscFunctionReturn(0);
}

// -contact_<support>_mu and -contact_<support>_friction: a support's own friction coefficient and
// law (per stage, as -contact_friction), over -contact_mu and -contact_friction (collective). A
// -contact_<name>_mu or _friction whose name is no support is refused, naming the supports.
static PetscErrorCode ReadSupportFriction(MPI_Comm comm, int stages, const ContactOptions &o,
                                          const std::vector<SupportSpec> &supports, ContactSet *c) {
  const bool none = o.law == FrictionLaw::None && std::all_of(o.stage_laws.begin(), o.stage_laws.end(),
                                                              [](FrictionLaw l) { return l == FrictionLaw::None; });
  std::vector<double> mu(supports.size());
  std::vector<std::vector<FrictionLaw>> laws(supports.size());
  bool any_mu = false, any_law = false;
  std::string names;
  PetscFunctionBeginUser;
  for (size_t s = 0; s < supports.size(); ++s) {
    const std::string prefix = "contact_" + supports[s].name + "_";
    PetscBool set = PETSC_FALSE, law_set = PETSC_FALSE;
    char *law_names[64] = {nullptr};
    PetscInt nlaw = 64;
    names += (names.empty() ? "" : ", ") + supports[s].name;
    PetscOptionsBegin(comm, prefix.c_str(), ("Friction on rigid support " + supports[s].name).c_str(), "Contact");
    PetscCall(PetscOptionsStringArray("-friction",
                                      "Friction law of this support's pairs (default -contact_friction): lagged, "
                                      "implicit, none or fixed, or one per stage separated by commas",
                                      "", law_names, &nlaw, &law_set));
    if (!law_set) nlaw = 0;
    PetscCall(ParseFrictionLaws(comm, "-" + prefix + "friction", law_names, nlaw, &laws[s]));
    // A support with a law of its own has friction even where the set's "none" made -contact_mu 0.
    mu[s] = !laws[s].empty() ? o.mu_given : c->params.mu;
    PetscCall(PetscOptionsReal("-mu", "Coulomb friction coefficient of this support's pairs (default -contact_mu)", "",
                               mu[s], &mu[s], &set));
    PetscOptionsEnd();
    PetscCheck(mu[s] >= 0 && std::isfinite(mu[s]), comm, PETSC_ERR_ARG_OUTOFRANGE,
               "-%smu %g: the friction coefficient must be >= 0", prefix.c_str(), mu[s]);
    PetscCheck(laws[s].size() <= (size_t)stages, comm, PETSC_ERR_ARG_SIZ,
               "-%sfriction lists %d laws but the analysis has %d stages: give one law, or one per stage",
               prefix.c_str(), (int)laws[s].size(), stages);
    PetscCheck(!(o.follow && std::count(laws[s].begin(), laws[s].end(), FrictionLaw::Lagged) > 0), comm,
               PETSC_ERR_SUP,
               "-contact_normal follow works with -%sfriction implicit, none or fixed; the lagged (thesis) law keeps "
               "the thesis's frozen frame",
               prefix.c_str());
    // "none" throughout is frictionless (as -contact_mu is then), on a support without a law of
    // its own by the set's law.
    const bool own_none = !laws[s].empty() && std::all_of(laws[s].begin(), laws[s].end(),
                                                          [](FrictionLaw l) { return l == FrictionLaw::None; });
    // A coefficient given where the law makes it 0 would be dropped unseen.
    PetscCheck(!(set && mu[s] > 0 && (own_none || (laws[s].empty() && none))), comm, PETSC_ERR_ARG_INCOMP,
               "-%smu %g: support %s is frictionless (%s none): give it a law of its own (-%sfriction implicit, "
               "lagged or fixed) or leave out -%smu",
               prefix.c_str(), mu[s], supports[s].name.c_str(),
               own_none ? ("-" + prefix + "friction").c_str() : "-contact_friction", prefix.c_str(), prefix.c_str());
    if (own_none || (laws[s].empty() && none)) mu[s] = 0.0;
    any_mu |= set || !laws[s].empty();
    any_law |= !laws[s].empty();
  }
  // Left over: -contact_<x>_mu or _friction of a name that is no support (a typo, or a support
  // not listed).
  PetscInt n;
  char **left, **values;
  std::string bad;
  PetscCall(PetscOptionsLeftGet(nullptr, &n, &left, &values));
  for (PetscInt i = 0; i < n && bad.empty(); ++i) {
    const size_t len = std::strlen(left[i]);
    if (std::strncmp(left[i], "contact_", 8) == 0 &&
        ((len > 11 && std::strcmp(left[i] + len - 3, "_mu") == 0) ||
         (len > 17 && std::strcmp(left[i] + len - 9, "_friction") == 0)))
      bad = left[i];
  }
  PetscCall(PetscOptionsLeftRestore(nullptr, &n, &left, &values));
  PetscCheck(bad.empty(), comm, PETSC_ERR_ARG_WRONG,
             "-%s: no such rigid support; -contact_<support>_mu and -contact_<support>_friction take a support of this "
             "scene (%s)",
             bad.c_str(), names.c_str());
  if (any_mu) c->support_mu = mu;
  if (any_law) c->support_laws = laws;
  PetscFunctionReturn(0);
}

static PetscErrorCode ContactCreate(Problem *P, ContactSet *c) {
  const ContactSpec &spec = P->scene.contact;
  ContactOptions o;
  PetscFunctionBeginUser;
  // Default penalties: three orders above the axial film stiffness E h (the thesis's rule).
  PetscCall(ContactOptionsFromCommandLine(P->comm, 1e3 * P->AxialStiffness(), spec.search_tol, &o));
  c->params = o.params;
  c->law = o.law;
  c->follow = o.follow;
  PetscCheck(o.stage_laws.size() <= (size_t)P->scene.NumStages(), P->comm, PETSC_ERR_ARG_SIZ,
             "-contact_friction lists %d laws but the analysis has %d stages: give one law, or one per stage",
             (int)o.stage_laws.size(), P->scene.NumStages());
  // One law (or a list that repeats it) is the single-law run, unchanged.
  if (std::any_of(o.stage_laws.begin(), o.stage_laws.end(), [&](FrictionLaw l) { return l != o.law; }))
    c->stage_laws = o.stage_laws;
  // AddContactTerm marks the tangent non-symmetric from the first stage's law; a later stage
  // with friction needs it too (slip tangent, eq. 4.31).
  PetscCall(ReadSupportFriction(P->comm, P->scene.NumStages(), o, spec.supports, c));
  for (FrictionLaw l : c->stage_laws)
    if (l != FrictionLaw::Fixed && l != FrictionLaw::None && c->MaxMu() > 0)
      PetscCall(MatSetOption(P->J, MAT_SYMMETRIC, PETSC_FALSE));
  for (const std::vector<FrictionLaw> &laws : c->support_laws)
    for (FrictionLaw l : laws)
      if (l != FrictionLaw::Fixed && l != FrictionLaw::None && c->MaxMu() > 0)
        PetscCall(MatSetOption(P->J, MAT_SYMMETRIC, PETSC_FALSE));
  c->frictionless_until = o.frictionless_until;
  c->lagged_repeat = o.lagged_repeat;
  c->probe_nodes = o.probe_nodes;
  c->penalty_length = o.penalty_length;
  const PetscReal tol = o.search_tol;
  c->supports = spec.supports;

  // Candidates: a node set of the mesh, or every node; pairs are made on owned nodes, and
  // pair_local also flags the ghosts that make pairs on their owners (the same test).
  const LocalMesh &m = P->mesh;
  std::vector<char> candidate(m.NumLocal(), 1), pair_local(m.NumLocal(), 0);
  if (!spec.node_set.empty()) PetscCall(ProblemNodeSetFlags(P, spec.node_set.c_str(), &candidate));
  std::vector<std::vector<char>> own(spec.supports.size());  // a support's own candidates (empty: all)
  for (size_t s = 0; s < spec.supports.size(); ++s)
    if (!spec.supports[s].node_set.empty())
      PetscCall(ProblemNodeSetFlags(P, spec.supports[s].node_set.c_str(), &own[s]));
  for (PetscInt l = 0; l < m.NumLocal(); ++l) {
    if (!candidate[l]) continue;
    for (size_t s = 0; s < spec.supports.size(); ++s) {
      if (!own[s].empty() && !own[s][l]) continue;
      ContactPair pr{};
      const double *X = &m.X[3 * l];
      const double d = SupportProject(spec.supports[s], X, pr.M, pr.R);
      if (std::fabs(d) > tol) continue;
      pair_local[l] = 1;
      if (l >= m.num_owned) break;
      pr.local_node = l;
      pr.d0 = d;
      for (int i = 0; i < 3; ++i) pr.X[i] = X[i];
      pr.natural_node = m.natural_id[l];
      pr.support = (int)s;
      // A pair starts touching with zero gap (thesis: contact at t0); the offset d within the
      // search tolerance is round-off or modelling slack, not a preload.
      pr.g0[0] = pr.g0[1] = pr.g0[2] = 0.0;
      pr.committed = ContactState{{0, 0, 0}, {0, 0, 0}, CONTACT_STICK};  // g0 = 0; follow: u = 0, f = 0
      pr.trial = pr.committed;
      c->pairs.push_back(pr);
      break;
    }
  }
  // Global ids in scene node order (pairs are few: gather their node ids everywhere).
  std::vector<PetscInt> mine, all;
  for (const ContactPair &pr : c->pairs) mine.push_back(pr.natural_node);
  PetscCall(AllGatherConcat(P->comm, mine, &all, &c->pair_start));
  c->num_global = (PetscInt)all.size();
  std::sort(all.begin(), all.end());
  for (auto &pr : c->pairs) pr.id = std::lower_bound(all.begin(), all.end(), pr.natural_node) - all.begin();
  PetscCheck(c->num_global > 0, P->comm, PETSC_ERR_ARG_WRONG,
             "contact: no film node lies within -contact_search_tol %g mm of a support; check the "
             "support geometry or raise the tolerance",
             tol);
  if (c->penalty_length > 0) PetscCall(ScalePenaltiesByLength(P, all, pair_local, c));
  {
    // The force-balance test cannot see below the round-off of the penalty forces, about
    // 1e2 eps k |u| sqrt(pairs) (load_stepper.cpp). Against forces of about E h |u| / 10 (|u| per
    // unit force measured 5x (capstan) to 18x (saddle) above 1 / (E h)) that floor is the fraction
    // below of the forces to balance; past kPenaltyFloorMax the test would accept visibly wrong
    // answers (kn 1e15 on the saddle: displacements 20 % off), so refuse before solving.
    const double k = std::max(c->params.kn, c->params.kt) * c->k_scale_max, eh = P->AxialStiffness();
    const double per_k = PenaltyRoundoffFloor(1.0, 10.0 / eh, c->num_global);
    PetscCheck(per_k * k <= kPenaltyFloorMax, P->comm, PETSC_ERR_ARG_OUTOFRANGE,
               "-contact_kn %g / -contact_kt %g: the round-off of forces this stiff (~%.2g of the film forces, with "
               "%" PetscInt_FMT " pairs and E h = %g N/mm) would exceed the force tolerance, so a wrong answer could pass "
               "as converged; the largest usable penalty here is ~%.1e N/mm (the default 1e3 E h = %.3g N/mm is "
               "usually right)",
               c->params.kn, c->params.kt, per_k * k, c->num_global, eh, kPenaltyFloorMax / per_k, 1e3 * eh);
  }
  PetscFunctionReturn(0);
}

PetscErrorCode AddContactTerm(Problem *P) {
  PetscFunctionBeginUser;
  if (!P->scene.contact.active) PetscFunctionReturn(0);
  auto c = std::make_unique<ContactSet>();
  PetscCall(ContactCreate(P, c.get()));
  if (c->law != FrictionLaw::Fixed && c->MaxMu() > 0)
    PetscCall(MatSetOption(P->J, MAT_SYMMETRIC, PETSC_FALSE));  // slip tangent, eq. 4.31
  P->terms.push_back(std::move(c));
  PetscFunctionReturn(0);
}

namespace {

// A pair's parameters: the set's penalties scaled by the pair's share of the contact line, and
// its support's friction coefficient.
ContactParameters PairParameters(const ContactSet &c, const ContactPair &pr) {
  ContactParameters p = c.params;
  p.kn *= pr.k_scale, p.kt *= pr.k_scale;
  if (!c.support_mu.empty()) p.mu = c.support_mu[pr.support];
  return p;
}

// Following frame: the master point is the closest point of the support to the node now. The
// law sees the slide since the last commit in the current tangent plane and the committed
// force carried into the current frame; the tangent keeps the frame fixed within an iteration
// (its rotation contributes O(f / radius), small against the penalties).
int EvaluateFollow(const ContactSet &c, ContactPair &pr, ContactParameters p, const double u[3], FrictionLaw law,
                   bool frictionless, double fg[3], double Kg[9]) {
  double x[3], du[3], g[3], f[3], K[9], fc[3];
  for (int i = 0; i < 3; ++i) x[i] = pr.X[i] + u[i], du[i] = u[i] - pr.committed.g[i];
  const double d = SupportProject(c.supports[pr.support], x, pr.M, pr.R);
  ContactToLocal(pr.R, du, g);
  g[2] = d - pr.d0;
  ContactToLocal(pr.R, pr.committed.f, fc);
  ContactState from{{0, 0, 0}, {fc[0], fc[1], fc[2]}, pr.committed.status};
  if (frictionless || law == FrictionLaw::None) p.mu = 0.0;
  int status;
  if (law == FrictionLaw::Fixed) {
    ContactFixedForce(p, g, f, K);
    for (int i = 0; i < 2; ++i) f[i] += fc[i];
    status = CONTACT_STICK;
  } else {
    status = ContactImplicitForce(p, from, g, f, K);
  }
  ContactToGlobal(pr.R, f, fg);
  for (int i = 0; i < 3; ++i) pr.trial.g[i] = u[i], pr.trial.f[i] = fg[i];
  pr.trial.status = status;
  if (Kg) ContactRotateTangent(pr.R, K, Kg);
  return std::isfinite(fg[0] + fg[1] + fg[2]) ? 0 : 1;
}

} // namespace

ContactPairReport ContactReport(const ContactSet &c, const ContactPair &pr) {
  ContactPairReport r;
  double s[3];
  if (c.follow) {
    ContactToLocal(pr.R, pr.committed.f, r.force);
    ContactToLocal(pr.R, pr.committed.g, s);  // displacement since t0 in the current tangent plane
  } else {
    for (int i = 0; i < 3; ++i) r.force[i] = pr.committed.f[i], s[i] = pr.committed.g[i] - pr.g0[i];
  }
  r.slide_local[0] = s[0], r.slide_local[1] = s[1];
  r.slide_global[0] = pr.R[0] * s[0] + pr.R[3] * s[1];
  r.slide_global[1] = pr.R[1] * s[0] + pr.R[4] * s[1];
  r.status = pr.committed.status;
  return r;
}

int ContactEvaluate(const ContactSet &c, ContactPair &pr, const double u[3], double time,
                    double fg[3], double Kg[9]) {
  const bool frictionless = time <= c.frictionless_until + 1e-12;
  const FrictionLaw law = ContactLawAt(c, pr.support, time);
  ContactParameters params = PairParameters(c, pr);
  if (c.follow) return EvaluateFollow(c, pr, params, u, law, frictionless, fg, Kg);
  double g[3], f[3], K[9];
  ContactToLocal(pr.R, u, g);
  for (int i = 0; i < 3; ++i) g[i] += pr.g0[i];
  int status = pr.committed.status;
  if (law == FrictionLaw::None) params.mu = 0.0;  // a "none" stage of a per-stage list
  if (frictionless && law != FrictionLaw::Fixed) {
    params.mu = 0.0;
    status = ContactImplicitForce(params, pr.committed, g, f, K);
  } else switch (law) {
  case FrictionLaw::Lagged: ContactLaggedForce(params, pr.committed, g, f, K); break;
  case FrictionLaw::Implicit:
  case FrictionLaw::None: status = ContactImplicitForce(params, pr.committed, g, f, K); break;
  case FrictionLaw::Fixed: {
    // A run fixed throughout holds each node where it touched at t0. A fixed stage after
    // another law holds it where the last commit left it, with the force it had: springs from
    // the committed state (the pair no longer slides, whatever its friction did before).
    const bool held_since_t0 = HeldSinceStart(c, pr.support);
    const double *g_from = held_since_t0 ? pr.g0 : pr.committed.g;
    const double dg[3] = {g[0] - g_from[0], g[1] - g_from[1], g[2] - g_from[2]};
    ContactFixedForce(params, dg, f, K);
    if (!held_since_t0)
      for (int i = 0; i < 3; ++i) f[i] += pr.committed.f[i];
    status = CONTACT_STICK;
  } break;
  }
  pr.trial.g[0] = g[0], pr.trial.g[1] = g[1], pr.trial.g[2] = g[2];
  pr.trial.f[0] = f[0], pr.trial.f[1] = f[1], pr.trial.f[2] = f[2];
  pr.trial.status = status;
  ContactToGlobal(pr.R, f, fg);
  if (Kg) ContactRotateTangent(pr.R, K, Kg);
  return std::isfinite(fg[0] + fg[1] + fg[2]) ? 0 : 1;
}

PetscErrorCode ContactCommit(Problem *P, PetscInt counts[4]) {
  ContactSet &c = *FindTerm<ContactSet>(*P);
  const PetscScalar *u;
  PetscInt local[4] = {0, 0, 0, 0};
  PetscFunctionBeginUser;
  PetscCall(VecGetArrayRead(P->U, &u));
  for (ContactPair &pr : c.pairs) {
    const PetscInt l = pr.local_node;
    double fg[3];
    ContactEvaluate(c, pr, &u[3 * l], P->time, fg, nullptr);
    const int before = pr.committed.status;
    if (ContactLawAt(c, pr.support, P->time) == FrictionLaw::Lagged)
      (c.lagged_repeat > 0 ? ContactLaggedCommitSettled : ContactLaggedCommit)(PairParameters(c, pr), pr.committed,
                                                                               pr.trial.g, pr.trial.f, &pr.committed);
    else pr.committed = pr.trial;
    local[pr.committed.status]++;
    if (pr.committed.status == CONTACT_OPEN && before != CONTACT_OPEN) local[3]++;
  }
  PetscCall(VecRestoreArrayRead(P->U, &u));
  PetscInt global[4];
  PetscCallMPI(MPI_Allreduce(local, global, 4, MPIU_INT, MPI_SUM, P->comm));
  for (int i = 0; i < 4; ++i) counts[i] = global[i];
  PetscFunctionReturn(0);
}

PetscErrorCode ContactLaggedBeginStep(Problem *P) {
  PetscFunctionBeginUser;
  for (ContactPair &pr : FindTerm<ContactSet>(*P)->pairs) {
    pr.step_start = pr.solved = pr.committed;
    pr.step_changes = 0;
  }
  PetscFunctionReturn(0);
}

PetscErrorCode ContactLaggedUndoRevise(Problem *P) {
  PetscFunctionBeginUser;
  for (ContactPair &pr : FindTerm<ContactSet>(*P)->pairs) pr.committed = pr.solved;
  PetscFunctionReturn(0);
}

PetscErrorCode ContactLaggedRevise(Problem *P, PetscInt *changed) {
  ContactSet &c = *FindTerm<ContactSet>(*P);
  const PetscScalar *u;
  PetscInt local = 0;
  PetscFunctionBeginUser;
  *changed = 0;
  // Frictionless tensioning runs the return map whatever the law: no statuses to settle.
  const bool frictionless = P->time <= c.frictionless_until + 1e-12;
  if (frictionless) PetscFunctionReturn(0);
  PetscCall(VecGetArrayRead(P->U, &u));
  for (ContactPair &pr : c.pairs) {
    if (ContactLawAt(c, pr.support, P->time) != FrictionLaw::Lagged) continue;
    pr.solved = pr.committed;
    if (pr.committed.status == CONTACT_OPEN || pr.step_changes >= 2) continue;
    double fg[3];
    ContactEvaluate(c, pr, &u[3 * pr.local_node], P->time, fg, nullptr);
    const ContactParameters p = PairParameters(c, pr);
    ContactState next;
    ContactLaggedCommitSettled(p, pr.committed, pr.trial.g, pr.trial.f, &next);
    // A slip status without a direction ran the stick springs: it counts as stick.
    const int ran = ContactLaggedRunsSlip(p, pr.committed) || p.mu == 0.0 ? CONTACT_SLIP : CONTACT_STICK;
    if (next.status == CONTACT_OPEN) {
      // Lifted off at the end of the step: open for the whole of it. The lagged law keeps a pair
      // closed at f_z = 0 exactly, so a pair with no pressure (one at a grip, re-closed by
      // round-off) would otherwise carry its tangential springs through the step unbounded.
      if (pr.trial.f[0] == 0.0 && pr.trial.f[1] == 0.0 && pr.trial.f[2] == 0.0) continue;
      pr.committed = pr.step_start;
      pr.committed.status = CONTACT_OPEN;
      ++local;
      continue;
    }
    if (next.status == ran) continue;
    const int status = ++pr.step_changes >= 2 ? CONTACT_SLIP : next.status;
    if (status == ran) continue;
    ContactLaggedRestartState(p, pr.step_start, status, next.f, &pr.committed);
    ++local;
  }
  PetscCall(VecRestoreArrayRead(P->U, &u));
  PetscCallMPI(MPI_Allreduce(&local, changed, 1, MPIU_INT, MPI_SUM, P->comm));
  PetscFunctionReturn(0);
}

PetscErrorCode ContactWriteProbes(Problem *P, const std::string &stem, PetscInt step, double time) {
  PetscFunctionBeginUser;
  for (PetscInt node : FindTerm<ContactSet>(*P)->probe_nodes)
    for (const ContactPair &pr : FindTerm<ContactSet>(*P)->pairs) {
      if (pr.natural_node != node) continue;
      const std::string path = stem + "_contact_node" + std::to_string((long long)node) + ".csv";
      FILE *f = CsvHistoryOpen(path, step,
                               "step,time,status,slide_x0,slide_y0,slide_X,slide_Y,force_x0,force_y0,force_z0");
      PetscCheck(f, PETSC_COMM_SELF, PETSC_ERR_FILE_OPEN, "cannot write %s", path.c_str());
      const ContactPairReport r = ContactReport(*FindTerm<ContactSet>(*P), pr);
      std::fprintf(f, "%lld,%.10g,%d,%.10e,%.10e,%.10e,%.10e,%.10e,%.10e,%.10e\n", (long long)step, time, r.status,
                   r.slide_local[0], r.slide_local[1], r.slide_global[0], r.slide_global[1], r.force[0], r.force[1],
                   r.force[2]);
      std::fclose(f);
    }
  PetscFunctionReturn(0);
}

} // namespace etfe
