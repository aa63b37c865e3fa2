// Gas chambers (see chamber.h and kernels/chamber.h).
#include "etfe/assembly/chamber.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <string>

#include "etfe/assembly/assembly.h"
#include "etfe/kernels/chamber.h"
#include "etfe/kernels/geodesic.h"
#include "etfe/kernels/pressure.h"
#include "etfe/assembly/layer_contact.h"
#include "etfe/assembly/pressure_term.h"
#include "etfe/assembly/problem.h"

namespace etfe {

namespace {

void Coordinates(const LocalMesh &m, PetscInt e, const PetscScalar *u, double x[9]) {
  for (int a = 0; a < 3; ++a)
    for (int i = 0; i < 3; ++i) {
      const int l = m.tri[3 * e + a];
      x[3 * a + i] = m.X[3 * l + i] + PetscRealPart(u[3 * l + i]);
    }
}

// The supplied pressure now; in the stage after a release, blended from the sealed gas's
// pressure at the release to the schedule's value at the stage end.
double SuppliedGauge(const Problem *P, int k) {
  const ScheduledValue &p = P->scene.chambers[k].supplied;
  const ChamberSet &c = *FindTerm<ChamberSet>(*P);
  double g = p.At(P->scene.schedules, P->time);
  const double t0 = c.release_time[k], s = P->time - t0;
  if (t0 >= 0 && s < 1.0) g += (c.release_gauge[k] - p.At(P->scene.schedules, t0)) * (1.0 - s);
  return g;
}

// The gauge pressure of chamber k at volume V: supplied, or from its sealed amount.
double Gauge(const Problem *P, int k, double V) {
  const ChamberSet &c = *FindTerm<ChamberSet>(*P);
  if (!c.sealed[k]) return SuppliedGauge(P, k);
  return SealedGauge(c.amount[k], c.atmosphere, V, P->scene.chambers[k].kappa);
}

// A chamber that encloses nothing at the start has its foils on each other (flat foils give
// Newton no out-of-plane stiffness to start from, and sealed they would hold no gas); a negative
// volume means its surfaces face into it. Both are input errors, stated before any load step (the
// scale: the volume of a cube on the chamber's surface area).
PetscErrorCode ChamberCheckStartVolume(Problem *P) {
  const ChamberSet &c = *FindTerm<ChamberSet>(*P);
  const PetscScalar *u;
  Vec Ul;
  std::vector<double> area(c.volume.size(), 0.0);
  PetscFunctionBeginUser;
  PetscCall(GetLocalArray(P->U, P->U_work, &Ul, &u));
  for (const FollowerPressure &load : PressureLoads(*P)) {
    if (load.chamber < 0) continue;
    for (PetscInt e : load.elements) {
      double x[9];
      Coordinates(P->mesh, e, u, x);
      area[load.chamber] += TriangleArea(x, x + 3, x + 6);
    }
  }
  PetscCall(RestoreLocalArray(P->U_work, &Ul, &u));
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, area.data(), (int)area.size(), MPI_DOUBLE, MPI_SUM, P->comm));
  for (size_t k = 0; k < area.size(); ++k) {
    const std::string &name = P->scene.chambers[k].name;
    const double scale = std::pow(area[k], 1.5);
    PetscCheck(c.volume[k] > -1e-9 * scale, P->comm, PETSC_ERR_ARG_WRONG,
               "chamber %s encloses a negative volume at the start (%g m^3): its surfaces' normals point into it; "
               "flip the signs in -chamber_%s_signs (+1 where a group's normals point out of the chamber)",
               name.c_str(), 1e-9 * c.volume[k], name.c_str());
    PetscCheck(c.volume[k] > 1e-9 * scale, P->comm, PETSC_ERR_ARG_WRONG,
               "chamber %s encloses no volume at the start (%g m^3 for %g m^2 of foil): its foils lie on each other or "
               "flat on the plane that closes it, where a flat foil gives Newton no out-of-plane stiffness to start from; start them apart (scripts/cushion-mesh --lens, "
               "-structure_initial_bulge)",
               name.c_str(), 1e-9 * c.volume[k], 1e-6 * area[k]);
  }
  PetscFunctionReturn(0);
}

// A foil bounds a chamber on one side: two chambers on the same side of one foil would be two
// gases in one space, their pressures adding on it (a middle foil bounds one chamber above and
// one below, with opposite signs). Nor does a chamber list one foil twice. Checked per element,
// so that two names of one foil's elements are caught too.
PetscErrorCode ChamberCheckSharedSides(Problem *P) {
  struct Side {
    int chamber, group;
    double sign;
  };
  const std::vector<ChamberSpec> &spec = P->scene.chambers;
  std::vector<std::pair<int, int>> entry;  // (chamber, group) in order: a flat index for the reduction
  std::map<PetscInt, std::vector<Side>> at;
  PetscFunctionBeginUser;
  for (size_t k = 0; k < spec.size(); ++k)
    for (size_t g = 0; g < spec[k].groups.size(); ++g) {
      const auto set = P->mesh.element_sets.find(spec[k].groups[g]);
      if (set != P->mesh.element_sets.end())
        for (PetscInt e : set->second) at[e].push_back({(int)k, (int)g, spec[k].signs[g]});
      entry.emplace_back((int)k, (int)g);
    }
  auto flat = [&](const Side &s) {
    return (int)(std::find(entry.begin(), entry.end(), std::make_pair(s.chamber, s.group)) - entry.begin());
  };
  const int L = (int)entry.size();
  int clash = L * L;  // the first clash a * L + b (a < b) of entries; L * L: none
  for (const auto &kv : at)
    for (size_t i = 0; i < kv.second.size(); ++i)
      for (size_t j = i + 1; j < kv.second.size(); ++j) {
        const Side &a = kv.second[i], &b = kv.second[j];
        if (a.chamber != b.chamber && a.sign != b.sign) continue;  // one chamber on each side
        clash = std::min(clash, std::min(flat(a), flat(b)) * L + std::max(flat(a), flat(b)));
      }
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &clash, 1, MPI_INT, MPI_MIN, P->comm));
  if (clash == L * L) PetscFunctionReturn(0);
  const auto [ka, ga] = entry[clash / L];
  const auto [kb, gb] = entry[clash % L];
  const std::string &na = spec[ka].name, &nb = spec[kb].name;
  const std::string &a = spec[ka].groups[ga], &b = spec[kb].groups[gb];
  PetscCheck(ka != kb, P->comm, PETSC_ERR_ARG_WRONG,
             "chamber %s: its surface groups %s and %s share triangles (-chamber_%s_groups lists a foil twice): a "
             "chamber's boundary is each foil once",
             na.c_str(), a.c_str(), b.c_str(), na.c_str());
  SETERRQ(P->comm, PETSC_ERR_ARG_WRONG,
          "chambers %s and %s lie on the same side of one foil (surface group %s of %s, %s of %s, with the same sign "
          "in -chamber_<name>_signs): two gases cannot fill one space, and their pressures would add on the foil. "
          "Give each space one chamber (one gas on both sides of a middle foil: one chamber of the outer foils; two "
          "chambers: the middle foil -1 for the upper one, +1 for the lower)",
          na.c_str(), nb.c_str(), a.c_str(), na.c_str(), b.c_str(), nb.c_str());
}

// A load may push a supplied chamber's top foil down onto the foil below, never through it. A
// chamber whose volume is not positive after a converged increment has turned inside out, unless
// it is supplied and layer contact between its own foils keeps them apart: then they rest on each
// other, the penalty's penetration leaving a slightly negative volume. Contact elsewhere does not
// count (a pair top:bottom lets the top foil through a middle one), nor for a sealed chamber,
// whose gas law has no meaning at a volume of zero.
PetscErrorCode ChamberCheckInsideOut(Problem *P, double t) {
  const ChamberSet &c = *FindTerm<ChamberSet>(*P);
  PetscFunctionBeginUser;
  for (size_t k = 0; k < c.volume.size(); ++k) {
    if (c.volume[k] > 0) continue;
    const ChamberSpec &s = P->scene.chambers[k];
    std::string missing, groups;
    const bool apart = LayerContactKeepsApart(FindTerm<LayerContactSet>(*P), s.groups, &missing);
    if (apart && !c.sealed[k]) continue;
    for (const std::string &g : s.groups) groups += (groups.empty() ? "" : ",") + g;
    const int stage = std::max(0, std::min((int)std::floor(t - 1e-9), P->scene.NumStages() - 1)) + 1;
    std::string way;  // a sealed chamber cannot empty: its gas law has no meaning there
    if (!c.sealed[k] && !missing.empty())
      way = ", or let its foils rest on each other: contact between them, " + missing + " in -layer_contact" +
            (FindTerm<LayerContactSet>(*P) ? " (the pairs given do not join them)" : "");
    else if (!c.sealed[k])
      way = ", or bound it with two foils and let them rest on each other (-layer_contact)";
    SETERRQ(P->comm, PETSC_ERR_NOT_CONVERGED,
            "chamber %s turned inside out at load time %g (stage %d, volume %g m^3): its foils (%s) passed through "
            "each other (a load heavier than the %s pressure), so the state cannot be trusted from here. Lower the "
            "load or raise the pressure%s%s",
            s.name.c_str(), t, stage, 1e-9 * c.volume[k], groups.c_str(), c.sealed[k] ? "sealed gas's" : "inflation",
            c.sealed[k] ? "" : ", seal the chamber", way.c_str());
  }
  PetscFunctionReturn(0);
}

} // namespace

PetscErrorCode ChamberUpdate(Problem *P, Vec U) {
  const PetscScalar *u;
  Vec Ul;
  PetscFunctionBeginUser;
  PetscCall(GetLocalArray(U, P->U_work, &Ul, &u));
  PetscCall(ChamberEvaluate(P, u));
  PetscCall(RestoreLocalArray(P->U_work, &Ul, &u));
  PetscFunctionReturn(0);
}

PetscErrorCode AddChamberTerm(Problem *P) {
  const size_t n = P->scene.chambers.size();
  PetscFunctionBeginUser;
  if (n == 0) PetscFunctionReturn(0);
  auto *c = new ChamberSet();
  P->terms.emplace_back(c);
  c->atmosphere = P->scene.atmosphere;
  c->volume.assign(n, 0.0), c->gauge.assign(n, 0.0), c->sealed.assign(n, 0), c->amount.assign(n, 0.0);
  c->release_time.assign(n, -1.0), c->release_gauge.assign(n, 0.0);
  for (const ChamberSpec &s : P->scene.chambers) c->per_stage |= !s.sealed_stages.empty();
  PetscBool rank_one = PETSC_TRUE;
  PetscOptionsBegin(P->comm, nullptr, "Gas chambers", "Chamber");
  PetscCall(PetscOptionsBool("-chamber_rank_one",
                             "Newton's tangent includes the sealed gas's stiffness (kappa p_abs / V) g g^T (off: the "
                             "pressure is updated between iterations only, and Newton converges linearly)",
                             "", rank_one, &rank_one, nullptr));
  PetscOptionsEnd();
  for (const ChamberSpec &s : P->scene.chambers) c->may_seal |= s.EverSealed() && rank_one;
  if (c->may_seal) {
    PetscInt nlocal, N;
    PetscCall(VecGetLocalSize(P->U, &nlocal));
    PetscCall(VecGetSize(P->U, &N));
    PetscCall(MatCreateDense(P->comm, nlocal, PETSC_DECIDE, N, (PetscInt)n, nullptr, &c->U));
    PetscCall(MatZeroEntries(c->U));
    PetscCall(MatAssemblyBegin(c->U, MAT_FINAL_ASSEMBLY));
    PetscCall(MatAssemblyEnd(c->U, MAT_FINAL_ASSEMBLY));
    PetscCall(VecCreateSeq(PETSC_COMM_SELF, (PetscInt)n, &c->c));
    PetscCall(VecZeroEntries(c->c));
    PetscCall(MatCreateLRC(P->J, c->U, c->c, nullptr, &c->J));
    PetscCall(VecDuplicate(P->U, &c->g_work));
  }
  PetscCall(ChamberCheckSharedSides(P));
  // Sealed from the start: the gas the chamber holds at load time 0.
  PetscCall(ChamberUpdate(P, P->U));
  PetscCall(ChamberCheckStartVolume(P));
  for (size_t k = 0; k < n; ++k)
    if (P->scene.chambers[k].SealedIn(1)) {
      PetscCheck(c->volume[k] > 0, P->comm, PETSC_ERR_ARG_WRONG,
                 "chamber %s is sealed from stage 1 but encloses %g mm^3 at the start: inflate it in a stage before "
                 "sealing it, or check the orientation of its surfaces (-chamber_%s_signs)",
                 P->scene.chambers[k].name.c_str(), c->volume[k], P->scene.chambers[k].name.c_str());
      const double gauge = SuppliedGauge(P, (int)k);
      c->amount[k] = SealedAmount(gauge, c->atmosphere, c->volume[k], P->scene.chambers[k].kappa);
      c->sealed[k] = 1;
      // Allowed (a bag of air closed at the atmosphere's pressure) but rarely meant: say so.
      PetscCall(PetscPrintf(P->comm,
                            "chamber %s: sealed from the start with %.6g kPa gauge in %.6g m^3%s\n",
                            P->scene.chambers[k].name.c_str(), 1e3 * gauge, 1e-9 * c->volume[k],
                            gauge <= 0 ? " (never inflated: to inflate it first, supply it in stage 1 and seal it "
                                         "from stage 2)"
                                       : ""));
    }
  PetscFunctionReturn(0);
}

PetscErrorCode ChamberEvaluate(Problem *P, const PetscScalar *u) {
  ChamberSet &c = *FindTerm<ChamberSet>(*P);
  const size_t n = c.volume.size();
  PetscFunctionBeginUser;
  std::vector<double> V(n, 0.0);
  for (const FollowerPressure &load : PressureLoads(*P)) {
    if (load.chamber < 0) continue;
    const double *o = P->scene.chambers[load.chamber].origin;
    for (PetscInt e : load.elements) {
      double x[9];
      Coordinates(P->mesh, e, u, x);
      V[load.chamber] += load.sign * ChamberTetVolume(x, o);
    }
  }
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, V.data(), (int)n, MPI_DOUBLE, MPI_SUM, P->comm));
  for (size_t k = 0; k < n; ++k) {
    c.volume[k] = V[k] + P->scene.chambers[k].extra_volume;
    c.gauge[k] = c.sealed[k] && !(c.volume[k] > 0) ? NAN : Gauge(P, (int)k, c.volume[k]);
  }
  PetscFunctionReturn(0);
}

double ChamberLoadPressure(const Problem *P, int chamber, double sign) { return sign * FindTerm<ChamberSet>(*P)->gauge[chamber]; }

PetscErrorCode ChamberTangent(Problem *P, const PetscScalar *u) {
  ChamberSet &c = *FindTerm<ChamberSet>(*P);
  const size_t n = c.volume.size();
  PetscFunctionBeginUser;
  if (!c.may_seal) PetscFunctionReturn(0);
  for (size_t k = 0; k < n; ++k) {
    Vec gl, col;
    PetscScalar *g;
    PetscCall(VecGhostGetLocalForm(c.g_work, &gl));
    PetscCall(VecZeroEntries(gl));
    PetscCall(VecGetArray(gl, &g));
    for (const FollowerPressure &load : PressureLoads(*P)) {
      if (load.chamber != (int)k) continue;
      for (PetscInt e : load.elements) {
        double x[9], f[9];
        Coordinates(P->mesh, e, u, x);
        PressureLoad(load.sign, x, f, nullptr);  // dV/dx per unit pressure
        for (int a = 0; a < 3; ++a)
          for (int i = 0; i < 3; ++i) g[3 * P->mesh.tri[3 * e + a] + i] += f[3 * a + i];
      }
    }
    PetscCall(VecRestoreArray(gl, &g));
    PetscCall(VecGhostRestoreLocalForm(c.g_work, &gl));
    PetscCall(VecGhostUpdateBegin(c.g_work, ADD_VALUES, SCATTER_REVERSE));
    PetscCall(VecGhostUpdateEnd(c.g_work, ADD_VALUES, SCATTER_REVERSE));
    {  // prescribed DOFs do not move: no volume change through them
      PetscScalar *a;
      PetscCall(VecGetArray(c.g_work, &a));
      for (PetscInt d : P->con_owned_dof) a[d] = 0.0;
      PetscCall(VecRestoreArray(c.g_work, &a));
    }
    PetscCall(MatDenseGetColumnVecWrite(c.U, (PetscInt)k, &col));
    PetscCall(VecCopy(c.g_work, col));
    PetscCall(MatDenseRestoreColumnVecWrite(c.U, (PetscInt)k, &col));
    const double stiff = c.sealed[k] ? SealedStiffness(c.amount[k], c.volume[k], P->scene.chambers[k].kappa) : 0.0;
    PetscCall(VecSetValue(c.c, (PetscInt)k, stiff, INSERT_VALUES));
  }
  PetscCall(VecAssemblyBegin(c.c));
  PetscCall(VecAssemblyEnd(c.c));
  // U and c are the LRC matrix's own (it multiplies with them as they are now).
  PetscFunctionReturn(0);
}

PetscErrorCode ChamberCommit(Problem *P, double t) {
  ChamberSet &c = *FindTerm<ChamberSet>(*P);
  PetscFunctionBeginUser;
  PetscCall(ChamberUpdate(P, P->U));
  PetscCall(ChamberCheckInsideOut(P, t));
  const double next = std::round(t) + 1;  // the stage that starts at t, if t ends one
  if (std::fabs(t - std::round(t)) > 1e-9) PetscFunctionReturn(0);
  for (size_t k = 0; k < c.volume.size(); ++k) {
    const ChamberSpec &s = P->scene.chambers[k];
    const bool released = !s.sealed_stages.empty() && next <= s.sealed_stages.size() && !s.SealedIn((int)next);
    if (c.sealed[k] && released) {
      c.release_time[k] = t, c.release_gauge[k] = c.gauge[k];
      c.sealed[k] = 0, c.amount[k] = 0.0;
      PetscCall(PetscPrintf(P->comm, "chamber %s: supplied again at load time %g, from %.6g kPa gauge\n", s.name.c_str(),
                            t, 1e3 * c.release_gauge[k]));
      continue;
    }
    if (c.sealed[k] || !s.SealedIn((int)next)) continue;
    PetscCheck(c.volume[k] > 0, P->comm, PETSC_ERR_ARG_WRONG,
               "chamber %s is sealed from stage %d but encloses %g mm^3 then: inflate it first, or check the "
               "orientation of its surfaces (-chamber_%s_signs)",
               s.name.c_str(), (int)next, c.volume[k], s.name.c_str());
    c.amount[k] = SealedAmount(SuppliedGauge(P, (int)k), c.atmosphere, c.volume[k], s.kappa);
    c.sealed[k] = 1;
    PetscCall(PetscPrintf(P->comm, "chamber %s: sealed at load time %g with %.6g kPa gauge in %.6g m^3\n", s.name.c_str(),
                          t, 1e3 * (c.amount[k] * std::pow(c.volume[k], -s.kappa) - c.atmosphere), 1e-9 * c.volume[k]));
  }
  PetscFunctionReturn(0);
}

void ChamberStateGet(const Problem *P, std::vector<double> *state) {
  state->clear();
  if (!FindTerm<ChamberSet>(*P)) return;
  const ChamberSet &c = *FindTerm<ChamberSet>(*P);
  for (size_t k = 0; k < c.sealed.size(); ++k) state->push_back(c.sealed[k]), state->push_back(c.amount[k]);
  if (c.per_stage)
    for (size_t k = 0; k < c.sealed.size(); ++k) state->push_back(c.release_time[k]), state->push_back(c.release_gauge[k]);
}

void ChamberStateSet(Problem *P, const std::vector<double> &state) {
  if (!FindTerm<ChamberSet>(*P)) return;
  ChamberSet &c = *FindTerm<ChamberSet>(*P);
  const size_t n = c.sealed.size();
  for (size_t k = 0; k < n && 2 * k + 1 < state.size(); ++k) c.sealed[k] = state[2 * k] != 0, c.amount[k] = state[2 * k + 1];
  for (size_t k = 0; c.per_stage && k < n && 2 * n + 2 * k + 1 < state.size(); ++k)
    c.release_time[k] = state[2 * n + 2 * k], c.release_gauge[k] = state[2 * n + 2 * k + 1];
}

} // namespace etfe
