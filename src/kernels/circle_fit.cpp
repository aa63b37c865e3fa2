// Circle fit (see circle_fit.h).
#include "etfe/kernels/circle_fit.h"

#include <cmath>

namespace etfe {

namespace {

// Eigenvectors of a symmetric 3x3 matrix by Jacobi rotations: columns of V, eigenvalues in w.
void SymmetricEigen3(double A[9], double V[9], double w[3]) {
  for (int i = 0; i < 9; ++i) V[i] = (i % 4 == 0) ? 1.0 : 0.0;
  for (int sweep = 0; sweep < 50; ++sweep) {
    const double off = A[1] * A[1] + A[2] * A[2] + A[5] * A[5];
    if (off < 1e-300) break;
    for (int p = 0; p < 2; ++p)
      for (int q = p + 1; q < 3; ++q) {
        const double apq = A[3 * p + q];
        if (std::fabs(apq) < 1e-300) continue;
        const double theta = 0.5 * (A[3 * q + q] - A[3 * p + p]) / apq;
        const double t = (theta >= 0 ? 1.0 : -1.0) / (std::fabs(theta) + std::sqrt(theta * theta + 1.0));
        const double c = 1.0 / std::sqrt(t * t + 1.0), s = t * c;
        for (int k = 0; k < 3; ++k) {  // A <- A J
          const double akp = A[3 * k + p], akq = A[3 * k + q];
          A[3 * k + p] = c * akp - s * akq, A[3 * k + q] = s * akp + c * akq;
        }
        for (int k = 0; k < 3; ++k) {  // A <- J^T A
          const double apk = A[3 * p + k], aqk = A[3 * q + k];
          A[3 * p + k] = c * apk - s * aqk, A[3 * q + k] = s * apk + c * aqk;
        }
        for (int k = 0; k < 3; ++k) {
          const double vkp = V[3 * k + p], vkq = V[3 * k + q];
          V[3 * k + p] = c * vkp - s * vkq, V[3 * k + q] = s * vkp + c * vkq;
        }
      }
  }
  for (int i = 0; i < 3; ++i) w[i] = A[4 * i];
}

bool Solve3(const double M[9], const double b[3], double x[3]) {
  const double det = M[0] * (M[4] * M[8] - M[5] * M[7]) - M[1] * (M[3] * M[8] - M[5] * M[6]) +
                     M[2] * (M[3] * M[7] - M[4] * M[6]);
  const double scale = std::fabs(M[0] * M[4] * M[8]) + 1e-300;
  if (std::fabs(det) < 1e-14 * scale) return false;
  for (int c = 0; c < 3; ++c) {
    double Mc[9];
    for (int i = 0; i < 9; ++i) Mc[i] = M[i];
    for (int r = 0; r < 3; ++r) Mc[3 * r + c] = b[r];
    x[c] = (Mc[0] * (Mc[4] * Mc[8] - Mc[5] * Mc[7]) - Mc[1] * (Mc[3] * Mc[8] - Mc[5] * Mc[6]) +
            Mc[2] * (Mc[3] * Mc[7] - Mc[4] * Mc[6])) / det;
  }
  return true;
}

// Mean and covariance eigenvectors (columns of V) with their eigenvalues w.
void Spread(const double *pts, int n, double mean[3], double V[9], double w[3]) {
  double C[9] = {0};
  for (int i = 0; i < 3; ++i) mean[i] = 0.0;
  for (int k = 0; k < n; ++k)
    for (int i = 0; i < 3; ++i) mean[i] += pts[3 * k + i] / n;
  for (int k = 0; k < n; ++k)
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) C[3 * i + j] += (pts[3 * k + i] - mean[i]) * (pts[3 * k + j] - mean[j]);
  SymmetricEigen3(C, V, w);
}

} // namespace

bool LongAxis(const double *pts, int n, double axis[3]) {
  if (n < 2) return false;
  double mean[3], V[9], w[3];
  Spread(pts, n, mean, V, w);
  int hi = 0;
  for (int i = 1; i < 3; ++i)
    if (w[i] > w[hi]) hi = i;
  int big = 0;
  for (int i = 0; i < 3; ++i) {
    axis[i] = V[3 * i + hi];
    if (std::fabs(axis[i]) > std::fabs(axis[big])) big = i;
  }
  if (axis[big] < 0)
    for (int i = 0; i < 3; ++i) axis[i] = -axis[i];
  return true;
}

bool FitCircle(const double *pts, int n, CircleFit *fit) {
  if (n < 3) return false;
  double mean[3], V[9], w[3];
  Spread(pts, n, mean, V, w);
  int lo = 0, hi = 0;
  for (int i = 1; i < 3; ++i) {
    if (w[i] < w[lo]) lo = i;
    if (w[i] > w[hi]) hi = i;
  }
  if (lo == hi) return false;
  const int mid = 3 - lo - hi;
  const double nrm[3] = {V[lo], V[3 + lo], V[6 + lo]}, e1[3] = {V[hi], V[3 + hi], V[6 + hi]},
               e2[3] = {V[mid], V[3 + mid], V[6 + mid]};
  // x^2 + y^2 = 2 a x + 2 b y + c in the plane's coordinates (x, y) about the mean.
  double M[9] = {0}, rhs[3] = {0, 0, 0}, sol[3];
  for (int k = 0; k < n; ++k) {
    double d[3], x = 0, y = 0;
    for (int i = 0; i < 3; ++i) d[i] = pts[3 * k + i] - mean[i];
    for (int i = 0; i < 3; ++i) x += d[i] * e1[i], y += d[i] * e2[i];
    const double row[3] = {2 * x, 2 * y, 1.0}, r = x * x + y * y;
    for (int i = 0; i < 3; ++i) {
      rhs[i] += row[i] * r;
      for (int j = 0; j < 3; ++j) M[3 * i + j] += row[i] * row[j];
    }
  }
  if (!Solve3(M, rhs, sol)) return false;
  const double r2 = sol[2] + sol[0] * sol[0] + sol[1] * sol[1];
  if (!(r2 > 0)) return false;
  CircleFit f;
  f.radius = std::sqrt(r2);
  for (int i = 0; i < 3; ++i) f.centre[i] = mean[i] + sol[0] * e1[i] + sol[1] * e2[i], f.axis[i] = nrm[i];
  f.max_deviation = 0.0;
  for (int k = 0; k < n; ++k) {
    double d[3], along = 0;
    for (int i = 0; i < 3; ++i) d[i] = pts[3 * k + i] - f.centre[i], along += d[i] * f.axis[i];
    double radial2 = 0;
    for (int i = 0; i < 3; ++i) radial2 += (d[i] - along * f.axis[i]) * (d[i] - along * f.axis[i]);
    f.max_deviation = std::fmax(f.max_deviation, std::hypot(std::sqrt(radial2) - f.radius, along));
  }
  *fit = f;
  return true;
}

} // namespace etfe
