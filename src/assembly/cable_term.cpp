// The cable term: every cable of the scene (SceneSpec::cables) on the problem's term list.
//
// Cables are small beside the film (hundreds of nodes, not hundreds of thousands), so each rank
// keeps the whole of every cable: before each residual and Jacobian the current positions of the
// cable nodes are summed over the ranks (each node's owner gives it, the others zero), and every
// rank evaluates every cable the same way. A rank then adds the forces and the tangent rows of the
// cable nodes it owns. So the cable forces do not depend on the partition (1 rank or 2: the same
// numbers), and a sliding cable's single force, which depends on the whole chain, needs no more
// communication than that.
//
// Tension only: a slack segment (or a slack sliding cable) carries nothing and adds no stiffness;
// Newton stays regular because every cable node is a film node (the set-up refuses others), and
// the film's own stiffness holds a node whose cables are slack.
//
// Clamps (CableSpec::clamps, kernels/cable_clamp.h): a sliding cable with clamps is evaluated by
// CableClamped over its whole chain, one force per sub-chain between clamps; the stress-free length
// each clamp has passed on (its transfer) is the term's history: the return map starts from the
// committed transfers, Commit adds the converged increment's slip, and the checkpoint holds them.
// Its tangent (dense over the chain, not symmetric where a clamp slips) goes into the matrix.
// A sliding cable's interior node held in x, y and z is a pulley (a saddle when it is a clamp):
// the report gives its reaction.
//
// Form finding (P->scene.form_finding): a cable carries its prescribed force T whatever its length
// (kernels/cable.h: CableSegmentConstantForce; a target sag is such a T, found by the scene), or
// with a force density q each segment carries q times its current length (CableSegmentForceDensity);
// each segment's stress-free (cut) length is then found from its force and EA (CableLengthForForce)
// and their sum reported.
#include "etfe/assembly/cable_term.h"

#include <algorithm>
#include <cmath>
#include <set>
#include <unordered_map>

#include "etfe/base/fnv64.h"
#include "etfe/kernels/cable.h"
#include "etfe/kernels/cable_clamp.h"
#include "etfe/kernels/status.h"
#include "etfe/assembly/physics_term.h"

namespace etfe {

namespace {

struct Cable {
  const CableSpec *spec = nullptr;
  int first = 0, count = 0;  // its nodes: entries first .. first + count - 1 of the term's arrays
  std::vector<double> L0;    // stress-free length per segment [mm]
  double L0_total = 0.0;
  // At the last evaluation:
  std::vector<CableState> segment;  // per segment (a sliding cable: its one state in chain)
  CableState chain;                 // whole cable: length, (sliding) force
  double weight = 0.0;              // N/mm
  // Clamps (a sliding cable): chain indices, per sub-chain the initial stress-free length, per
  // clamp the committed transfer [mm] (+: towards the chain's last end) and the last committed
  // increment's status and slip; the last evaluation's return map.
  std::vector<int> clamp, clamp_node;
  std::vector<double> L0_sub, transfer, last_delta;
  std::vector<int> last_status;
  CableClampState clamp_state{};
  std::vector<int> pulleys;  // sliding: chain indices of interior nodes held in x, y and z
  // The committed stress-free length per sub-chain.
  void CommittedLengths(double *L0c) const {
    const int nc = (int)clamp.size();
    for (int j = 0; j <= nc; ++j) L0c[j] = L0_sub[j] - (j < nc ? transfer[j] : 0.0) + (j > 0 ? transfer[j - 1] : 0.0);
  }
};

class CableTerm : public PhysicsTerm {
 public:
  const char *Name() const override { return "cables"; }
  bool ReportsLastEvaluation() const override { return true; }
  PetscErrorCode SetUp(Problem &P) override;
  PetscErrorCode Prepare(Problem &P, const PetscScalar *u) override;
  PetscErrorCode AddLocalForces(Problem &P, const PetscScalar *u, PetscScalar *f, int *status, double *external2) override;
  PetscErrorCode AddInternalForces(Problem &P, const PetscScalar *u, PetscScalar *f) override;
  PetscErrorCode AddTangent(Problem &P, Vec U, const PetscScalar *u, Mat A) override;
  PetscErrorCode Columns(const Problem &P, std::vector<TermColumn> *columns) const override;
  PetscErrorCode Fields(const Problem &P, std::vector<TermData> *fields) const override;
  PetscErrorCode Report(const Problem &P, std::vector<std::string> *lines) const override;
  PetscErrorCode Commit(Problem &P, double t) override;
  PetscErrorCode State(const Problem &P, std::vector<TermData> *blocks) const override;
  PetscErrorCode Restore(Problem &P, const std::vector<TermData> &blocks) override;
  void Fingerprint(Fnv64 &h) const override;
  PetscErrorCode ForceFloor(Problem &P, Vec X, double fnorm, double tol, double *floor) override;
  // The largest move in U of a cable node across its cable (along the cable a node may drift: the
  // constant force on both sides does not hold it there, and that drift does not change the shape).
  PetscErrorCode LargestMove(Problem &P, Vec U, PetscReal *move);

 private:
  void Evaluate(const Problem &P);
  PetscErrorCode AddRows(Problem &P, Mat A, int row_entry, const std::vector<int> &col_entries, const double *K,
                         int ncols_total, int row_offset);

  std::vector<Cable> cables_;
  std::vector<PetscInt> local_;  // per entry: local node id when this rank owns it, else -1
  std::vector<PetscInt> gid_;    // per entry: PETSc node id
  std::vector<char> con_;        // per entry: 3 flags, the DOF is prescribed
  std::vector<double> x_;        // per entry: 3 current coordinates
  std::vector<double> fint_;     // per entry: 3, cable internal force minus its weight (residual part)
  std::vector<double> wload_;    // per entry: 3, the weight's nodal load
  bool form_finding_ = false;
  bool clamped_ = false;         // some cable has clamps (the checkpoint block, the fingerprint)
  // eps sqrt(sum over segments of (EA / L0)^2) [N/mm]: times the coordinates' size, the round-off
  // of the cables' forces (ForceFloor).
  double roundoff_per_x_ = 0.0;
  bool clamp_failed_ = false;    // the last evaluation: a clamp return map did not converge
};

PetscErrorCode CableTerm::SetUp(Problem &P) {
  const LocalMesh &m = P.mesh;
  PetscFunctionBeginUser;
  form_finding_ = P.scene.form_finding;
  PetscCheck(!P.unassembled, P.comm, PETSC_ERR_SUP,
             "cables with an unassembled matrix (-mat_type is): not supported; use the default matrix type");
  std::unordered_map<int, int> natural;  // scene id -> first entry (for ownership lookup)
  int entries = 0;
  for (const CableSpec &s : P.scene.cables) {
    Cable c;
    c.spec = &s, c.first = entries, c.count = (int)s.nodes.size();
    entries += c.count;
    cables_.push_back(c);
  }
  std::unordered_map<int, std::vector<int>> entries_of;
  for (const Cable &c : cables_)
    for (int k = 0; k < c.count; ++k) entries_of[c.spec->nodes[k]].push_back(c.first + k);
  local_.assign(entries, -1);
  std::vector<PetscInt> owners(entries, 0), gid(entries, 0), con(3 * entries, 0);
  std::vector<double> X(3 * entries, 0.0);
  for (PetscInt l = 0; l < m.num_owned; ++l) {
    const auto it = entries_of.find((int)m.natural_id[l]);
    if (it == entries_of.end()) continue;
    for (int k : it->second) {
      local_[k] = l, owners[k] = 1, gid[k] = m.global_id[l];
      for (int i = 0; i < 3; ++i) con[3 * k + i] = P.dof_constrained[3 * l + i], X[3 * k + i] = m.X[3 * l + i];
    }
  }
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, owners.data(), entries, MPIU_INT, MPI_SUM, P.comm));
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, gid.data(), entries, MPIU_INT, MPI_SUM, P.comm));
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, con.data(), 3 * entries, MPIU_INT, MPI_MAX, P.comm));
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, X.data(), 3 * entries, MPI_DOUBLE, MPI_SUM, P.comm));
  for (const Cable &c : cables_)
    for (int k = 0; k < c.count; ++k)
      PetscCheck(owners[c.first + k] == 1, P.comm, PETSC_ERR_PLIB, "cable %s: node %d is owned by %d ranks",
                 c.spec->name.c_str(), c.spec->nodes[k], (int)owners[c.first + k]);
  gid_ = gid;
  con_.assign(con.begin(), con.end());
  x_ = X;
  fint_.assign(3 * entries, 0.0);
  wload_.assign(3 * entries, 0.0);
  // Stress-free lengths from the reference geometry: as meshed, scaled to the given length, or
  // shortened for the prestress (docs/theory.md §14: L0 = L / (1 + T / EA)).
  for (Cable &c : cables_) {
    const CableSpec &s = *c.spec;
    double total = 0.0;
    for (int k = 0; k + 1 < c.count; ++k) {
      const double *a = &X[3 * (c.first + k)], *b = a + 3;
      const double L = std::sqrt((b[0] - a[0]) * (b[0] - a[0]) + (b[1] - a[1]) * (b[1] - a[1]) + (b[2] - a[2]) * (b[2] - a[2]));
      PetscCheck(L > 0, P.comm, PETSC_ERR_ARG_WRONG, "cable %s: its segment %d has zero length in the mesh",
                 s.name.c_str(), k);
      c.L0.push_back(L), total += L;
    }
    for (double &L : c.L0) L = s.length > 0 ? L * s.length / total : CableLengthForForce(L, s.prestress, s.EA);
    for (double L : c.L0) c.L0_total += L;
    // A segment's length from coordinates of size |x| carries eps |x| of round-off, its force
    // that times EA / L0 (form finding: a constant force T turning by eps |x| / L0; a force
    // density q: q times it).
    for (double L : c.L0) {
      const double k = form_finding_ && s.force_density > 0 ? s.force_density : (form_finding_ ? s.prestress : s.EA) / L;
      roundoff_per_x_ += k * k;
    }
    c.segment.assign(c.count - 1, CableState());
    if (!s.sliding || form_finding_) continue;
    // Pulleys and clamps (scene checks: clamps are interior nodes of a sliding cable).
    for (int k = 1; k + 1 < c.count; ++k)
      if (con[3 * (c.first + k)] && con[3 * (c.first + k) + 1] && con[3 * (c.first + k) + 2]) c.pulleys.push_back(k);
    if (s.clamps.empty()) continue;
    PetscCheck((int)s.clamps.size() <= kCableMaxClamps, P.comm, PETSC_ERR_SUP,
               "cable %s: %d clamps and saddles; a cable takes at most %d (split it into several 1-D groups)",
               s.name.c_str(), (int)s.clamps.size(), kCableMaxClamps);
    for (int k = 1; k + 1 < c.count; ++k)
      if (std::find(s.clamps.begin(), s.clamps.end(), s.nodes[k]) != s.clamps.end())
        c.clamp.push_back(k), c.clamp_node.push_back(s.nodes[k]);
    const int nc = (int)c.clamp.size();
    c.L0_sub.assign(nc + 1, 0.0);
    for (int k = 0, j = 0; k + 1 < c.count; ++k) {
      if (j < nc && k == c.clamp[j]) ++j;
      c.L0_sub[j] += c.L0[k];
    }
    c.transfer.assign(nc, 0.0), c.last_delta.assign(nc, 0.0), c.last_status.assign(nc, 0);
    clamped_ = true;
  }
  // A slipping clamp's tangent is not symmetric (the capstan ratio couples the two sides unequally).
  if (clamped_) PetscCall(MatSetOption(P.J, MAT_SYMMETRIC, PETSC_FALSE));
  // A sliding cable couples all its nodes (a dense rank-one block) and a cable may join film
  // nodes no triangle shares: both are nonzeros the film's preallocation lacks.
  PetscCall(MatSetOption(P.J, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_FALSE));
  PetscFunctionReturn(0);
}

// Every cable at x_: segment states, the internal forces (minus the weight) per entry.
void CableTerm::Evaluate(const Problem &P) {
  clamp_failed_ = false;
  std::fill(fint_.begin(), fint_.end(), 0.0);
  std::fill(wload_.begin(), wload_.end(), 0.0);
  for (Cable &c : cables_) {
    const CableSpec &s = *c.spec;
    double *x = &x_[3 * c.first], *f = &fint_[3 * c.first], *w = &wload_[3 * c.first];
    c.chain = CableState();
    if (!form_finding_ && !c.clamp.empty()) {
      // Sub-chains between clamps, each its own force (kernels/cable_clamp.h).
      double L0c[kCableMaxClamps + 1];
      c.CommittedLengths(L0c);
      CableClamped(c.count, x, (int)c.clamp.size(), c.clamp.data(), L0c, s.EA, s.mu, f, nullptr, &c.clamp_state);
      const CableClampState &cs = c.clamp_state;
      clamp_failed_ |= !cs.result.converged;
      c.chain.slack = true;
      for (int k = 0, j = 0; k + 1 < c.count; ++k) {
        if (j < (int)c.clamp.size() && k == c.clamp[j]) ++j;
        double scratch[6];
        c.segment[k].length = CableSlidingSegment(&x[3 * k], 0.0, 0.0, scratch, nullptr);
        c.segment[k].force = cs.force[j], c.segment[k].slack = !(cs.length[j] > cs.L0[j]);
        c.chain.length += c.segment[k].length;
        c.chain.force = std::max(c.chain.force, cs.force[j]), c.chain.slack &= c.segment[k].slack;
      }
    } else if (!form_finding_ && s.sliding) {
      // One force from the total length (docs/theory.md §14, engineering strain over the whole cable).
      for (int k = 0; k + 1 < c.count; ++k) {
        double scratch[6];
        c.chain.length += CableSlidingSegment(&x[3 * k], 0.0, 0.0, scratch, nullptr);
      }
      c.chain.slack = !(c.chain.length > c.L0_total);
      c.chain.force = c.chain.slack ? 0.0 : s.EA * (c.chain.length - c.L0_total) / c.L0_total;
    }
    for (int k = 0; k + 1 < c.count && (form_finding_ || c.clamp.empty()); ++k) {
      double fe[6];
      if (form_finding_ && s.force_density > 0) {
        c.segment[k] = CableSegmentForceDensity(&x[3 * k], s.force_density, fe, nullptr);
      } else if (form_finding_) {
        c.segment[k] = CableSegmentConstantForce(&x[3 * k], s.prestress, fe, nullptr);
      } else if (s.sliding) {
        c.segment[k].length = CableSlidingSegment(&x[3 * k], c.chain.force, 0.0, fe, nullptr);
        c.segment[k].force = c.chain.force, c.segment[k].slack = c.chain.slack;
      } else {
        c.segment[k] = CableSegment(&x[3 * k], c.L0[k], s.EA, fe, nullptr);
      }
      for (int i = 0; i < 6; ++i) f[3 * k + i] += fe[i];
      if (!s.sliding || form_finding_) c.chain.length += c.segment[k].length;
    }
    if (!s.sliding || form_finding_) {  // (a clamped cable is sliding)
      c.chain.force = 0.0, c.chain.slack = true;
      for (const CableState &st : c.segment) c.chain.force = std::max(c.chain.force, st.force), c.chain.slack &= st.slack;
    }
    // Self-weight: each segment's weight w L0 shared by its two nodes, along -z (a dead load).
    c.weight = (!form_finding_ && s.weighted) ? s.weight.At(P.scene.schedules, P.time) : 0.0;
    if (c.weight != 0.0)
      for (int k = 0; k + 1 < c.count; ++k) {
        const double half = 0.5 * c.weight * c.L0[k];
        w[3 * k + 2] -= half, w[3 * (k + 1) + 2] -= half;
      }
    for (int i = 0; i < 3 * c.count; ++i) f[i] -= w[i];
  }
}

PetscErrorCode CableTerm::Prepare(Problem &P, const PetscScalar *u) {
  PetscFunctionBeginUser;
  std::fill(x_.begin(), x_.end(), 0.0);
  for (size_t k = 0; k < local_.size(); ++k)
    if (local_[k] >= 0)
      for (int i = 0; i < 3; ++i) x_[3 * k + i] = P.mesh.X[3 * local_[k] + i] + u[3 * local_[k] + i];
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, x_.data(), (int)x_.size(), MPI_DOUBLE, MPI_SUM, P.comm));
  Evaluate(P);
  PetscFunctionReturn(0);
}

PetscErrorCode CableTerm::AddLocalForces(Problem &, const PetscScalar *, PetscScalar *f, int *status, double *external2) {
  PetscFunctionBeginUser;
  // A clamp's return map that did not settle: the state is refused like an element's (the line
  // search steps back, or the increment is cut), never used.
  if (clamp_failed_) *status = std::max(*status, (int)KERNEL_NO_CONVERGENCE);
  for (size_t k = 0; k < local_.size(); ++k) {
    if (local_[k] < 0) continue;
    for (int i = 0; i < 3; ++i) {
      f[3 * local_[k] + i] += fint_[3 * k + i];
      *external2 += wload_[3 * k + i] * wload_[3 * k + i];
    }
  }
  PetscFunctionReturn(0);
}

// The segment forces at u without the weight (a load): evaluated afresh, as FormInternalForce may
// ask at a state (the committed one) the last residual was not evaluated at.
PetscErrorCode CableTerm::AddInternalForces(Problem &P, const PetscScalar *u, PetscScalar *f) {
  PetscFunctionBeginUser;
  PetscCall(Prepare(P, u));
  for (size_t k = 0; k < local_.size(); ++k)
    if (local_[k] >= 0)
      for (int i = 0; i < 3; ++i) f[3 * local_[k] + i] += fint_[3 * k + i] + wload_[3 * k + i];
  PetscFunctionReturn(0);
}

// Adds the three rows of entry row_entry (rows row_offset .. row_offset + 2 of the row-major K
// with ncols_total columns, the columns being the blocks of col_entries), constrained rows and
// columns left out, when this rank owns the row.
PetscErrorCode CableTerm::AddRows(Problem &P, Mat A, int row_entry, const std::vector<int> &col_entries, const double *K,
                                  int ncols_total, int row_offset) {
  PetscFunctionBeginUser;
  if (local_[row_entry] < 0) PetscFunctionReturn(0);
  const int nb = (int)col_entries.size();
  std::vector<double> v(3 * 3 * nb);
  std::vector<PetscInt> cols(nb);
  for (int b = 0; b < nb; ++b) cols[b] = gid_[col_entries[b]];
  for (int i = 0; i < 3; ++i)
    for (int c = 0; c < 3 * nb; ++c) {
      const bool off = con_[3 * row_entry + i] || con_[3 * col_entries[c / 3] + c % 3];
      v[i * 3 * nb + c] = off ? 0.0 : K[(row_offset + i) * ncols_total + c];
    }
  const PetscInt row = gid_[row_entry];
  PetscCall(MatSetValuesBlocked(A, 1, &row, nb, cols.data(), v.data(), ADD_VALUES));
  PetscFunctionReturn(0);
}

PetscErrorCode CableTerm::AddTangent(Problem &P, Vec, const PetscScalar *, Mat A) {
  PetscFunctionBeginUser;
  for (Cable &c : cables_) {
    const CableSpec &s = *c.spec;
    const double *x = &x_[3 * c.first];
    const bool sliding = s.sliding && !form_finding_;
    if (sliding && !c.clamp.empty()) {
      // The clamped chain's dense tangent (its sub-chains' couplings through the slipping clamps).
      const int n = 3 * c.count;
      std::vector<double> f(n), K((size_t)n * n);
      double L0c[kCableMaxClamps + 1];
      c.CommittedLengths(L0c);
      CableClamped(c.count, x, (int)c.clamp.size(), c.clamp.data(), L0c, s.EA, s.mu, f.data(), K.data(), nullptr);
      std::vector<int> cols(c.count);
      for (int j = 0; j < c.count; ++j) cols[j] = c.first + j;
      for (int r = 0; r < c.count; ++r) PetscCall(AddRows(P, A, c.first + r, cols, K.data(), n, 3 * r));
      continue;
    }
    for (int k = 0; k + 1 < c.count; ++k) {
      double fe[6], K[36];
      if (form_finding_ && s.force_density > 0) CableSegmentForceDensity(&x[3 * k], s.force_density, fe, K);
      else if (form_finding_) CableSegmentConstantForce(&x[3 * k], s.prestress, fe, K);
      else if (sliding) CableSlidingSegment(&x[3 * k], c.chain.force, 0.0, fe, K);
      else CableSegment(&x[3 * k], c.L0[k], s.EA, fe, K);
      const std::vector<int> cols = {c.first + k, c.first + k + 1};
      PetscCall(AddRows(P, A, c.first + k, cols, K, 6, 0));
      PetscCall(AddRows(P, A, c.first + k + 1, cols, K, 6, 3));
    }
    if (sliding && !c.chain.slack) {
      // The rank-one part (EA / L0) g g^T over the whole chain, g = dl/dx (node i: e_{i-1} - e_i).
      const int n = c.count;
      std::vector<double> g(3 * n, 0.0), K(3 * 3 * n);
      for (int k = 0; k + 1 < n; ++k) {
        const double *a = &x[3 * k], *b = a + 3;
        const double l = c.segment[k].length;
        for (int i = 0; i < 3; ++i) g[3 * k + i] -= (b[i] - a[i]) / l, g[3 * k + 3 + i] += (b[i] - a[i]) / l;
      }
      std::vector<int> cols(n);
      for (int j = 0; j < n; ++j) cols[j] = c.first + j;
      const double ka = s.EA / c.L0_total;
      for (int r = 0; r < n; ++r) {
        if (local_[c.first + r] < 0) continue;
        for (int i = 0; i < 3; ++i)
          for (int j = 0; j < 3 * n; ++j) K[i * 3 * n + j] = ka * g[3 * r + i] * g[j];
        PetscCall(AddRows(P, A, c.first + r, cols, K.data(), 3 * n, 0));
      }
    }
  }
  PetscFunctionReturn(0);
}

PetscErrorCode CableTerm::Columns(const Problem &, std::vector<TermColumn> *columns) const {
  PetscFunctionBeginUser;
  for (const Cable &c : cables_) {
    double nmax = 0.0;
    int slack = 0;
    for (const CableState &s : c.segment) nmax = std::max(nmax, s.force), slack += s.slack;
    columns->push_back({"cable_" + c.spec->name + "_force_max", "N", nmax});
    columns->push_back({"cable_" + c.spec->name + "_length", "mm", c.chain.length});
    columns->push_back({"cable_" + c.spec->name + "_slack_segments", "1", (double)slack});
    for (size_t i = 0; i < c.clamp.size(); ++i) {
      const std::string pre = "cable_" + c.spec->name + "_clamp" + std::to_string(i);
      const double hi = std::max(c.clamp_state.force[i], c.clamp_state.force[i + 1]);
      const double lo = std::min(c.clamp_state.force[i], c.clamp_state.force[i + 1]);
      columns->push_back({pre + "_ratio", "1", lo > 0 ? hi / lo : 0.0});
      columns->push_back({pre + "_limit", "1", c.clamp_state.ratio[i]});
      columns->push_back({pre + "_transfer", "mm", c.transfer[i] + c.clamp_state.delta[i]});
      columns->push_back({pre + "_slip", "1", (double)c.last_status[i]});
    }
  }
  PetscFunctionReturn(0);
}

// Every segment of every cable, the cables in the scene's order (cables/cable: which one).
PetscErrorCode CableTerm::Fields(const Problem &, std::vector<TermData> *fields) const {
  PetscFunctionBeginUser;
  TermData force{"force", Layout::Items, true, 1, {}, "N", "axial force per segment"};
  TermData length{"length", Layout::Items, true, 1, {}, "mm", "length per segment"};
  TermData slack{"slack", Layout::Items, true, 1, {}, "1", "1 where a segment is slack"};
  TermData cable{"cable", Layout::Items, true, 1, {}, "1", "the segment's cable"};
  for (size_t k = 0; k < cables_.size(); ++k)
    for (const CableState &st : cables_[k].segment)
      force.values.push_back(st.force), length.values.push_back(st.length), slack.values.push_back(st.slack),
          cable.values.push_back((double)k);
  for (TermData *d : {&force, &length, &slack, &cable}) fields->push_back(std::move(*d));
  PetscFunctionReturn(0);
}

PetscErrorCode CableTerm::Report(const Problem &, std::vector<std::string> *lines) const {
  char buf[512];
  PetscFunctionBeginUser;
  for (const Cable &c : cables_) {
    const CableSpec &s = *c.spec;
    double nmin = 1e300, nmax = 0.0;
    int slack = 0;
    for (const CableState &st : c.segment) nmin = std::min(nmin, st.force), nmax = std::max(nmax, st.force), slack += st.slack;
    // Cut length: the stress-free length; form finding finds it per segment from the segment's
    // force at the shape found (the prescribed T, or q l).
    double cut = c.L0_total;
    if (form_finding_) {
      cut = 0.0;
      for (const CableState &st : c.segment) cut += CableLengthForForce(st.length, st.force, s.EA);
    }
    std::snprintf(buf, sizeof buf,
                  "cable %s (%d segments%s): force min = %.6e N, max = %.6e N, length = %.6f mm, cut_length = %.6f mm, "
                  "slack = %d segments",
                  s.name.c_str(), c.count - 1, s.sliding ? ", sliding" : "", nmin, nmax, c.chain.length, cut, slack);
    lines->push_back(buf);
    // What the cable pulls on its two end nodes (its anchors): minus its residual part there.
    for (int end = 0; end < 2; ++end) {
      const int k = c.first + (end ? c.count - 1 : 0);
      std::snprintf(buf, sizeof buf, "cable %s end %d (node %d): pull = (%.6e, %.6e, %.6e) N", s.name.c_str(), end,
                    s.nodes[end ? c.count - 1 : 0], -fint_[3 * k], -fint_[3 * k + 1], -fint_[3 * k + 2]);
      lines->push_back(buf);
    }
    // Clamps: the sub-chains' forces either side, the capstan limit at the current angle, what
    // the last increment did and the stress-free length passed on in all.
    const CableClampState &cs = c.clamp_state;
    for (size_t i = 0; i < c.clamp.size(); ++i) {
      const double hi = std::max(cs.force[i], cs.force[i + 1]), lo = std::min(cs.force[i], cs.force[i + 1]);
      std::snprintf(buf, sizeof buf,
                    "cable %s clamp %d (node %d): forces = %.9e, %.9e N, ratio = %.9e, limit exp(mu theta) = %.9e "
                    "(theta = %.9e rad), last increment = %s, transferred = %.6e mm",
                    s.name.c_str(), (int)i, c.clamp_node[i], cs.force[i], cs.force[i + 1], lo > 0 ? hi / lo : 0.0,
                    cs.ratio[i], cs.theta[i], c.last_status[i] ? "slip" : "stick", c.transfer[i] + cs.delta[i]);
      lines->push_back(buf);
    }
    // Pulleys and saddles: the cable's resultant on the held node (the mast head's load).
    for (int k : c.pulleys) {
      const int e = c.first + k;
      const double R[3] = {-fint_[3 * e], -fint_[3 * e + 1], -fint_[3 * e + 2]};
      const bool saddle = std::find(c.clamp.begin(), c.clamp.end(), k) != c.clamp.end();
      std::snprintf(buf, sizeof buf, "cable %s %s (node %d): reaction = (%.6e, %.6e, %.6e) N, |reaction| = %.9e N",
                    s.name.c_str(), saddle ? "saddle" : "pulley", s.nodes[k], R[0], R[1], R[2],
                    std::sqrt(R[0] * R[0] + R[1] * R[1] + R[2] * R[2]));
      lines->push_back(buf);
    }
  }
  PetscFunctionReturn(0);
}

// The converged increment's slips become committed transfer (evaluated afresh at the committed
// displacement: the last evaluation may have been at another state).
PetscErrorCode CableTerm::Commit(Problem &P, double) {
  const PetscScalar *ua;
  PetscFunctionBeginUser;
  if (!clamped_ || form_finding_) PetscFunctionReturn(0);
  std::fill(x_.begin(), x_.end(), 0.0);
  PetscCall(VecGetArrayRead(P.U, &ua));
  for (size_t k = 0; k < local_.size(); ++k)
    if (local_[k] >= 0)
      for (int i = 0; i < 3; ++i) x_[3 * k + i] = P.mesh.X[3 * local_[k] + i] + ua[3 * local_[k] + i];
  PetscCall(VecRestoreArrayRead(P.U, &ua));
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, x_.data(), (int)x_.size(), MPI_DOUBLE, MPI_SUM, P.comm));
  Evaluate(P);
  for (Cable &c : cables_)
    for (size_t i = 0; i < c.clamp.size(); ++i) {
      c.transfer[i] += c.clamp_state.delta[i];
      c.last_delta[i] = c.clamp_state.delta[i], c.last_status[i] = c.clamp_state.status[i];
    }
  Evaluate(P);  // what the report reads: the state from the new committed transfers
  PetscFunctionReturn(0);
}

// Per clamp, cable after cable: the committed transfer, then the last increment's slip and status.
PetscErrorCode CableTerm::State(const Problem &, std::vector<TermData> *blocks) const {
  PetscFunctionBeginUser;
  if (!clamped_) PetscFunctionReturn(0);
  std::vector<double> values;
  for (const Cable &c : cables_)
    for (size_t i = 0; i < c.clamp.size(); ++i)
      values.insert(values.end(), {c.transfer[i], c.last_delta[i], (double)c.last_status[i]});
  blocks->push_back(kCableCheckpoint.Block(std::move(values)));
  PetscFunctionReturn(0);
}

PetscErrorCode CableTerm::Restore(Problem &P, const std::vector<TermData> &blocks) {
  PetscFunctionBeginUser;
  const std::vector<double> *values = kCableCheckpoint.Find(blocks);
  if (!values) PetscFunctionReturn(0);
  size_t clamps = 0;
  for (const Cable &c : cables_) clamps += c.clamp.size();
  PetscCheck(values->size() == 3 * clamps, P.comm, PETSC_ERR_FILE_UNEXPECTED,
             "the checkpoint's %s holds %zu values, not 3 for each of this run's %zu cable clamps: restart with "
             "the clamps the checkpoint was written with",
             kCableCheckpoint.name, values->size(), clamps);
  size_t k = 0;
  for (Cable &c : cables_)
    for (size_t i = 0; i < c.clamp.size(); ++i, k += 3)
      c.transfer[i] = (*values)[k], c.last_delta[i] = (*values)[k + 1], c.last_status[i] = (int)(*values)[k + 2];
  PetscFunctionReturn(0);
}

// What a restart or a branch must keep: each cable's stiffness, stress-free length and kind (its
// weight is a load, which a branch may change); the clamps. A run without cables adds nothing.
void CableTerm::Fingerprint(Fnv64 &h) const {
  if (!cables_.empty()) h.Add(std::string("cables"));
  for (const Cable &c : cables_) h.Add(c.spec->name), h.Add(c.spec->EA), h.Add(c.L0), h.Add(c.spec->sliding);
  if (!clamped_) return;
  h.Add(std::string("cable_clamps"));
  for (const Cable &c : cables_) h.Add(c.spec->mu), h.Add(c.clamp_node);
}

// The cables' forces cannot balance below their round-off: stiff cables of short segments on a
// fine mesh (EA 1.2e7 N, 27 mm segments at 10^5 triangles: 6e-7 N a segment) stall Newton above
// the force tolerance without it. x_ (every cable node, on every rank) is the last evaluation's.
PetscErrorCode CableTerm::ForceFloor(Problem &, Vec, double, double, double *floor) {
  double xmax = 0.0;
  PetscFunctionBeginUser;
  for (double x : x_) xmax = std::max(xmax, std::fabs(x));
  *floor = std::max(*floor, PETSC_MACHINE_EPSILON * std::sqrt(roundoff_per_x_) * xmax);
  PetscFunctionReturn(0);
}

PetscErrorCode CableTerm::LargestMove(Problem &P, Vec U, PetscReal *move) {
  const PetscScalar *ua;
  PetscFunctionBeginUser;
  std::vector<double> u(x_.size(), 0.0), x(x_.size(), 0.0);
  PetscCall(VecGetArrayRead(U, &ua));
  for (size_t k = 0; k < local_.size(); ++k)
    if (local_[k] >= 0)
      for (int i = 0; i < 3; ++i) u[3 * k + i] = ua[3 * local_[k] + i], x[3 * k + i] = P.mesh.X[3 * local_[k] + i] + ua[3 * local_[k] + i];
  PetscCall(VecRestoreArrayRead(U, &ua));
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, u.data(), (int)u.size(), MPI_DOUBLE, MPI_SUM, P.comm));
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, x.data(), (int)x.size(), MPI_DOUBLE, MPI_SUM, P.comm));
  PetscReal m = 0.0;
  for (const Cable &c : cables_)
    for (int k = 0; k < c.count; ++k) {
      const int a = c.first + std::max(k - 1, 0), b = c.first + std::min(k + 1, c.count - 1), e = c.first + k;
      double t[3], tt = 0.0, ut = 0.0, uu = 0.0;
      for (int i = 0; i < 3; ++i) t[i] = x[3 * b + i] - x[3 * a + i], tt += t[i] * t[i];
      for (int i = 0; i < 3; ++i) ut += u[3 * e + i] * t[i], uu += u[3 * e + i] * u[3 * e + i];
      m = std::max(m, std::sqrt(std::max(uu - (tt > 0 ? ut * ut / tt : 0.0), 0.0)));
    }
  *move = std::max(*move, m);
  PetscFunctionReturn(0);
}

} // namespace

const TermDatasetInfo kCableCheckpoint = {"cable_clamps", Layout::Nodes, true, 1};

PetscErrorCode CableLargestMove(Problem *P, Vec U, PetscReal *move) {
  PetscFunctionBeginUser;
  *move = 0.0;
  for (auto &term : P->terms)
    if (auto *c = dynamic_cast<CableTerm *>(term.get())) PetscCall(c->LargestMove(*P, U, move));
  PetscFunctionReturn(0);
}

PetscErrorCode CableTermAdd(Problem *P) {
  PetscFunctionBeginUser;
  if (P->scene.cables.empty()) PetscFunctionReturn(0);
  auto term = std::make_unique<CableTerm>();
  PetscCall(term->SetUp(*P));
  P->terms.push_back(std::move(term));
  PetscFunctionReturn(0);
}

} // namespace etfe
