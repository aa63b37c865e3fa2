// Cable kernels (docs/theory.md §14; formulation and layouts in etfe/kernels/cable.h).
#include "etfe/kernels/cable.h"

#include <cmath>

namespace etfe {

namespace {

// Writes the 6x6 segment tangent from its 3x3 block B (K11 = K22 = B, K12 = K21 = -B).
void SegmentBlocks(const double B[9], double K[36]) {
  for (int a = 0; a < 2; ++a)
    for (int b = 0; b < 2; ++b) {
      const double s = a == b ? 1.0 : -1.0;
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) K[(3 * a + i) * 6 + 3 * b + j] = s * B[3 * i + j];
    }
}

double Length(const double d[3]) { return std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]); }

// Length of the segment from node i to node i + 1 of a chain.
double SegmentLength(const double *x, int i) {
  const double d[3] = {x[3 * i + 3] - x[3 * i], x[3 * i + 4] - x[3 * i + 1], x[3 * i + 5] - x[3 * i + 2]};
  return Length(d);
}

} // namespace

CableState CableSegment(const double x[6], double L0, double EA, double f[6], double K[36]) {
  const double d[3] = {x[3] - x[0], x[4] - x[1], x[5] - x[2]};
  CableState s;
  s.length = Length(d);
  const double E = (s.length * s.length - L0 * L0) / (2.0 * L0 * L0);
  for (int k = 0; k < 6; ++k) f[k] = 0.0;
  if (K)
    for (int k = 0; k < 36; ++k) K[k] = 0.0;
  if (!(E > 0.0)) {  // slack (or exactly unstrained): no force, no stiffness
    s.slack = true;
    return s;
  }
  const double c = EA * E / L0;  // force per unit of d
  s.force = c * s.length;
  for (int i = 0; i < 3; ++i) f[3 + i] = c * d[i], f[i] = -c * d[i];
  if (K) {
    double B[9];
    const double m = EA / (L0 * L0 * L0);
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) B[3 * i + j] = m * d[i] * d[j] + (i == j ? c : 0.0);
    SegmentBlocks(B, K);
  }
  return s;
}

double CableSlidingSegment(const double x[6], double N, double ka, double f[6], double K[36]) {
  const double d[3] = {x[3] - x[0], x[4] - x[1], x[5] - x[2]};
  const double l = Length(d);
  const double e[3] = {d[0] / l, d[1] / l, d[2] / l};
  for (int i = 0; i < 3; ++i) f[3 + i] = N * e[i], f[i] = -N * e[i];
  if (K) {
    double B[9];
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) B[3 * i + j] = ka * e[i] * e[j] + (N / l) * ((i == j ? 1.0 : 0.0) - e[i] * e[j]);
    SegmentBlocks(B, K);
  }
  return l;
}

CableState CableSegmentConstantForce(const double x[6], double T, double f[6], double K[36]) {
  CableState s;
  s.length = CableSlidingSegment(x, T, 0.0, f, K);
  s.force = T;
  return s;
}

CableState CableSegmentForceDensity(const double x[6], double q, double f[6], double K[36]) {
  const double d[3] = {x[3] - x[0], x[4] - x[1], x[5] - x[2]};
  CableState s;
  s.length = Length(d);
  s.force = q * s.length;
  for (int i = 0; i < 3; ++i) f[3 + i] = q * d[i], f[i] = -q * d[i];
  if (K) {
    const double B[9] = {q, 0.0, 0.0, 0.0, q, 0.0, 0.0, 0.0, q};
    SegmentBlocks(B, K);
  }
  return s;
}

CableState CableSliding(int nodes, const double *x, double L0, double EA, double *f, double *K) {
  const int n = 3 * nodes;
  CableState s;
  for (int i = 0; i + 1 < nodes; ++i) s.length += SegmentLength(x, i);
  s.slack = !(s.length > L0);
  s.force = s.slack ? 0.0 : EA * (s.length - L0) / L0;
  const double ka = s.slack ? 0.0 : EA / L0;
  for (int k = 0; k < n; ++k) f[k] = 0.0;
  if (K)
    for (int k = 0; k < n * n; ++k) K[k] = 0.0;
  double fe[6], Ke[36];
  for (int i = 0; i + 1 < nodes; ++i) {
    CableSlidingSegment(&x[3 * i], s.force, 0.0, fe, K ? Ke : nullptr);
    for (int k = 0; k < 6; ++k) f[3 * i + k] += fe[k];
    if (K)
      for (int r = 0; r < 6; ++r)
        for (int c = 0; c < 6; ++c) K[(3 * i + r) * n + 3 * i + c] += Ke[6 * r + c];
  }
  if (K && ka > 0.0) {
    // The rank-one part over the whole chain: g = dl/dx, node i's part e_{i-1} - e_i (computed
    // per entry: a kernel allocates nothing).
    auto G = [&](int node, int comp) {
      double v = 0.0;
      if (node > 0) v += (x[3 * node + comp] - x[3 * node - 3 + comp]) / SegmentLength(x, node - 1);
      if (node + 1 < nodes) v -= (x[3 * node + 3 + comp] - x[3 * node + comp]) / SegmentLength(x, node);
      return v;
    };
    for (int r = 0; r < n; ++r) {
      const double gr = G(r / 3, r % 3);
      for (int c = 0; c < n; ++c) K[r * n + c] += ka * gr * G(c / 3, c % 3);
    }
  }
  return s;
}

double CableLengthForForce(double L, double T, double EA) { return L / (1.0 + T / EA); }

} // namespace etfe
