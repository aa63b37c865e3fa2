// Follower pressure load (src/kernels/pressure.cpp): the load stiffness is the exact derivative
// of the load, the resultant is p times the area vector, and reversing the node order (the
// normal) reverses the load; the Jacobian's fused K -= L matches the load stiffness bitwise.
#include "etfe/kernels/pressure.h"

#include "check.h"
#include "fd_tangent.h"

#include <cmath>
#include <cstdint>
#include <cstring>

int main() {
  using etfe::PressureLoad;
  Rng rng{12345};

  for (int trial = 0; trial < 20; ++trial) {
    double x[9];
    const double scale = trial < 10 ? 1.0 : 1000.0;  // unit-size and mm-size (saddle) triangles
    for (int k = 0; k < 9; ++k) x[k] = scale * rng.Next();
    const double p = 0.002 * (1.0 + rng.Next());  // 0 .. 4 kPa in MPa

    double f[9], L[81];
    PressureLoad(p, x, f, L);

    // f is quadratic in x: central differences are exact up to rounding.
    double Lfd[81];
    etfe_test::CentralDifferenceJacobian([&](const double *y, double *fy) { PressureLoad(p, y, fy, nullptr); }, x, 9,
                                         9, 1e-4 * scale, Lfd);
    double diff[81];
    for (int k = 0; k < 81; ++k) diff[k] = L[k] - Lfd[k];
    const double rel = MaxAbs(diff, 81) / MaxAbs(L, 81);
    CHECK(rel < 1e-7, "trial %d: |L - L_fd|/|L| = %g", trial, rel);

    // The Jacobian loop's fused form: K -= L in place, bitwise as subtracting the whole L.
    double K0[81], K1[81], f1[9];
    for (int k = 0; k < 81; ++k) K0[k] = K1[k] = scale * rng.Next();
    for (int k = 0; k < 81; ++k) K0[k] -= L[k];
    etfe::PressureLoadSubtractTangent(p, x, f1, K1);
    bool same = true;
    for (int k = 0; k < 81; ++k) same = same && std::memcmp(&K0[k], &K1[k], sizeof(double)) == 0;
    for (int k = 0; k < 9; ++k) same = same && std::memcmp(&f[k], &f1[k], sizeof(double)) == 0;
    CHECK(same, "trial %d: PressureLoadSubtractTangent differs from PressureLoad and K -= L", trial);
    // Without the force (the Jacobian loop's call): the same K.
    double K2[81], K3[81];
    for (int k = 0; k < 81; ++k) K2[k] = K3[k] = scale * rng.Next();
    for (int k = 0; k < 81; ++k) K2[k] -= L[k];
    etfe::PressureLoadSubtractTangent(p, x, nullptr, K3);
    CHECK(std::memcmp(K2, K3, sizeof K2) == 0, "trial %d: K -= L without the force differs", trial);

    // Resultant = p * (area vector) = p * area * unit normal.
    double a[3], b[3], n[3];
    for (int i = 0; i < 3; ++i) {
      a[i] = x[3 + i] - x[i];
      b[i] = x[6 + i] - x[i];
    }
    n[0] = a[1] * b[2] - a[2] * b[1];
    n[1] = a[2] * b[0] - a[0] * b[2];
    n[2] = a[0] * b[1] - a[1] * b[0];
    const double twice_area = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    for (int i = 0; i < 3; ++i) {
      const double total = f[i] + f[3 + i] + f[6 + i];
      const double expect = p * 0.5 * twice_area * (n[i] / twice_area);
      CHECK_CLOSE(total, expect, 1e-13, 1e-15 * p * twice_area);
    }

    // Swapping nodes 2 and 3 flips the normal and the load; the per-node load is the same.
    double xs[9], fs[9];
    for (int i = 0; i < 3; ++i) {
      xs[i] = x[i];
      xs[3 + i] = x[6 + i];
      xs[6 + i] = x[3 + i];
    }
    PressureLoad(p, xs, fs, nullptr);
    for (int k = 0; k < 9; ++k) CHECK_CLOSE(fs[k], -f[k], 1e-13, 1e-15 * p * twice_area);
    // A cyclic renumbering keeps the orientation and hence the load.
    double xc[9], fc[9];
    for (int k = 0; k < 9; ++k) xc[k] = x[(k + 3) % 9];
    PressureLoad(p, xc, fc, nullptr);
    for (int k = 0; k < 9; ++k) CHECK_CLOSE(fc[k], f[k], 1e-12, 1e-14 * p * twice_area);
  }

  // Hand case: unit right triangle in the XY plane, counter-clockwise seen from +Z: the load on
  // each node is p/6 along +Z.
  {
    const double x[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    double f[9], L[81];
    PressureLoad(3.0, x, f, L);
    for (int a = 0; a < 3; ++a) {
      CHECK(f[3 * a] == 0.0 && f[3 * a + 1] == 0.0, "in-plane load at node %d", a);
      CHECK_CLOSE(f[3 * a + 2], 0.5, 1e-15, 0.0);
    }
    // Lifting node 3 tilts the normal towards -Y: df_y/dz_3 = p/6 * (x2 - x1)_x * (-1).
    CHECK_CLOSE(L[9 * 1 + 3 * 2 + 2], -0.5, 1e-15, 0.0);
  }

  TEST_MAIN_END();
}
