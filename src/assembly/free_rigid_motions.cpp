// The rigid motions the DOF constraints leave free (see free_rigid_motions.h). With r = (x - c)/L
// (c the nodes' centroid, L their RMS distance from it, so translations and rotations weigh
// alike), a rigid motion q = (t, theta) moves node x by u = t + theta x r. A constrained DOF (node
// x, component i) sees u_i = m . q with m = (e_i, r x e_i); the constraints hold q unless
// G q = 0, G = sum over constrained DOFs of m m^T (6 x 6). Its null space is the free motions:
// Jacobi's eigenvalues of G, then the null vectors in reduced row echelon form, rotation columns
// first, so a free rotation about an axis-aligned axis and a free translation along x, y or z
// come out as themselves.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "etfe/assembly/free_rigid_motions.h"

namespace etfe {

namespace {

// Below this (relative to the trace of G) an eigenvalue is a motion no constraint touches: a
// held motion has an eigenvalue of the order of (constrained DOFs touching it) x (its lever / L)^2,
// a free one of round-off.
constexpr double kFreeTol = 1e-9;

// Eigenvalues and eigenvectors (columns of V) of the symmetric 6 x 6 matrix A (Jacobi rotations).
void SymmetricEigen6(double A[6][6], double lambda[6], double V[6][6]) {
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j)
      V[i][j] = i == j ? 1.0 : 0.0;
  for (int sweep = 0; sweep < 100; ++sweep) {
    double off = 0.0, diag = 0.0;
    for (int i = 0; i < 6; ++i) {
      diag += A[i][i] * A[i][i];
      for (int j = i + 1; j < 6; ++j)
        off += A[i][j] * A[i][j];
    }
    if (off <= 1e-30 * diag || off == 0.0) break;
    for (int p = 0; p < 6; ++p)
      for (int q = p + 1; q < 6; ++q) {
        if (A[p][q] == 0.0) continue;
        const double theta = (A[q][q] - A[p][p]) / (2.0 * A[p][q]);
        const double t =
            (theta >= 0 ? 1.0 : -1.0) / (std::fabs(theta) + std::sqrt(theta * theta + 1.0));
        const double c = 1.0 / std::sqrt(t * t + 1.0), s = t * c;
        for (int k = 0; k < 6; ++k) { // A <- A J (columns p, q)
          const double akp = A[k][p], akq = A[k][q];
          A[k][p] = c * akp - s * akq, A[k][q] = s * akp + c * akq;
        }
        for (int k = 0; k < 6; ++k) { // A <- J^T A (rows p, q)
          const double apk = A[p][k], aqk = A[q][k];
          A[p][k] = c * apk - s * aqk, A[q][k] = s * apk + c * aqk;
        }
        for (int k = 0; k < 6; ++k) {
          const double vkp = V[k][p], vkq = V[k][q];
          V[k][p] = c * vkp - s * vkq, V[k][q] = s * vkp + c * vkq;
        }
      }
  }
  for (int i = 0; i < 6; ++i)
    lambda[i] = A[i][i];
}

// The rows of N (k x 6, a basis of the free motions) in reduced row echelon form, pivots taken in
// the column order rotations (3, 4, 5), then translations (0, 1, 2).
void ReducedRowEchelon(std::vector<std::vector<double>> *N) {
  const int order[6] = {3, 4, 5, 0, 1, 2};
  std::vector<std::vector<double>> &n = *N;
  size_t row = 0;
  for (int col : order) {
    if (row == n.size()) break;
    size_t best = row;
    for (size_t r = row; r < n.size(); ++r)
      if (std::fabs(n[r][col]) > std::fabs(n[best][col])) best = r;
    if (std::fabs(n[best][col]) < 1e-8) continue;
    std::swap(n[row], n[best]);
    const double pivot = n[row][col];
    for (double &v : n[row])
      v /= pivot;
    for (size_t r = 0; r < n.size(); ++r)
      if (r != row) {
        const double f = n[r][col];
        for (int k = 0; k < 6; ++k)
          n[r][k] -= f * n[row][k];
      }
    ++row;
  }
  for (auto &r : n)
    for (double &v : r)
      if (std::fabs(v) < 1e-9) v = 0.0;
}

std::string AxisName(const double d[3]) {
  for (int i = 0; i < 3; ++i)
    if (std::fabs(std::fabs(d[i]) - 1.0) < 1e-6) return std::string(1, "xyz"[i]);
  char buf[96];
  std::snprintf(buf, sizeof buf, "(%.3f, %.3f, %.3f)", d[0], d[1], d[2]);
  return buf;
}

} // namespace

std::string RigidMotion::Describe() const {
  if (!rotation) return "translation along " + AxisName(direction);
  const auto mm = [](double v) { return std::fabs(v) < 0.5 ? 0.0 : v; }; // no "-0"
  char buf[160];
  std::snprintf(buf, sizeof buf, "rotation about %s through (%.0f, %.0f, %.0f) mm",
                AxisName(direction).c_str(), mm(point[0]), mm(point[1]), mm(point[2]));
  return buf;
}

PetscErrorCode FreeRigidMotions(Problem *P, Vec U, std::vector<RigidMotion> *free) {
  const LocalMesh &m = P->mesh;
  const PetscScalar *u;
  double sums[4] = {0, 0, 0, (double)m.num_owned}, c[3], spread = 0.0, L;
  double G[6][6] = {}, lambda[6], V[6][6];
  PetscFunctionBeginUser;
  free->clear();
  PetscCall(VecGetArrayRead(U, &u));
  std::vector<double> x(3 * m.num_owned);
  for (PetscInt i = 0; i < 3 * m.num_owned; ++i)
    x[i] = m.X[i] + PetscRealPart(u[i]);
  PetscCall(VecRestoreArrayRead(U, &u));
  for (PetscInt l = 0; l < m.num_owned; ++l)
    for (int i = 0; i < 3; ++i)
      sums[i] += x[3 * l + i];
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, sums, 4, MPI_DOUBLE, MPI_SUM, P->comm));
  for (int i = 0; i < 3; ++i)
    c[i] = sums[3] > 0 ? sums[i] / sums[3] : 0.0;
  for (PetscInt l = 0; l < m.num_owned; ++l)
    for (int i = 0; i < 3; ++i)
      spread += (x[3 * l + i] - c[i]) * (x[3 * l + i] - c[i]);
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &spread, 1, MPI_DOUBLE, MPI_SUM, P->comm));
  L = sums[3] > 0 && spread > 0 ? std::sqrt(spread / sums[3]) : 1.0;
  for (PetscInt dof : P->con_owned_dof) {
    const PetscInt l = dof / 3;
    const int i = (int)(dof % 3);
    double r[3], mv[6] = {0, 0, 0, 0, 0, 0};
    for (int k = 0; k < 3; ++k)
      r[k] = (x[3 * l + k] - c[k]) / L;
    mv[i] = 1.0;
    // (theta x r)_i = theta . (r x e_i): the rotation columns are r x e_i.
    const double rxe[3][3] = {{0, r[2], -r[1]}, {-r[2], 0, r[0]}, {r[1], -r[0], 0}};
    for (int k = 0; k < 3; ++k)
      mv[3 + k] = rxe[i][k];
    for (int a = 0; a < 6; ++a)
      for (int b = 0; b < 6; ++b)
        G[a][b] += mv[a] * mv[b];
  }
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &G[0][0], 36, MPI_DOUBLE, MPI_SUM, P->comm));
  double trace = 0.0;
  for (int a = 0; a < 6; ++a)
    trace += G[a][a];
  SymmetricEigen6(G, lambda, V);
  std::vector<std::vector<double>> null;
  for (int k = 0; k < 6; ++k)
    if (lambda[k] <= kFreeTol * trace) {
      std::vector<double> q(6);
      for (int a = 0; a < 6; ++a)
        q[a] = V[a][k];
      null.push_back(q);
    }
  ReducedRowEchelon(&null);
  for (const auto &q : null) {
    RigidMotion mo;
    const double theta = std::sqrt(q[3] * q[3] + q[4] * q[4] + q[5] * q[5]);
    if (theta == 0.0) {
      const double t = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2]);
      for (int k = 0; k < 3; ++k)
        mo.direction[k] = q[k] / t;
    } else {
      // u = t + w x (x - c), w = theta / L: the axis passes through c + (w x t) / |w|^2.
      double w[3], wxt[3];
      for (int k = 0; k < 3; ++k)
        w[k] = q[3 + k] / L, mo.direction[k] = q[3 + k] / theta;
      wxt[0] = w[1] * q[2] - w[2] * q[1], wxt[1] = w[2] * q[0] - w[0] * q[2],
      wxt[2] = w[0] * q[1] - w[1] * q[0];
      const double w2 = w[0] * w[0] + w[1] * w[1] + w[2] * w[2];
      mo.rotation = true;
      for (int k = 0; k < 3; ++k)
        mo.point[k] = c[k] + wxt[k] / w2;
    }
    free->push_back(mo);
  }
  PetscFunctionReturn(0);
}

namespace {

// "rim (z), corner_1 (xyz)": the node groups (curves and points, not surfaces) whose nodes carry
// constraints and the components held there, the group with the most held nodes first (the one to
// name in the advice); *others: the node groups without any (at most 8 of each named). Collective.
PetscErrorCode DescribeSupports(Problem *P, std::string *held, std::string *others) {
  const LocalMesh &m = P->mesh;
  std::vector<std::string> names;
  std::vector<long long> count; // per group: held nodes, then the components' bits
  PetscFunctionBeginUser;
  for (const auto &set : m.node_sets) {
    if (set.first == "all" || m.element_sets.count(set.first)) continue;
    long long nodes = 0, bits = 0;
    for (PetscInt l : set.second) {
      if (l >= m.num_owned) continue;
      bool any = false;
      for (int i = 0; i < 3; ++i)
        if (P->dof_constrained[3 * l + i]) bits |= 1 << i, any = true;
      nodes += any;
    }
    names.push_back(set.first);
    count.push_back(nodes);
    count.push_back(bits);
  }
  std::vector<long long> total(count.size());
  if (!count.empty()) {
    PetscCallMPI(MPI_Allreduce(count.data(), total.data(), (int)count.size(), MPI_LONG_LONG,
                               MPI_SUM, P->comm));
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, count.data(), (int)count.size(), MPI_LONG_LONG,
                               MPI_BOR, P->comm));
  }
  std::vector<size_t> order(names.size());
  for (size_t k = 0; k < order.size(); ++k) order[k] = k;
  std::stable_sort(order.begin(), order.end(),
                   [&](size_t a, size_t b) { return total[2 * a] > total[2 * b]; });
  int nh = 0, no = 0;
  for (size_t k : order) {
    const bool supported = total[2 * k] > 0;
    std::string &s = supported ? *held : *others;
    int &n = supported ? nh : no;
    if (++n > 8) {
      if (n == 9) s += ", ...";
      continue;
    }
    if (!s.empty()) s += ", ";
    s += names[k];
    if (supported) {
      s += " (";
      for (int i = 0; i < 3; ++i)
        if (count[2 * k + 1] & (1 << i)) s += "xyz"[i];
      s += ")";
    }
  }
  PetscFunctionReturn(0);
}

} // namespace

PetscErrorCode CheckSupportsHoldRigidMotions(Problem *P, Vec U, bool refuse) {
  std::vector<RigidMotion> free;
  PetscFunctionBeginUser;
  PetscCall(FreeRigidMotions(P, U, &free));
  if (free.empty()) PetscFunctionReturn(0);
  std::string motions;
  for (const RigidMotion &mo : free)
    motions += (motions.empty() ? "" : ", ") + mo.Describe();
  for (const auto &term : P->terms) { // a rigid support may hold them (a plane, a cylinder with friction)
    if (!term->RigidMotionHolder()) continue;
    PetscCall(PetscPrintf(P->comm, "etfe: the DOF constraints leave %s free; %s are to hold %s\n", motions.c_str(),
                          term->RigidMotionHolder(), free.size() > 1 ? "them" : "it"));
    PetscFunctionReturn(0);
  }
  std::string held, others, way;
  PetscCall(DescribeSupports(P, &held, &others));
  if (P->scene.name == "structure") {
    if (!held.empty()) {
      const std::string first = held.substr(0, held.find(' '));
      way = "add the missing components to a supported group (e.g. -bc_" + first +
            "_fix xyz) or hold another node "
            "group with -bc_<group>_fix";
    } else {
      way = "hold a node group with -bc_<group>_fix xyz";
    }
    if (!others.empty()) way += " (node groups without a support: " + others + ")";
    way += ", or give the film a rigid support (-structure_rigid)";
  } else {
    way = "check the scene's supports";
  }
  const std::string what =
      "the supports leave the film free to move as a rigid body: " + motions +
      ". No constraint touches " + (free.size() > 1 ? "these motions" : "this motion") +
      " and nothing in the film resists " + (free.size() > 1 ? "them" : "it") +
      ", so the equilibrium is not unique (or there is none under a load along " +
      (free.size() > 1 ? "them" : "it") +
      "). Supports found: " + (held.empty() ? std::string("none") : held) + ". Way out: " + way;
  PetscCheck(!refuse, P->comm, PETSC_ERR_ARG_WRONG, "%s; -load_check_supports false runs it anyway",
             what.c_str());
  PetscCall(PetscPrintf(P->comm, "etfe: WARNING %s (-load_check_supports false: running anyway)\n",
                        what.c_str()));
  PetscFunctionReturn(0);
}

} // namespace etfe
