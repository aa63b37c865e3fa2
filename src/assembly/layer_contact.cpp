// Frictionless contact between film layers (see layer_contact.h and kernels/layer_contact.h).
#include "etfe/assembly/layer_contact.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>

#include "etfe/assembly/assembly.h"
#include "etfe/kernels/layer_contact.h"
#include "etfe/assembly/problem.h"

namespace etfe {

namespace {

// The slave:master pairs of -layer_contact, each an element set of the mesh.
PetscErrorCode ReadOptions(Problem *P, LayerContactSet *c, bool *given) {
  char *list[16];
  PetscInt n = 16;
  PetscBool set = PETSC_FALSE;
  PetscFunctionBeginUser;
  PetscOptionsBegin(P->comm, nullptr, "Contact between film layers (cushions)", "LayerContact");
  PetscCall(PetscOptionsStringArray("-layer_contact",
                                    "Frictionless contact: slave:master surface groups (the slave's nodes keep to "
                                    "their side of the master's triangles), e.g. top:bottom",
                                    "", list, &n, &set));
  PetscCall(PetscOptionsReal("-layer_contact_penalty",
                             "Contact pressure per mm of penetration [MPa/mm] (0.01: 10 kPa per mm)", "", c->penalty,
                             &c->penalty, nullptr));
  PetscOptionsEnd();
  *given = set && n > 0;
  for (PetscInt k = 0; k < (set ? n : 0); ++k) {
    const std::string s = list[k];
    PetscCall(PetscFree(list[k]));
    const size_t colon = s.find(':');
    PetscCheck(colon != std::string::npos && colon > 0 && colon + 1 < s.size(), P->comm, PETSC_ERR_ARG_WRONG,
               "-layer_contact %s: give slave:master surface groups, e.g. top:bottom", s.c_str());
    c->slaves.push_back(s.substr(0, colon)), c->masters.push_back(s.substr(colon + 1));
    // Contact of a foil with itself is not modelled: every node of it lies on the layer, so the
    // pair would hold nothing while a chamber of that foil counted as kept apart.
    PetscCheck(c->slaves.back() != c->masters.back(), P->comm, PETSC_ERR_SUP,
               "-layer_contact %s: a foil's contact with itself is not modelled; pair two different surface groups "
               "(the upper foil's and the one below it, e.g. top:bottom)",
               s.c_str());
    for (const std::string &g : {c->slaves.back(), c->masters.back()})
      PetscCheck(P->mesh.element_sets.count(g), P->comm, PETSC_ERR_ARG_WRONG,
                 "-layer_contact %s: the mesh has no surface group %s", s.c_str(), g.c_str());
  }
  PetscCheck(c->penalty > 0, P->comm, PETSC_ERR_ARG_OUTOFRANGE, "-layer_contact_penalty %g: must be positive",
             c->penalty);
  PetscFunctionReturn(0);
}

// Every rank gets every master triangle: its layer, its nodes' PETSc ids, reference coordinates
// and held DOFs (each triangle lives on one rank).
PetscErrorCode GatherMasters(Problem *P, LayerContactSet *c) {
  const LocalMesh &m = P->mesh;
  constexpr int kRec = 2 + 3 + 9 + 9;  // layer, scene id, ids, X, held
  std::vector<double> mine;
  PetscFunctionBeginUser;
  for (size_t l = 0; l < c->masters.size(); ++l)
    for (PetscInt e : m.element_sets.at(c->masters[l])) {
      mine.push_back((double)l), mine.push_back((double)m.element_natural[e]);
      for (int a = 0; a < 3; ++a) mine.push_back((double)m.global_id[m.tri[3 * e + a]]);
      for (int a = 0; a < 3; ++a)
        for (int i = 0; i < 3; ++i) mine.push_back(m.X[3 * m.tri[3 * e + a] + i]);
      for (int a = 0; a < 3; ++a)
        for (int i = 0; i < 3; ++i) mine.push_back(P->dof_constrained[3 * m.tri[3 * e + a] + i]);
    }
  int count = (int)mine.size();
  std::vector<int> counts(P->size), offsets(P->size, 0);
  PetscCallMPI(MPI_Allgather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, P->comm));
  std::partial_sum(counts.begin(), counts.end() - 1, offsets.begin() + 1);
  std::vector<double> all((size_t)offsets.back() + counts.back());
  PetscCallMPI(MPI_Allgatherv(mine.data(), count, MPI_DOUBLE, all.data(), counts.data(), offsets.data(), MPI_DOUBLE,
                              P->comm));
  std::map<PetscInt, int> index;
  for (size_t r = 0; r < all.size(); r += kRec)
    for (int a = 0; a < 3; ++a) index.emplace((PetscInt)all[r + 2 + a], 0);
  for (auto &kv : index) kv.second = (int)c->master_ids.size(), c->master_ids.push_back(kv.first);
  c->master_X.assign(3 * c->master_ids.size(), 0.0), c->master_held.assign(3 * c->master_ids.size(), 0);
  for (size_t r = 0; r < all.size(); r += kRec) {
    c->tri_layer.push_back((int)all[r]), c->tri_natural.push_back((PetscInt)all[r + 1]);
    for (int a = 0; a < 3; ++a) {
      const int k = index[(PetscInt)all[r + 2 + a]];
      c->master_tri.push_back(k);
      for (int i = 0; i < 3; ++i)
        c->master_X[3 * k + i] = all[r + 5 + 3 * a + i], c->master_held[3 * k + i] |= all[r + 14 + 3 * a + i] != 0;
    }
  }
  PetscFunctionReturn(0);
}

// The slave nodes: owned, of a slave layer, not on its master layer, not held in every DOF; their
// penalty k = penalty x tributary area (a third of each reference triangle, summed over ranks).
PetscErrorCode FindSlaves(Problem *P, LayerContactSet *c) {
  const LocalMesh &m = P->mesh;
  Vec area, al;
  PetscScalar *a;
  PetscFunctionBeginUser;
  PetscCall(VecDuplicate(P->U_work, &area));
  for (size_t l = 0; l < c->slaves.size(); ++l) {
    std::vector<PetscInt> on_master;  // the PETSc ids of this pair's master layer
    for (size_t t = 0; t < c->tri_layer.size(); ++t)
      if (c->tri_layer[t] == (int)l)
        for (int a = 0; a < 3; ++a) on_master.push_back(c->master_ids[c->master_tri[3 * t + a]]);
    std::sort(on_master.begin(), on_master.end());
    PetscCall(VecZeroEntries(area));
    PetscCall(VecGhostGetLocalForm(area, &al));
    PetscCall(VecGetArray(al, &a));
    for (PetscInt e : m.element_sets.at(c->slaves[l]))
      for (int k = 0; k < 3; ++k) a[3 * m.tri[3 * e + k]] += m.ref[e].area / 3.0;
    PetscCall(VecRestoreArray(al, &a));
    PetscCall(VecGhostRestoreLocalForm(area, &al));
    PetscCall(VecGhostUpdateBegin(area, ADD_VALUES, SCATTER_REVERSE));
    PetscCall(VecGhostUpdateEnd(area, ADD_VALUES, SCATTER_REVERSE));
    PetscCall(VecGetArray(area, &a));
    for (PetscInt n = 0; n < m.num_owned; ++n) {
      const bool held = P->dof_constrained[3 * n] && P->dof_constrained[3 * n + 1] && P->dof_constrained[3 * n + 2];
      if (a[3 * n] <= 0 || held || std::binary_search(on_master.begin(), on_master.end(), m.global_id[n]))
        continue;
      c->nodes.push_back({n, (int)l, 0.0, c->penalty * PetscRealPart(a[3 * n])});
    }
    PetscCall(VecRestoreArray(area, &a));
  }
  PetscCall(VecDestroy(&area));
  // A pair without a node to hold (the slave's nodes all on its master layer or held) is a wrong
  // pair of groups, not contact.
  std::vector<PetscInt> count(c->slaves.size(), 0);
  for (const LayerContactSet::Node &s : c->nodes) ++count[s.layer];
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, count.data(), (int)count.size(), MPIU_INT, MPI_SUM, P->comm));
  for (size_t l = 0; l < count.size(); ++l)
    PetscCheck(count[l] > 0, P->comm, PETSC_ERR_ARG_WRONG,
               "-layer_contact %s:%s pairs no node: every node of %s lies on %s or is held in every direction, so "
               "there is nothing for contact to hold; pair two foils that meet only at their rim, the first one free "
               "to move",
               c->slaves[l].c_str(), c->masters[l].c_str(), c->slaves[l].c_str(), c->masters[l].c_str());
  PetscFunctionReturn(0);
}

// x (12): the slave node's and the master triangle's current positions.
void Positions(const LayerContactSet &c, const LocalMesh &m, const LayerContactSet::Node &s, const PetscScalar *u,
               const PetscScalar *um, double x[12]) {
  for (int i = 0; i < 3; ++i) x[i] = m.X[3 * s.local + i] + PetscRealPart(u[3 * s.local + i]);
  for (int a = 0; a < 3; ++a) {
    const int k = c.master_tri[3 * s.tri + a];
    for (int i = 0; i < 3; ++i) x[3 + 3 * a + i] = c.master_X[3 * k + i] + PetscRealPart(um[3 * k + i]);
  }
}

// The PETSc ids of the slave node and its triangle's nodes.
void PairIds(const LayerContactSet &c, const LocalMesh &m, const LayerContactSet::Node &s, PetscInt ids[4]) {
  ids[0] = m.global_id[s.local];
  for (int a = 0; a < 3; ++a) ids[1 + a] = c.master_ids[c.master_tri[3 * s.tri + a]];
}

// Whether (px, py) lies in the triangle's plan, its barycentric coordinates down to -tol.
bool InPlan(const double *t, double px, double py, double tol = 1e-9) {
  const double d = (t[3] - t[0]) * (t[7] - t[1]) - (t[6] - t[0]) * (t[4] - t[1]);
  if (d == 0) return false;
  const double l1 = ((t[3] - px) * (t[7] - py) - (t[6] - px) * (t[4] - py)) / d;
  const double l2 = ((t[6] - px) * (t[1] - py) - (t[0] - px) * (t[7] - py)) / d;
  return l1 >= -tol && l2 >= -tol && 1 - l1 - l2 >= -tol;
}

// The signed distance of the point xs from the plane of triangle t (9 coordinates), positive on
// the side its normal points to; false for a degenerate triangle.
bool GapTo(const double xs[3], const double *t, double *g) {
  double x[12];
  std::copy(xs, xs + 3, x), std::copy(t, t + 9, x + 3);
  return LayerGap(x, 1.0, g, nullptr);
}

// A node keeps its triangle while its plan stays within 5 % of the triangle's size beyond an
// edge: a node at a vertex of the layer below (a cushion's foils share their plan mesh) would
// otherwise take a different triangle, hence plane and force, at every pairing.
constexpr double kKeepTriangle = 0.05;

// The master nodes' displacements scattered from U, and both arrays for reading.
PetscErrorCode BeginArrays(LayerContactSet &c, Vec U, const PetscScalar **u, const PetscScalar **um) {
  PetscFunctionBeginUser;
  PetscCall(VecScatterBegin(c.scatter, U, c.master_u, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecScatterEnd(c.scatter, U, c.master_u, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecGetArrayRead(U, u));
  PetscCall(VecGetArrayRead(c.master_u, um));
  PetscFunctionReturn(0);
}

PetscErrorCode EndArrays(LayerContactSet &c, Vec U, const PetscScalar **u, const PetscScalar **um) {
  PetscFunctionBeginUser;
  PetscCall(VecRestoreArrayRead(c.master_u, um));
  PetscCall(VecRestoreArrayRead(U, u));
  PetscFunctionReturn(0);
}

} // namespace

PetscErrorCode AddLayerContactTerm(Problem *P) {
  bool given;
  PetscFunctionBeginUser;
  auto *c = new LayerContactSet();
  PetscCall(ReadOptions(P, c, &given));
  if (!given) {
    delete c;
    PetscFunctionReturn(0);
  }
  P->terms.emplace_back(c);
  PetscCheck(!P->unassembled, P->comm, PETSC_ERR_SUP,
             "-layer_contact couples nodes of different subdomains, which the unassembled tangent (-mat_type is, "
             "-pc_type bddc) cannot hold: use an assembled solver path (e.g. options/solvers/mumps_lu.opts)");
  PetscCall(GatherMasters(P, c));
  PetscCall(FindSlaves(P, c));
  IS is;
  const PetscInt nm = (PetscInt)c->master_ids.size();
  PetscCall(ISCreateBlock(PETSC_COMM_SELF, 3, nm, c->master_ids.data(), PETSC_COPY_VALUES, &is));
  PetscCall(VecCreateSeq(PETSC_COMM_SELF, 3 * nm, &c->master_u));
  PetscCall(VecScatterCreate(P->U, is, c->master_u, nullptr, &c->scatter));
  PetscCall(ISDestroy(&is));
  PetscCall(LayerContactPair(P, P->U));
  PetscFunctionReturn(0);
}

PetscErrorCode LayerContactPair(Problem *P, Vec U) {
  LayerContactSet &c = *FindTerm<LayerContactSet>(*P);
  const LocalMesh &m = P->mesh;
  const PetscScalar *u, *um;
  PetscFunctionBeginUser;
  PetscCall(BeginArrays(c, U, &u, &um));
  // A plan grid of the master triangles' bounding boxes, about one triangle per cell.
  const size_t nt = c.tri_layer.size();
  std::vector<double> pos(9 * nt);
  double lo[2] = {1e300, 1e300}, hi[2] = {-1e300, -1e300};
  for (size_t t = 0; t < nt; ++t)
    for (int a = 0; a < 3; ++a)
      for (int i = 0; i < 3; ++i) {
        const int k = c.master_tri[3 * t + a];
        pos[9 * t + 3 * a + i] = c.master_X[3 * k + i] + PetscRealPart(um[3 * k + i]);
        if (i < 2) lo[i] = std::min(lo[i], pos[9 * t + 3 * a + i]), hi[i] = std::max(hi[i], pos[9 * t + 3 * a + i]);
      }
  const int cells = std::max(1, (int)std::sqrt((double)nt));
  const double w[2] = {(hi[0] - lo[0]) / cells + 1e-12, (hi[1] - lo[1]) / cells + 1e-12};
  auto cell = [&](double v, int i) { return std::min(cells - 1, std::max(0, (int)((v - lo[i]) / w[i]))); };
  std::vector<std::vector<int>> grid((size_t)cells * cells);
  for (size_t t = 0; t < nt; ++t) {
    const double *p = &pos[9 * t];
    const int x0 = cell(std::min({p[0], p[3], p[6]}), 0), x1 = cell(std::max({p[0], p[3], p[6]}), 0);
    const int y0 = cell(std::min({p[1], p[4], p[7]}), 1), y1 = cell(std::max({p[1], p[4], p[7]}), 1);
    for (int i = x0; i <= x1; ++i)
      for (int j = y0; j <= y1; ++j) grid[(size_t)i * cells + j].push_back((int)t);
  }
  PetscInt paired = 0, on_it = -1;
  for (LayerContactSet::Node &s : c.nodes) {
    double xs[3];
    for (int i = 0; i < 3; ++i) xs[i] = m.X[3 * s.local + i] + PetscRealPart(u[3 * s.local + i]);
    if (s.tri >= 0 && InPlan(&pos[9 * s.tri], xs[0], xs[1], kKeepTriangle)) {
      ++paired;
      continue;
    }
    s.tri = -1;
    double best = 1e300;
    if (xs[0] >= lo[0] && xs[0] <= hi[0] && xs[1] >= lo[1] && xs[1] <= hi[1])
      for (int t : grid[(size_t)cell(xs[0], 0) * cells + cell(xs[1], 1)]) {
        if (c.tri_layer[t] != s.layer || !InPlan(&pos[9 * t], xs[0], xs[1])) continue;
        double g;
        if (GapTo(xs, &pos[9 * t], &g) && std::fabs(g) < best) best = std::fabs(g), s.tri = t;
      }
    if (s.tri < 0) continue;
    ++paired;
    if (s.side == 0.0) {  // the first pairing fixes the side the node keeps to
      double g;
      GapTo(xs, &pos[9 * s.tri], &g);
      s.side = g > 0 ? 1.0 : -1.0;
      if (g == 0.0) on_it = std::max(on_it, m.natural_id[s.local]);
    }
  }
  PetscCall(EndArrays(c, U, &u, &um));
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &on_it, 1, MPIU_INT, MPI_MAX, P->comm));
  PetscCheck(on_it < 0, P->comm, PETSC_ERR_ARG_WRONG,
             "-layer_contact: node %" PetscInt_FMT " (scene id) lies on a triangle of the layer below it at the start: "
             "start the layers apart (scripts/cushion-mesh --lens)", on_it);
  PetscCallMPI(MPI_Allreduce(&paired, &c.paired, 1, MPIU_INT, MPI_SUM, P->comm));
  PetscFunctionReturn(0);
}

PetscErrorCode LayerContactResidual(Problem *P, Vec U, Vec F) {
  LayerContactSet &c = *FindTerm<LayerContactSet>(*P);
  const LocalMesh &m = P->mesh;
  const PetscScalar *u, *um;
  PetscInt active = 0;
  double deepest = 0.0;
  PetscFunctionBeginUser;
  PetscCall(BeginArrays(c, U, &u, &um));
  for (const LayerContactSet::Node &s : c.nodes) {
    if (s.tri < 0) continue;
    double x[12], f[12];
    Positions(c, m, s, u, um, x);
    const double g = LayerContactForce(x, s.side, s.k, f, nullptr);
    if (g >= 0) continue;
    ++active, deepest = std::max(deepest, -g);
    PetscInt ids[4];
    PairIds(c, m, s, ids);
    PetscCall(VecSetValuesBlocked(F, 4, ids, f, ADD_VALUES));  // a triangle's nodes may be another rank's
  }
  PetscCall(EndArrays(c, U, &u, &um));
  PetscCall(VecAssemblyBegin(F));
  PetscCall(VecAssemblyEnd(F));
  PetscCallMPI(MPI_Allreduce(&active, &c.active, 1, MPIU_INT, MPI_SUM, P->comm));
  PetscCallMPI(MPI_Allreduce(&deepest, &c.deepest, 1, MPI_DOUBLE, MPI_MAX, P->comm));
  PetscFunctionReturn(0);
}

PetscErrorCode LayerContactJacobian(Problem *P, Vec U, Mat A) {
  LayerContactSet &c = *FindTerm<LayerContactSet>(*P);
  const LocalMesh &m = P->mesh;
  const PetscScalar *u, *um;
  PetscFunctionBeginUser;
  // A new pair couples nodes the mesh does not: the matrix grows where contact starts.
  PetscCall(MatSetOption(A, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_FALSE));
  PetscCall(BeginArrays(c, U, &u, &um));
  for (const LayerContactSet::Node &s : c.nodes) {
    if (s.tri < 0) continue;
    double x[12], f[12], K[144];
    Positions(c, m, s, u, um, x);
    if (LayerContactForce(x, s.side, s.k, f, K) >= 0) continue;
    PetscInt ids[4];
    PairIds(c, m, s, ids);
    char held[12];
    for (int i = 0; i < 3; ++i) held[i] = P->dof_constrained[3 * s.local + i];
    for (int a = 0; a < 3; ++a)
      for (int i = 0; i < 3; ++i) held[3 + 3 * a + i] = c.master_held[3 * c.master_tri[3 * s.tri + a] + i];
    for (int r = 0; r < 12; ++r)  // held rows and columns stay the identity's
      if (held[r])
        for (int q = 0; q < 12; ++q) K[12 * r + q] = K[12 * q + r] = 0.0;
    PetscCall(MatSetValuesBlocked(A, 4, ids, 4, ids, K, ADD_VALUES));
  }
  PetscCall(EndArrays(c, U, &u, &um));
  PetscFunctionReturn(0);
}

void LayerContactStateGet(const Problem *P, std::vector<double> *v) {
  v->assign(P->mesh.num_owned, -1.0);
  const LayerContactSet &c = *FindTerm<LayerContactSet>(*P);
  for (const LayerContactSet::Node &s : c.nodes)
    if (s.tri >= 0) (*v)[s.local] = (double)c.tri_natural[s.tri];
}

void LayerContactStateSet(Problem *P, const std::vector<double> &v) {
  LayerContactSet &c = *FindTerm<LayerContactSet>(*P);
  std::map<PetscInt, int> tri;
  for (size_t t = 0; t < c.tri_natural.size(); ++t) tri[c.tri_natural[t]] = (int)t;
  for (LayerContactSet::Node &s : c.nodes) {
    const auto it = tri.find((PetscInt)v[s.local]);
    s.tri = v[s.local] < 0 || it == tri.end() ? -1 : it->second;
  }
}

bool LayerContactKeepsApart(const LayerContactSet *c, const std::vector<std::string> &groups, std::string *missing) {
  missing->clear();
  if (groups.size() < 2) return false;
  // The groups joined by pairs, as components (union-find over the list's indices).
  std::vector<size_t> root(groups.size());
  std::iota(root.begin(), root.end(), 0);
  auto find = [&](size_t i) {
    while (root[i] != i) i = root[i] = root[root[i]];
    return i;
  };
  const auto index = [&](const std::string &g) {
    return (size_t)(std::find(groups.begin(), groups.end(), g) - groups.begin());
  };
  for (size_t l = 0; c && l < c->slaves.size(); ++l) {
    const size_t a = index(c->slaves[l]), b = index(c->masters[l]);
    if (a < groups.size() && b < groups.size()) root[find(a)] = find(b);
  }
  for (size_t j = 1; j < groups.size(); ++j)
    if (find(j) != find(0)) {
      *missing = groups[0] + ":" + groups[j];
      return false;
    }
  return true;
}


} // namespace etfe
