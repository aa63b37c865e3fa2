// Node-to-triangle frictionless penalty contact between film layers (see layer_contact.h).
#include "etfe/kernels/layer_contact.h"
#include "etfe/kernels/vec3.h"

#include <algorithm>
#include <cmath>

namespace etfe {

bool LayerGap(const double x[12], double side, double *g, double dg[12]) {
  const double *xs = x, *x1 = x + 3, *x2 = x + 6, *x3 = x + 9;
  double a[3], b[3], d[3], c[3];
  for (int i = 0; i < 3; ++i) a[i] = x2[i] - x1[i], b[i] = x3[i] - x1[i], d[i] = xs[i] - x1[i];
  Cross(a, b, c);
  const double len = std::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
  if (!(len > 0)) return false;
  const double T = d[0] * c[0] + d[1] * c[1] + d[2] * c[2];  // det[d, a, b]
  *g = side * T / len;
  if (!dg) return true;
  // dT: xs -> a x b, x2 -> b x d, x3 -> d x a, x1 -> minus their sum; d|c|: x2 -> b x n,
  // x3 -> n x a, x1 -> minus their sum (n = c / |c|).
  double n[3], bd[3], da[3], bn[3], na[3];
  for (int i = 0; i < 3; ++i) n[i] = c[i] / len;
  Cross(b, d, bd), Cross(d, a, da), Cross(b, n, bn), Cross(n, a, na);
  for (int i = 0; i < 3; ++i) {
    const double ts = c[i], t2 = bd[i], t3 = da[i], l2 = bn[i], l3 = na[i];
    dg[i] = side * ts / len;
    dg[6 + i] = side * (t2 - T * l2 / len) / len;
    dg[9 + i] = side * (t3 - T * l3 / len) / len;
    dg[3 + i] = -(dg[i] + dg[6 + i] + dg[9 + i]);  // g is unchanged by a rigid translation
  }
  return true;
}

double LayerContactForce(const double x[12], double side, double k, double f[12], double K[144], bool curvature) {
  double g, dg[12];
  std::fill(f, f + 12, 0.0);
  if (K) std::fill(K, K + 144, 0.0);
  if (!LayerGap(x, side, &g, dg)) return 0.0;
  if (g >= 0) return g;
  for (int i = 0; i < 12; ++i) f[i] = k * g * dg[i];
  if (!K) return g;
  for (int i = 0; i < 12; ++i)
    for (int j = 0; j < 12; ++j) K[12 * i + j] = k * dg[i] * dg[j];
  if (!curvature) return g;
  double scale = 0.0;  // a length of the triangle, for the difference step
  for (int i = 0; i < 3; ++i) scale = std::max(scale, std::fabs(x[6 + i] - x[3 + i]) + std::fabs(x[9 + i] - x[3 + i]));
  const double h = 1e-6 * scale;
  for (int j = 0; j < 12; ++j) {
    double xp[12], xm[12], gp, gm, dp[12], dm[12];
    std::copy(x, x + 12, xp), std::copy(x, x + 12, xm);
    xp[j] += h, xm[j] -= h;
    LayerGap(xp, side, &gp, dp);
    LayerGap(xm, side, &gm, dm);
    for (int i = 0; i < 12; ++i) K[12 * i + j] += k * g * (dp[i] - dm[i]) / (2 * h);
  }
  for (int i = 0; i < 12; ++i)  // the Hessian is symmetric: drop the differences' asymmetry
    for (int j = 0; j < i; ++j) K[12 * i + j] = K[12 * j + i] = 0.5 * (K[12 * i + j] + K[12 * j + i]);
  return g;
}

} // namespace etfe
