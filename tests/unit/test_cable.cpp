// Cable kernels (src/kernels/cable.cpp): a straight segment's force against EA E l / L0, the
// consistent tangent against central differences taut and slack, tension only, the constant-force
// and force-density segments, and the sliding chain (force uniform, the sum of segment lengths, its dense tangent).
#include "etfe/kernels/cable.h"

#include "check.h"
#include "fd_tangent.h"

#include <cmath>
#include <vector>

int main() {
  using namespace etfe;
  const double EA = 1.0e5, L0 = 1000.0;

  // Straight segment along a skew axis stretched by 1%: N = EA E l / L0, force along the axis.
  {
    const double e[3] = {2.0 / 3.0, -1.0 / 3.0, 2.0 / 3.0}, l = 1010.0;
    const double x[6] = {5, 6, 7, 5 + l * e[0], 6 + l * e[1], 7 + l * e[2]};
    double f[6];
    const CableState s = CableSegment(x, L0, EA, f, nullptr);
    const double E = (l * l - L0 * L0) / (2 * L0 * L0);
    CHECK(!s.slack, "a stretched segment is taut");
    CHECK_CLOSE(s.force, EA * E * l / L0, 1e-13, 0.0);
    CHECK_CLOSE(s.length, l, 1e-14, 0.0);
    for (int i = 0; i < 3; ++i) {
      CHECK_CLOSE(f[3 + i], s.force * e[i], 1e-12, 1e-12);
      CHECK_CLOSE(f[i], -f[3 + i], 0.0, 0.0);
    }
    // Engineering prestress: L0 for a force T gives back T within the GL/engineering difference.
    const double T = 500.0, Lc = CableLengthForForce(1000.0, T, EA);
    const double xs[6] = {0, 0, 0, 1000.0, 0, 0};
    const CableState sp = CableSegment(xs, Lc, EA, f, nullptr);
    CHECK_CLOSE(sp.force, T, 1e-2, 0.0);
  }

  // Tangent against central differences, taut and slack, on several shapes.
  const double shapes[3][6] = {{0, 0, 0, 1020, 30, -40}, {10, -5, 3, 700, 500, 200}, {0, 0, 0, 600, 100, 0}};
  for (int k = 0; k < 3; ++k) {
    double f[6], K[36], Kfd[36];
    const CableState s = CableSegment(shapes[k], L0, EA, f, K);
    auto res = [&](const double *x, double *out) { CableSegment(x, L0, EA, out, nullptr); };
    etfe_test::CentralDifferenceJacobian(res, shapes[k], 6, 6, 1e-4, Kfd);
    const double scale = std::fmax(MaxAbs(Kfd, 36), 1.0);
    CHECK(MaxDiff(K, Kfd, 36) <= 1e-6 * scale, "segment tangent vs differences (shape %d, %s): %g of %g", k,
          s.slack ? "slack" : "taut", MaxDiff(K, Kfd, 36), scale);
    if (k == 2) {  // 608 mm < L0: compressed, carries nothing
      CHECK(s.slack && s.force == 0.0 && MaxAbs(f, 6) == 0.0 && MaxAbs(K, 36) == 0.0,
            "a compressed segment carries nothing and has no stiffness");
    }
  }

  // Constant-force segment: force T along the chord whatever the length; tangent consistent.
  {
    const double x[6] = {0, 0, 0, 300, 400, 120}, T = 250.0;
    double f[6], K[36], Kfd[36];
    const CableState s = CableSegmentConstantForce(x, T, f, K);
    CHECK_CLOSE(std::sqrt(f[3] * f[3] + f[4] * f[4] + f[5] * f[5]), T, 1e-14, 0.0);
    CHECK_CLOSE(s.force, T, 0.0, 0.0);
    auto res = [&](const double *y, double *out) { CableSegmentConstantForce(y, T, out, nullptr); };
    etfe_test::CentralDifferenceJacobian(res, x, 6, 6, 1e-4, Kfd);
    CHECK(MaxDiff(K, Kfd, 36) <= 1e-8 * MaxAbs(Kfd, 36), "constant-force tangent: %g", MaxDiff(K, Kfd, 36));
  }

  // Force-density segment: force q (x2 - x1), N = q l, tangent q I blocks against differences (and
  // symmetric: the residual is linear in x).
  {
    const double x[6] = {10, -20, 5, 310, 380, 125}, q = 0.75;
    const double l = std::sqrt(300.0 * 300.0 + 400.0 * 400.0 + 120.0 * 120.0);
    double f[6], K[36], Kfd[36];
    const CableState s = CableSegmentForceDensity(x, q, f, K);
    CHECK_CLOSE(s.length, l, 1e-14, 0.0);
    CHECK_CLOSE(s.force, q * l, 1e-14, 0.0);
    CHECK_CLOSE(std::sqrt(f[3] * f[3] + f[4] * f[4] + f[5] * f[5]), q * l, 1e-14, 0.0);
    for (int i = 0; i < 3; ++i) {
      CHECK_CLOSE(f[3 + i], q * (x[3 + i] - x[i]), 1e-15, 0.0);
      CHECK_CLOSE(f[i], -f[3 + i], 0.0, 0.0);
    }
    auto res = [&](const double *y, double *out) { CableSegmentForceDensity(y, q, out, nullptr); };
    etfe_test::CentralDifferenceJacobian(res, x, 6, 6, 1e-4, Kfd);
    CHECK(MaxDiff(K, Kfd, 36) <= 1e-8 * MaxAbs(Kfd, 36), "force-density tangent: %g", MaxDiff(K, Kfd, 36));
    double asym = 0.0;
    for (int r = 0; r < 6; ++r)
      for (int c = 0; c < 6; ++c) asym = std::fmax(asym, std::fabs(K[6 * r + c] - K[6 * c + r]));
    CHECK(asym == 0.0, "force-density tangent symmetric: %g", asym);
  }

  // Sliding chain of 5 nodes over a bent path: force uniform (every segment's pull equals N), the
  // length is the sum, the dense tangent matches differences taut and slack.
  {
    const int nodes = 5, n = 3 * nodes;
    const double x[n] = {0, 0, 0, 250, 40, 10, 500, 60, 0, 760, 30, -20, 1000, 0, 0};
    double lsum = 0.0;
    for (int i = 0; i + 1 < nodes; ++i)
      lsum += std::sqrt(std::pow(x[3 * i + 3] - x[3 * i], 2) + std::pow(x[3 * i + 4] - x[3 * i + 1], 2) +
                        std::pow(x[3 * i + 5] - x[3 * i + 2], 2));
    for (double L0c : {0.99 * lsum, 1.02 * lsum}) {
      std::vector<double> f(n), K(n * n), Kfd(n * n);
      const CableState s = CableSliding(nodes, x, L0c, EA, f.data(), K.data());
      CHECK_CLOSE(s.length, lsum, 1e-14, 0.0);
      if (!s.slack) {
        CHECK_CLOSE(s.force, EA * (lsum - L0c) / L0c, 1e-13, 0.0);
        // The end nodes feel N along the end segments; an interior node N (e_{i-1} - e_i).
        CHECK_CLOSE(std::sqrt(f[0] * f[0] + f[1] * f[1] + f[2] * f[2]), s.force, 1e-13, 0.0);
        CHECK_CLOSE(std::sqrt(f[n - 3] * f[n - 3] + f[n - 2] * f[n - 2] + f[n - 1] * f[n - 1]), s.force, 1e-13, 0.0);
      } else {
        CHECK(s.force == 0.0 && MaxAbs(f.data(), n) == 0.0, "a slack sliding cable carries nothing");
      }
      auto res = [&](const double *y, double *out) { CableSliding(nodes, y, L0c, EA, out, nullptr); };
      etfe_test::CentralDifferenceJacobian(res, x, n, n, 1e-4, Kfd.data());
      const double scale = std::fmax(MaxAbs(Kfd.data(), n * n), 1.0);
      CHECK(MaxDiff(K.data(), Kfd.data(), n * n) <= 1e-6 * scale, "sliding tangent (%s): %g of %g",
            s.slack ? "slack" : "taut", MaxDiff(K.data(), Kfd.data(), n * n), scale);
    }
  }
  TEST_MAIN_END();
}
