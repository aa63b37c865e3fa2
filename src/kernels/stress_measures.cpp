// Cauchy stress, its von Mises value and principal stresses of the membrane (see
// stress_measures.h for the thickness assumption).
#include "etfe/kernels/stress_measures.h"

#include <cmath>

namespace etfe {

void CauchyStress(const double F[6], const double S[3], double sigma[6]) {
  // P = F S (3x2), sigma = P F^T.
  double P[6];
  for (int i = 0; i < 3; ++i) {
    P[2 * i] = F[2 * i] * S[0] + F[2 * i + 1] * S[2];
    P[2 * i + 1] = F[2 * i] * S[2] + F[2 * i + 1] * S[1];
  }
  auto at = [&](int i, int j) { return P[2 * i] * F[2 * j] + P[2 * i + 1] * F[2 * j + 1]; };
  sigma[0] = at(0, 0);
  sigma[1] = at(1, 1);
  sigma[2] = at(2, 2);
  sigma[3] = at(0, 1);
  sigma[4] = at(1, 2);
  sigma[5] = at(0, 2);
}

double MisesStress3(const double s[6]) {
  const double a = s[0] - s[1], b = s[1] - s[2], c = s[2] - s[0];
  return std::sqrt(0.5 * (a * a + b * b + c * c) + 3.0 * (s[3] * s[3] + s[4] * s[4] + s[5] * s[5]));
}

void PrincipalStresses(const double F[6], const double s[6], double p[2], double d1[3], double d2[3]) {
  // An orthonormal basis (t1, t2) of the tangent plane from F's columns (Gram-Schmidt), the 2x2
  // tensor in it, and its eigen-decomposition in closed form.
  double t1[3] = {F[0], F[2], F[4]}, t2[3] = {F[1], F[3], F[5]};
  const double n1 = std::sqrt(t1[0] * t1[0] + t1[1] * t1[1] + t1[2] * t1[2]);
  for (double &x : t1) x /= n1;
  const double proj = t1[0] * t2[0] + t1[1] * t2[1] + t1[2] * t2[2];
  for (int i = 0; i < 3; ++i) t2[i] -= proj * t1[i];
  const double n2 = std::sqrt(t2[0] * t2[0] + t2[1] * t2[1] + t2[2] * t2[2]);
  for (double &x : t2) x /= n2;
  auto full = [&](int i, int j) {
    static const int idx[3][3] = {{0, 3, 5}, {3, 1, 4}, {5, 4, 2}};
    return s[idx[i][j]];
  };
  auto quad = [&](const double *a, const double *b) {
    double q = 0.0;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) q += a[i] * full(i, j) * b[j];
    return q;
  };
  const double a11 = quad(t1, t1), a22 = quad(t2, t2), a12 = quad(t1, t2);
  const double mean = 0.5 * (a11 + a22), r = std::hypot(0.5 * (a11 - a22), a12);
  p[0] = mean + r;
  p[1] = mean - r;
  // Direction of p[0] in (t1, t2): angle theta with tan(2 theta) = 2 a12 / (a11 - a22).
  const double theta = 0.5 * std::atan2(2.0 * a12, a11 - a22);
  const double c = std::cos(theta), sn = std::sin(theta);
  for (int i = 0; i < 3; ++i) {
    d1[i] = c * t1[i] + sn * t2[i];
    d2[i] = -sn * t1[i] + c * t2[i];
  }
}

} // namespace etfe
