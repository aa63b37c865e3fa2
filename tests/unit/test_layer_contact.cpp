// Layer contact kernel (src/kernels/layer_contact.cpp, include/etfe/kernels/layer_contact.h):
//  * the gap is the signed distance to the triangle's plane, on the side the node started on;
//  * its gradient against central differences of the gap (a skewed triangle, every DOF);
//  * no force while the node is on its side; the force is the gradient of the penalty energy
//    k/2 g^2 (central differences) and sums to zero (no net force: action and reaction);
//  * the tangent with the gap's curvature against central differences of the force; without it
//    (what Newton uses) symmetric positive semi-definite: k dg dg^T.
#include "etfe/kernels/layer_contact.h"

#include "check.h"

#include <cmath>

namespace {

double Energy(const double x[12], double side, double k) {
  double g;
  etfe::LayerGap(x, side, &g, nullptr);
  return g < 0 ? 0.5 * k * g * g : 0.0;
}

} // namespace

int main() {
  {  // a node 2 above the plane z = 0 of a triangle with normal +z
    const double x[12] = {0.2, 0.3, 2.0, 0, 0, 0, 1, 0, 0, 0, 1, 0};
    double g;
    CHECK(etfe::LayerGap(x, 1.0, &g, nullptr), "gap of a regular triangle");
    CHECK_CLOSE(g, 2.0, 1e-15, 0.0);
    CHECK(etfe::LayerGap(x, -1.0, &g, nullptr), "gap, other side");
    CHECK_CLOSE(g, -2.0, 1e-15, 0.0);
    const double flat[12] = {0.2, 0.3, 2.0, 0, 0, 0, 1, 0, 0, 2, 0, 0};
    CHECK(!etfe::LayerGap(flat, 1.0, &g, nullptr), "a degenerate triangle is refused");
  }
  // a skewed triangle, the node just through it (side +1: it started above)
  const double x[12] = {0.31, 0.27, 0.05, -0.1, 0.05, 0.2, 1.2, -0.15, 0.35, 0.1, 0.95, 0.4};
  const double side = 1.0, k = 7.5, h = 1e-6;
  double g, dg[12];
  CHECK(etfe::LayerGap(x, side, &g, dg), "gap of the skewed triangle");
  CHECK(g < 0, "the node is through the triangle (g = %g)", g);
  for (int j = 0; j < 12; ++j) {
    double xp[12], xm[12], gp, gm;
    for (int i = 0; i < 12; ++i) xp[i] = xm[i] = x[i];
    xp[j] += h, xm[j] -= h;
    etfe::LayerGap(xp, side, &gp, nullptr);
    etfe::LayerGap(xm, side, &gm, nullptr);
    CHECK_CLOSE(dg[j], (gp - gm) / (2 * h), 1e-7, 1e-9);
  }
  double f[12], K[144];
  etfe::LayerContactForce(x, side, k, f, K, true);
  double sum[3] = {0, 0, 0};
  for (int j = 0; j < 12; ++j) {
    double xp[12], xm[12], fp[12], fm[12];
    for (int i = 0; i < 12; ++i) xp[i] = xm[i] = x[i];
    xp[j] += h, xm[j] -= h;
    CHECK_CLOSE(f[j], (Energy(xp, side, k) - Energy(xm, side, k)) / (2 * h), 1e-6, 1e-9);
    etfe::LayerContactForce(xp, side, k, fp, nullptr);
    etfe::LayerContactForce(xm, side, k, fm, nullptr);
    for (int i = 0; i < 12; ++i) CHECK_CLOSE(K[12 * i + j], (fp[i] - fm[i]) / (2 * h), 1e-5, 1e-8);
    sum[j % 3] += f[j];
  }
  for (double s : sum) CHECK_CLOSE(s, 0.0, 0.0, 1e-12);
  {  // Newton's part: k dg dg^T
    double fg[12], Kg[144];
    etfe::LayerContactForce(x, side, k, fg, Kg);
    for (int i = 0; i < 12; ++i)
      for (int j = 0; j < 12; ++j) CHECK_CLOSE(Kg[12 * i + j], k * dg[i] * dg[j], 1e-14, 1e-14);
  }
  {  // on its side: nothing
    double fo[12], Ko[144];
    const double out = etfe::LayerContactForce(x, -1.0, k, fo, Ko);
    CHECK(out > 0, "on its side the gap is positive (%g)", out);
    for (double v : fo) CHECK(v == 0.0, "no force on its side");
    for (double v : Ko) CHECK(v == 0.0, "no stiffness on its side");
  }
  TEST_MAIN_END();
}
