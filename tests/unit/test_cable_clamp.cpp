// Clamps with capstan friction on a sliding cable (src/kernels/cable_clamp.cpp): mu = 0 gives the
// frictionless sliding cable's one force; stick keeps the trial forces; slip puts the force ratio
// on exp(mu theta) and conserves the stress-free length; the ratio never passes the limit over
// many random states; the return map's dN/dl, dN/dr and the chain's tangent against central
// differences in stick and in slip; the turning angle's gradient.
#include "etfe/kernels/cable_clamp.h"

#include "etfe/kernels/cable.h"

#include "check.h"
#include "fd_tangent.h"

#include <cmath>
#include <cstdio>
#include <vector>

namespace {

// A bent chain of 7 nodes (clamps at nodes 2 and 4), turning by ~0.3-0.6 rad at each.
const double kChain[21] = {0, 0, 0, 200, 30, 10, 400, 100, 20, 580, 230, 0, 720, 390, -30, 900, 520, -20, 1100, 600, 0};
const int kClamps[2] = {2, 4};

} // namespace

int main() {
  using namespace etfe;
  const double EA = 1.0e5;

  // mu = 0: every clamp slips until the forces are equal; they equal the sliding cable's force.
  {
    const int m = 3;
    const double l[m] = {1000.0, 700.0, 1300.0}, L0c[m] = {990.0, 680.0, 1295.0}, r[m - 1] = {1.0, 1.0};
    double N[m], L0[m], d[m - 1];
    int st[m - 1];
    const CableClampReturnResult res = CableClampReturn(m, l, L0c, EA, r, N, L0, d, st, nullptr, nullptr);
    const double Ls = L0c[0] + L0c[1] + L0c[2], ls = l[0] + l[1] + l[2], Nsl = EA * (ls - Ls) / Ls;
    CHECK(res.converged, "mu = 0 return map converged");
    for (int j = 0; j < m; ++j) CHECK_CLOSE(N[j], Nsl, 1e-12, 0.0);
    CHECK_CLOSE(L0[0] + L0[1] + L0[2], Ls, 1e-15, 0.0);
    // And through the chain kernel: the same nodal forces as CableSliding.
    double Lc[3] = {0, 0, 0}, total = 0.0;
    {
      double f[21];
      CableClampState s;
      CableClamped(7, kChain, 2, kClamps, Lc, EA, 0.0, f, nullptr, &s);  // Lc = 0: only the lengths
      for (int j = 0; j < 3; ++j) Lc[j] = s.length[j] / (1.0 + (100.0 + 50.0 * j) / EA), total += Lc[j];
    }
    double f[21], fs[21];
    CableClampState s;
    CableClamped(7, kChain, 2, kClamps, Lc, EA, 0.0, f, nullptr, &s);
    const CableState sl = CableSliding(7, kChain, total, EA, fs, nullptr);
    CHECK(MaxDiff(f, fs, 21) <= 1e-11 * sl.force, "mu = 0 clamps: nodal forces of the sliding cable: %g of %g",
          MaxDiff(f, fs, 21), sl.force);
  }

  // Two sub-chains, r = 1.5: a trial ratio 1.2 sticks, 3 slips onto 1.5 (either direction).
  {
    const double r[1] = {1.5};
    const double l[2] = {1000.0, 1000.0};
    for (double T1 : {120.0, 300.0, 30.0}) {
      const double L0c[2] = {1000.0 / (1 + 100.0 / EA), 1000.0 / (1 + T1 / EA)};
      double N[2], L0[2], d[1];
      int st[1];
      CableClampReturn(2, l, L0c, EA, r, N, L0, d, st, nullptr, nullptr);
      const double trial = T1 / 100.0;
      if (trial < 1.5 && trial > 1 / 1.5) {
        CHECK(st[0] == 0 && d[0] == 0.0, "ratio %g below the limit: sticks", trial);
        CHECK_CLOSE(N[1], T1, 1e-12, 0.0);
      } else {
        CHECK(st[0] == (T1 > 100.0 ? 1 : -1), "ratio %g beyond the limit: slips towards the higher force", trial);
        CHECK_CLOSE(std::fmax(N[0], N[1]) / std::fmin(N[0], N[1]), 1.5, 1e-12, 0.0);
        CHECK_CLOSE(L0[0] + L0[1], L0c[0] + L0c[1], 1e-15, 0.0);
        CHECK(d[0] * st[0] > 0.0, "the slip goes towards the higher force");
      }
    }
  }

  // Random states of 4 sub-chains: no force ratio across a clamp passes its capstan ratio, and a
  // slipping clamp is on it.
  {
    unsigned seed = 12345u;
    auto rnd = [&]() { return (seed = seed * 1664525u + 1013904223u) / 4294967296.0; };
    double worst = 0.0;
    int slips = 0, sticks = 0, failed = 0;
    for (int trial = 0; trial < 2000; ++trial) {
      const int m = 4;
      double l[m], L0c[m], r[m - 1], N[m], L0[m], d[m - 1];
      int st[m - 1];
      for (int j = 0; j < m; ++j) l[j] = 500.0 + 1000.0 * rnd(), L0c[j] = l[j] / (1.0 + 0.02 * rnd() - 0.002);
      for (int i = 0; i < m - 1; ++i) r[i] = std::exp(0.3 * 3.0 * rnd());
      const CableClampReturnResult res = CableClampReturn(m, l, L0c, EA, r, N, L0, d, st, nullptr, nullptr);
      failed += !res.converged;
      double scale = 0.0;  // the largest trial force
      for (int j = 0; j < m; ++j) scale = std::fmax(scale, std::fabs(EA * (l[j] - L0c[j]) / L0c[j]));
      for (int i = 0; i < m - 1; ++i) {
        const double hi = std::fmax(N[i], N[i + 1]), lo = std::fmin(N[i], N[i + 1]);
        worst = std::fmax(worst, (hi - r[i] * lo) / (scale + EA));
        if (st[i]) {
          ++slips;
          // (to 1e-12 of the force scale, or 1e-12 EA where a sub-chain turns slack: kStepTol)
          CHECK(std::fabs(hi - r[i] * lo) <= 1e-12 * (scale + EA), "a slipping clamp is on the limit: %g of %g",
                hi - r[i] * lo, scale);
        } else {
          ++sticks;
        }
      }
    }
    CHECK(failed == 0, "every return map converged (%d did not)", failed);
    CHECK(worst <= 1e-12, "largest (T_high - r T_low) / (largest trial force + EA) over 2000 random states: %g", worst);
    CHECK(slips > 500 && sticks > 500, "both states met: %d slips, %d sticks", slips, sticks);
    std::printf("random states: %d slipping and %d sticking clamps, largest excess over the limit %.2e\n", slips, sticks,
                worst);
  }

  // The return map's tangent against differences, stick and slip (3 sub-chains, 2 clamps).
  for (int c = 0; c < 3; ++c) {
    const int m = 3;
    const double T[3][3] = {{100, 110, 105}, {300, 100, 120}, {100, 300, 90}};
    double z[5] = {1000.0, 800.0, 1200.0, 1.3, 1.2};  // l, then r
    double L0c[m];
    for (int j = 0; j < m; ++j) L0c[j] = z[j] / (1.0 + T[c][j] / EA);
    double N[m], L0[m], d[2], dNdl[9], dNdr[6], J[15], Jfd[15];
    int st[2];
    CableClampReturn(m, z, L0c, EA, z + 3, N, L0, d, st, dNdl, dNdr);
    for (int j = 0; j < m; ++j) {
      for (int k = 0; k < m; ++k) J[j * 5 + k] = dNdl[j * m + k];
      for (int i = 0; i < 2; ++i) J[j * 5 + 3 + i] = dNdr[j * 2 + i];
    }
    auto res = [&](const double *y, double *out) {
      double L[m], dd[2];
      int s2[2];
      CableClampReturn(m, y, L0c, EA, y + 3, out, L, dd, s2, nullptr, nullptr);
    };
    etfe_test::CentralDifferenceJacobian(res, z, 5, 3, 1e-6, Jfd);
    const double scale = MaxAbs(Jfd, 15);
    CHECK(MaxDiff(J, Jfd, 15) <= 1e-6 * scale, "return map tangent (case %d, status %d %d): %g of %g", c, st[0], st[1],
          MaxDiff(J, Jfd, 15), scale);
    if (c == 0) CHECK(st[0] == 0 && st[1] == 0, "case 0 sticks at both clamps");
    if (c > 0) CHECK(st[0] != 0, "case %d slips at clamp 0", c);
  }

  // The turning angle and its gradient.
  {
    const double p[9] = {0, 0, 0, 100, 20, 5, 180, 90, -10};
    double grad[9], gfd[9];
    const double th = CableTurningAngle(p, p + 3, p + 6, grad);
    auto res = [&](const double *y, double *out) { out[0] = CableTurningAngle(y, y + 3, y + 6, nullptr); };
    etfe_test::CentralDifferenceJacobian(res, p, 9, 1, 1e-5, gfd);
    CHECK(th > 0.3 && th < 1.2, "a turning angle of %g rad", th);
    CHECK(MaxDiff(grad, gfd, 9) <= 1e-7 * MaxAbs(gfd, 9), "angle gradient: %g", MaxDiff(grad, gfd, 9));
  }

  // The whole chain's tangent (mu = 0.4, the ratio following the current angles) against
  // differences of its nodal forces: all stick, both slipping, and one slipping beside one that
  // sticks (case 3: clamp 1's trial is past the limit, but once clamp 0 has slipped it sticks).
  for (int c = 0; c < 4; ++c) {
    const double T[4][3] = {{100, 105, 110}, {400, 100, 120}, {100, 100, 400}, {100, 300, 200}};
    double Lc[3];
    {
      double f[21];
      CableClampState s;
      const double zero[3] = {0, 0, 0};
      CableClamped(7, kChain, 2, kClamps, zero, EA, 0.4, f, nullptr, &s);
      for (int j = 0; j < 3; ++j) Lc[j] = s.length[j] / (1.0 + T[c][j] / EA);
    }
    std::vector<double> f(21), K(441), Kfd(441);
    CableClampState s;
    CableClamped(7, kChain, 2, kClamps, Lc, EA, 0.4, f.data(), K.data(), &s);
    auto res = [&](const double *y, double *out) { CableClamped(7, y, 2, kClamps, Lc, EA, 0.4, out, nullptr, nullptr); };
    etfe_test::CentralDifferenceJacobian(res, kChain, 21, 21, 1e-5, Kfd.data());
    const double scale = MaxAbs(Kfd.data(), 441);
    CHECK(MaxDiff(K.data(), Kfd.data(), 441) <= 1e-6 * scale, "chain tangent (case %d, status %d %d): %g of %g", c,
          s.status[0], s.status[1], MaxDiff(K.data(), Kfd.data(), 441), scale);
    if (c == 0) CHECK(s.status[0] == 0 && s.status[1] == 0, "chain case 0 sticks");
    if (c == 1 || c == 2) CHECK(s.status[0] != 0 && s.status[1] != 0, "chain case %d slips at both clamps", c);
    if (c == 3) CHECK(s.status[0] == 1 && s.status[1] == 0, "chain case 3: clamp 0 slips, clamp 1 sticks");
    for (int i = 0; i < 2; ++i) {
      const double hi = std::fmax(s.force[i], s.force[i + 1]), lo = std::fmin(s.force[i], s.force[i + 1]);
      CHECK(hi <= s.ratio[i] * lo * (1 + 1e-12), "chain case %d clamp %d: ratio %g within exp(mu theta) = %g", c, i,
            hi / lo, s.ratio[i]);
    }
    std::printf("chain case %d: status %d %d, forces %.3f %.3f %.3f N, tangent error %.2e of %.2e\n", c, s.status[0],
                s.status[1], s.force[0], s.force[1], s.force[2], MaxDiff(K.data(), Kfd.data(), 441), scale);
  }
  TEST_MAIN_END();
}
