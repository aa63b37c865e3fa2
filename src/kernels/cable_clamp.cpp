// Sliding cable through clamps with capstan friction (formulation and layouts in
// etfe/kernels/cable_clamp.h; docs/theory.md §14).
#include "etfe/kernels/cable_clamp.h"

#include <cmath>
#include <utility>

#include "etfe/kernels/cable.h"

namespace etfe {

namespace {

constexpr int kMaxChains = kCableMaxClamps + 1;
// A sticking clamp slips once its force ratio passes the capstan ratio by more than this part of
// the higher force: a clamp that has just slipped sits on the limit to rounding, and must not
// slip again on rounding alone when the same state is evaluated anew.
constexpr double kLimitTol = 1e-12;
constexpr int kNewtonMax = 60;
// The slip equations hold to this part of the largest trial force.
constexpr double kSolveTol = 1e-14;
constexpr double kStepTol = 1e-13;

// Engineering strain over a sub-chain, tension only, and its two partial derivatives.
struct SubForce {
  double N = 0.0, dl = 0.0, dL0 = 0.0;  // N, dN/dl, dN/dL0
};
SubForce Force(double l, double L0, double EA) {
  SubForce s;
  if (!(l > L0)) return s;
  s.N = EA * (l - L0) / L0, s.dl = EA / L0, s.dL0 = -EA * l / (L0 * L0);
  return s;
}

// dL0_j / dDelta_i: clamp i takes from sub-chain i and gives to sub-chain i + 1.
double LengthShare(int j, int i) { return j == i ? -1.0 : j == i + 1 ? 1.0 : 0.0; }

// Solves A X = B in place (A n x n, B n x nrhs, row-major; n <= kCableMaxClamps) by Gaussian
// elimination with partial pivoting. An unknown whose pivot vanishes (a clamp with both sides
// slack: its equation holds for any slip) gets 0.
void Solve(int n, double *A, int nrhs, double *B) {
  int perm_row[kCableMaxClamps];
  bool dead[kCableMaxClamps];
  for (int i = 0; i < n; ++i) perm_row[i] = i, dead[i] = false;
  for (int c = 0; c < n; ++c) {
    int p = c;
    for (int r = c + 1; r < n; ++r)
      if (std::fabs(A[r * n + c]) > std::fabs(A[p * n + c])) p = r;
    if (p != c) {
      for (int k = 0; k < n; ++k) std::swap(A[c * n + k], A[p * n + k]);
      for (int k = 0; k < nrhs; ++k) std::swap(B[c * nrhs + k], B[p * nrhs + k]);
      std::swap(perm_row[c], perm_row[p]);
    }
    if (!(std::fabs(A[c * n + c]) > 1e-300)) {
      dead[c] = true;
      continue;
    }
    for (int r = c + 1; r < n; ++r) {
      const double f = A[r * n + c] / A[c * n + c];
      if (f == 0.0) continue;
      for (int k = c; k < n; ++k) A[r * n + k] -= f * A[c * n + k];
      for (int k = 0; k < nrhs; ++k) B[r * nrhs + k] -= f * B[c * nrhs + k];
    }
  }
  for (int c = n - 1; c >= 0; --c)
    for (int k = 0; k < nrhs; ++k) {
      if (dead[c]) {
        B[c * nrhs + k] = 0.0;
        continue;
      }
      double v = B[c * nrhs + k];
      for (int j = c + 1; j < n; ++j) v -= A[c * n + j] * B[j * nrhs + k];
      B[c * nrhs + k] = v / A[c * n + c];
    }
}

double Length3(const double d[3]) { return std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]); }

} // namespace

CableClampReturnResult CableClampReturn(int m, const double *l, const double *L0c, double EA, const double *r, double *N,
                                        double *L0, double *delta, int *status, double *dNdl, double *dNdr) {
  const int nc = m - 1;
  CableClampReturnResult res;
  SubForce F[kMaxChains];
  for (int i = 0; i < nc; ++i) delta[i] = 0.0, status[i] = 0;
  auto update = [&]() {
    for (int j = 0; j < m; ++j) {
      L0[j] = L0c[j] - (j < nc ? delta[j] : 0.0) + (j > 0 ? delta[j - 1] : 0.0);
      F[j] = Force(l[j], L0[j], EA);
      N[j] = F[j].N;
    }
  };
  // The slipping clamps' equations G_a = N_high - r N_low (a over the active clamps) and their
  // Jacobian in the active slips (na x na).
  int act[kCableMaxClamps], na = 0;
  auto equations = [&](double *G, double *J) {
    for (int a = 0; a < na; ++a) {
      const int i = act[a], hi = status[i] > 0 ? i + 1 : i, lo = status[i] > 0 ? i : i + 1;
      G[a] = N[hi] - r[i] * N[lo];
      for (int b = 0; b < na; ++b) {
        const int k = act[b];
        J[a * na + b] = F[hi].dL0 * LengthShare(hi, k) - r[i] * F[lo].dL0 * LengthShare(lo, k);
      }
    }
  };
  update();
  // The force scale the slip equations are solved to: the largest trial force, tension or
  // compression (a slipping clamp may bring a taut sub-chain down to slack).
  double scale = 0.0;
  for (int j = 0; j < m; ++j) scale = std::fmax(scale, std::fabs(EA * (l[j] - L0c[j]) / L0c[j]));
  const int passes = 4 * nc + 4;
  bool settled = false;
  for (int pass = 0; pass < passes && !settled; ++pass) {
    na = 0;
    for (int i = 0; i < nc; ++i)
      if (status[i] != 0) act[na++] = i;
    // Newton on the slipping clamps' slips.
    for (int it = 0; na > 0 && it < kNewtonMax; ++it) {
      double G[kCableMaxClamps], J[kCableMaxClamps * kCableMaxClamps], gmax = 0.0;
      equations(G, J);
      for (int a = 0; a < na; ++a) gmax = std::fmax(gmax, std::fabs(G[a]));
      if (!(gmax > kSolveTol * scale)) break;
      for (int a = 0; a < na; ++a) G[a] = -G[a];
      Solve(na, J, 1, G);
      ++res.iterations;
      // Keep every stress-free length positive (a far trial could step past zero).
      double step = 1.0;
      for (int halvings = 0; halvings < 60; ++halvings) {
        bool ok = true;
        for (int j = 0; j < m && ok; ++j) {
          double L = L0c[j];
          for (int a = 0; a < na; ++a) L += step * G[a] * LengthShare(j, act[a]) + delta[act[a]] * LengthShare(j, act[a]);
          ok = L > 0.0;
        }
        if (ok) break;
        step *= 0.5;
      }
      double dmax = 0.0, lmax = 0.0;
      for (int a = 0; a < na; ++a) delta[act[a]] += step * G[a], dmax = std::fmax(dmax, std::fabs(step * G[a]));
      for (int j = 0; j < m; ++j) lmax = std::fmax(lmax, L0[j]);
      update();
      // A step below this part of the lengths: converged (where a sub-chain turns slack, the
      // equations have a kink and Newton may alternate across it at this level).
      if (!(dmax > kStepTol * lmax)) break;
      if (it + 1 == kNewtonMax) res.converged = false;
    }
    // A slip against its direction: the clamp sticks instead.
    bool changed = false;
    for (int i = 0; i < nc; ++i)
      if (status[i] != 0 && delta[i] * status[i] < 0.0) status[i] = 0, delta[i] = 0.0, changed = true;
    if (changed) {
      update();
      continue;
    }
    // A sticking clamp past the capstan limit: it slips, towards its higher force.
    for (int i = 0; i < nc; ++i) {
      if (status[i] != 0) continue;
      const double hi = std::fmax(N[i], N[i + 1]), lo = std::fmin(N[i], N[i + 1]);
      if (hi - r[i] * lo > kLimitTol * hi) status[i] = N[i + 1] > N[i] ? 1 : -1, changed = true;
    }
    settled = !changed;
  }
  if (!settled) res.converged = false;
  if (!dNdl && !dNdr) return res;
  // Tangent: dDelta_A = -J^-1 (G_l dl + G_r dr) for the slipping set at the solution.
  na = 0;
  for (int i = 0; i < nc; ++i)
    if (status[i] != 0) act[na++] = i;
  const int nrhs = m + nc;
  double G[kCableMaxClamps], J[kCableMaxClamps * kCableMaxClamps], X[kCableMaxClamps * (2 * kCableMaxClamps + 1)];
  equations(G, J);
  for (int a = 0; a < na; ++a) {
    const int i = act[a], hi = status[i] > 0 ? i + 1 : i, lo = status[i] > 0 ? i : i + 1;
    for (int k = 0; k < nrhs; ++k) X[a * nrhs + k] = 0.0;
    X[a * nrhs + hi] -= F[hi].dl;
    X[a * nrhs + lo] += r[i] * F[lo].dl;
    X[a * nrhs + m + i] += N[lo];  // -dG/dr_i = N_low
  }
  if (na > 0) Solve(na, J, nrhs, X);
  for (int j = 0; j < m; ++j) {
    for (int k = 0; k < nrhs; ++k) {
      double dL0 = 0.0;  // dL0_j / d(l_k or r_{k-m})
      for (int a = 0; a < na; ++a) dL0 += LengthShare(j, act[a]) * X[a * nrhs + k];
      const double v = F[j].dL0 * dL0 + (k == j ? F[j].dl : 0.0);
      if (k < m) {
        if (dNdl) dNdl[j * m + k] = v;
      } else if (dNdr) {
        dNdr[j * nc + (k - m)] = v;
      }
    }
  }
  return res;
}

double CableTurningAngle(const double a[3], const double b[3], const double c[3], double grad[9]) {
  const double d1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, d2[3] = {c[0] - b[0], c[1] - b[1], c[2] - b[2]};
  const double l1 = Length3(d1), l2 = Length3(d2);
  const double e1[3] = {d1[0] / l1, d1[1] / l1, d1[2] / l1}, e2[3] = {d2[0] / l2, d2[1] / l2, d2[2] / l2};
  const double cr[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
  const double s = Length3(cr), co = e1[0] * e2[0] + e1[1] * e2[1] + e1[2] * e2[2];
  const double theta = std::atan2(s, co);
  if (grad) {
    for (int k = 0; k < 9; ++k) grad[k] = 0.0;
    if (s > 1e-12)
      for (int i = 0; i < 3; ++i) {
        // d theta / d d1 = -(e2 - cos e1) / (sin l1), d theta / d d2 = -(e1 - cos e2) / (sin l2).
        const double g1 = -(e2[i] - co * e1[i]) / (s * l1), g2 = -(e1[i] - co * e2[i]) / (s * l2);
        grad[i] = -g1, grad[3 + i] = g1 - g2, grad[6 + i] = g2;
      }
  }
  return theta;
}

void CableClamped(int nodes, const double *x, int nc, const int *clamp, const double *L0c, double EA, double mu,
                  double *f, double *K, CableClampState *state) {
  const int n = 3 * nodes, m = nc + 1;
  CableClampState local;
  CableClampState &s = state ? *state : local;
  auto first = [&](int j) { return j == 0 ? 0 : clamp[j - 1]; };
  auto last = [&](int j) { return j == nc ? nodes - 1 : clamp[j]; };
  auto seg = [&](int k, int comp) {  // unit direction of segment k (node k -> k + 1)
    const double d[3] = {x[3 * k + 3] - x[3 * k], x[3 * k + 4] - x[3 * k + 1], x[3 * k + 5] - x[3 * k + 2]};
    return d[comp] / Length3(d);
  };
  for (int j = 0; j < m; ++j) {
    s.length[j] = 0.0;
    for (int k = first(j); k < last(j); ++k) {
      const double d[3] = {x[3 * k + 3] - x[3 * k], x[3 * k + 4] - x[3 * k + 1], x[3 * k + 5] - x[3 * k + 2]};
      s.length[j] += Length3(d);
    }
  }
  double grad[kCableMaxClamps][9];
  for (int i = 0; i < nc; ++i) {
    const int c = clamp[i];
    s.theta[i] = CableTurningAngle(&x[3 * c - 3], &x[3 * c], &x[3 * c + 3], K ? grad[i] : nullptr);
    s.ratio[i] = std::exp(mu * s.theta[i]);
  }
  double dNdl[kMaxChains * kMaxChains], dNdr[kMaxChains * kCableMaxClamps];
  s.result = CableClampReturn(m, s.length, L0c, EA, s.ratio, s.force, s.L0, s.delta, s.status, K ? dNdl : nullptr,
                              K ? dNdr : nullptr);
  for (int k = 0; k < n; ++k) f[k] = 0.0;
  if (K)
    for (int k = 0; k < n * n; ++k) K[k] = 0.0;
  // Each segment: its sub-chain's force along it, and that force's geometric stiffness.
  double fe[6], Ke[36];
  for (int j = 0; j < m; ++j)
    for (int k = first(j); k < last(j); ++k) {
      CableSlidingSegment(&x[3 * k], s.force[j], 0.0, fe, K ? Ke : nullptr);
      for (int a = 0; a < 6; ++a) f[3 * k + a] += fe[a];
      if (K)
        for (int a = 0; a < 6; ++a)
          for (int b = 0; b < 6; ++b) K[(3 * k + a) * n + 3 * k + b] += Ke[6 * a + b];
    }
  if (!K) return;
  // g_j = dl_j/dx at a node of sub-chain j: e_{node-1} - e_node within the sub-chain.
  auto g = [&](int j, int node, int comp) {
    double v = 0.0;
    if (node > first(j)) v += seg(node - 1, comp);
    if (node < last(j)) v -= seg(node, comp);
    return v;
  };
  for (int j = 0; j < m; ++j)
    for (int q = 0; q < m; ++q) {
      const double D = dNdl[j * m + q];
      if (D == 0.0) continue;
      for (int a = first(j); a <= last(j); ++a)
        for (int ia = 0; ia < 3; ++ia) {
          const double ga = D * g(j, a, ia);
          for (int b = first(q); b <= last(q); ++b)
            for (int ib = 0; ib < 3; ++ib) K[(3 * a + ia) * n + 3 * b + ib] += ga * g(q, b, ib);
        }
    }
  // The capstan ratio follows the current angle: dN_j/dr_i mu r_i dtheta_i/dx.
  for (int j = 0; j < m; ++j)
    for (int i = 0; i < nc; ++i) {
      const double coef = dNdr[j * nc + i] * mu * s.ratio[i];
      if (coef == 0.0) continue;
      const int c0 = clamp[i] - 1;
      for (int a = first(j); a <= last(j); ++a)
        for (int ia = 0; ia < 3; ++ia) {
          const double ga = coef * g(j, a, ia);
          for (int b = 0; b < 9; ++b) K[(3 * a + ia) * n + 3 * c0 + b] += ga * grad[i][b];
        }
    }
}

} // namespace etfe
