// Rigid contact as a physics term (contact.h): what the problem's loops ask of the pairs.
#include <algorithm>
#include <cstdio>

#include "etfe/contact/contact.h"
#include "etfe/base/fnv64.h"
#include "etfe/kernels/status.h"
#include "etfe/base/log_events.h"
#include "etfe/assembly/problem.h"

namespace etfe {

PetscErrorCode ContactSet::AddLocalForces(Problem &P, const PetscScalar *u, PetscScalar *f,
                                          int *status, double *) {
  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(LogEvents().contact, 0, 0, 0, 0));
  for (ContactPair &pr : pairs) {
    const PetscInt l = pr.local_node;
    double fg[3];
    if (ContactEvaluate(*this, pr, &u[3 * l], P.time, fg, nullptr)) {
      *status = std::max(*status, (int)KERNEL_NONFINITE);
      continue;
    }
    for (int i = 0; i < 3; ++i)
      f[3 * l + i] += fg[i];
  }
  PetscCall(PetscLogEventEnd(LogEvents().contact, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

// A pair's block on its own node's diagonal, the rows and columns of held DOFs left out.
PetscErrorCode ContactSet::AddTangent(Problem &P, Vec, const PetscScalar *u, Mat A) {
  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(LogEvents().contact, 0, 0, 0, 0));
  for (ContactPair &pr : pairs) {
    const PetscInt l = pr.local_node;
    double fg[3], K[9];
    ContactEvaluate(*this, pr, &u[3 * l], P.time, fg, K);
    for (int i = 0; i < 3; ++i)
      if (P.dof_constrained[3 * l + i])
        for (int j = 0; j < 3; ++j)
          K[3 * i + j] = K[3 * j + i] = 0.0;
    PetscCall(MatSetValuesBlockedLocal(A, 1, &l, 1, &l, K, ADD_VALUES));
  }
  PetscCall(PetscLogEventEnd(LogEvents().contact, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

PetscErrorCode ContactSet::Commit(Problem &P, double) {
  return ContactCommit(&P, counts);
}

// Per pair: gap or displacement (3), force (3), status.
const TermDatasetInfo ContactSet::kCheckpoint = {"contact_state", Layout::Pairs, false, 7};

PetscErrorCode ContactSet::State(const Problem &, std::vector<TermData> *blocks) const {
  TermData d;
  d.name = kCheckpoint.name;
  d.layout = kCheckpoint.layout;
  d.components = kCheckpoint.components;
  d.values.resize(7 * pairs.size());
  for (size_t k = 0; k < pairs.size(); ++k) {
    const ContactState &c = pairs[k].committed;
    for (int i = 0; i < 3; ++i)
      d.values[7 * k + i] = c.g[i], d.values[7 * k + 3 + i] = c.f[i];
    d.values[7 * k + 6] = c.status;
  }
  blocks->push_back(std::move(d));
  return 0;
}

PetscErrorCode ContactSet::Restore(Problem &, const std::vector<TermData> &blocks) {
  for (const TermData &d : blocks) {
    if (d.name != kCheckpoint.name) continue;
    for (size_t k = 0; k < pairs.size(); ++k) {
      ContactState &c = pairs[k].committed;
      for (int i = 0; i < 3; ++i)
        c.g[i] = d.values[7 * k + i], c.f[i] = d.values[7 * k + 3 + i];
      c.status = (int)d.values[7 * k + 6];
      pairs[k].trial = c;
    }
  }
  return 0;
}

PetscErrorCode ContactSet::BeginRepeats(Problem &P) {
  return ContactLaggedBeginStep(&P);
}
PetscErrorCode ContactSet::Revise(Problem &P, PetscInt *changed) {
  return ContactLaggedRevise(&P, changed);
}
PetscErrorCode ContactSet::UndoRevise(Problem &P) {
  return ContactLaggedUndoRevise(&P);
}

// A penalty force k w is computed from displacements of size |u|, so it carries a round-off of
// about eps k |u| per pair: no Newton iterate can balance below that.
PetscErrorCode ContactSet::ForceFloor(Problem &P, Vec X, double fnorm, double tol, double *floor) {
  PetscReal umax;
  PetscFunctionBeginUser;
  PetscCall(VecNorm(X, NORM_INFINITY, &umax));
  const double k = std::max(params.kn, params.kt) * k_scale_max;
  const double mine = PenaltyRoundoffFloor(k, umax, num_global);
  const double scale = P.diagnostics.force_scale;
  // Accepting on a floor that is a visible part of the forces would report a wrong answer as
  // converged; ContactCreate refuses most such penalties up front, this catches the rest.
  PetscCheck(!(fnorm > tol && fnorm <= mine && mine > kPenaltyFloorMax * scale), P.comm,
             PETSC_ERR_ARG_OUTOFRANGE,
             "-contact_kn %g / -contact_kt %g: the round-off of the penalty forces (%.3g N) is "
             "%.2g of the forces "
             "balanced (%.3g N), above the force tolerance of the test (%g of them), so this "
             "answer cannot be "
             "checked; the largest usable penalty here is ~%.1e N/mm",
             params.kn, params.kt, mine, mine / scale, scale, kPenaltyFloorMax,
             k * kPenaltyFloorMax * scale / mine);
  *floor = std::max(*floor, mine);
  PetscFunctionReturn(0);
}

void ContactSet::Fingerprint(Fnv64 &h) const {
  h.Add(params.kn), h.Add(params.kt), h.Add(params.mu), h.Add(law), h.Add(follow);
  h.Add(frictionless_until), h.Add(num_global);
  // A law per stage; a single law adds nothing, so its fingerprint is unchanged.
  if (!stage_laws.empty()) {
    h.Add(std::string("stage_laws")), h.Add(stage_laws.size());
    for (FrictionLaw l : stage_laws)
      h.Add((int)l);
  }
  // A coefficient per support; none adds nothing, so the fingerprint of such runs is unchanged.
  if (!support_mu.empty()) h.Add(std::string("support_mu")), h.Add(support_mu);
  if (!support_laws.empty()) {
    h.Add(std::string("support_laws"));
    for (const std::vector<FrictionLaw> &laws : support_laws) {
      h.Add(laws.size());
      for (FrictionLaw l : laws) h.Add((int)l);
    }
  }
  // Penalties per unit length; off adds nothing, so the fingerprint of such runs is unchanged.
  if (penalty_length > 0) h.Add(std::string("penalty_length")), h.Add(penalty_length);
}

bool ContactSet::PairRows(PetscInt *n, PetscInt *first, std::vector<PetscInt> *ids) const {
  *n = num_global, *first = pair_start;
  ids->clear();
  for (const ContactPair &pr : pairs)
    ids->push_back(pr.id);
  return true;
}

// Penalties three orders above the film's stiffness delay pivots.
TermSolverNeeds ContactSet::SolverNeeds() const {
  TermSolverNeeds n;
  n.penalty = true;
  return n;
}

PetscErrorCode ContactSet::SetupLines(const Problem &, std::vector<std::string> *lines) const {
  char buf[256];
  PetscFunctionBeginUser;
  if (!support_mu.empty()) {
    std::string line = "contact: friction coefficient per support (-contact_<support>_mu):";
    for (size_t s = 0; s < supports.size(); ++s) {
      PetscCall(PetscSNPrintf(buf, sizeof buf, "%s %s %g", s ? "," : "", supports[s].name.c_str(), support_mu[s]));
      line += buf;
      // Its own law (-contact_<support>_friction), per stage.
      if (!support_laws.empty() && !support_laws[s].empty()) {
        line += " (";
        for (size_t k = 0; k < support_laws[s].size(); ++k)
          line += std::string(k ? "," : "") + kFrictionLawNames[(int)support_laws[s][k]];
        line += ")";
      }
    }
    lines->push_back(line);
  }
  if (penalty_length <= 0) PetscFunctionReturn(0);
  PetscCall(PetscSNPrintf(buf, sizeof buf,
                          "contact: %" PetscInt_FMT
                          " pairs, penalties per unit length (kn %g, kt %g N/mm at a tributary "
                          "length of %g mm; pair factors %.3g-%.3g)",
                          num_global, params.kn, params.kt, penalty_length, k_scale_min, k_scale_max));
  lines->push_back(buf);
  PetscFunctionReturn(0);
}

// The pair states after the last commit; pairs that lift off between two printed lines are
// counted, not each printed.
std::string ContactSet::Progress(bool printed) {
  lifted_since_print += counts[3];
  if (!printed) return "";
  char buf[128], lifted[64] = "";
  if (lifted_since_print)
    std::snprintf(lifted, sizeof lifted, " (%lld lift-offs since the last line)", (long long)lifted_since_print);
  std::snprintf(buf, sizeof buf, "  contact open %lld stick %lld slip %lld%s", (long long)counts[0],
                (long long)counts[1], (long long)counts[2], lifted);
  lifted_since_print = 0;
  return buf;
}

PetscErrorCode ContactSet::IncrementOutput(Problem &P, const std::string &stem, PetscInt step, double t) {
  return ContactWriteProbes(&P, stem, step, t);
}

// Penalties this much stiffer than the film's axial stiffness make the line search's residual
// round-off noise near the pairs.
std::string ContactSet::LineSearchHint(const Problem &P) const {
  if (params.kn > 1e5 * P.AxialStiffness()) return "the contact penalties are very stiff: try a smaller -contact_kn/-contact_kt";
  return "";
}

} // namespace etfe
