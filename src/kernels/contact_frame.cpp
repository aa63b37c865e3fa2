// Contact pair frame on a cylindrical support and the rotations between the pair's local frame
// and the global axes (formulas in the header). Kept apart from the laws because the frame is
// geometry: the follow frame recomputes it at every iterate, the frozen one once per pair.
#include "etfe/kernels/contact_frame.h"
#include "etfe/kernels/vec3.h"

#include <cmath>

namespace etfe {

namespace {

void Normalize(double v[3]) {
  const double n = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  if (n > 0) v[0] /= n, v[1] /= n, v[2] /= n;
}

} // namespace

double ContactSupportFrame(const double centre[3], const double axis[3], double radius,
                           const double p[3], double M[3], double R[9]) {
  double a[3] = {axis[0], axis[1], axis[2]}, d[3], n[3], x0[3], y0[3];
  Normalize(a);
  for (int i = 0; i < 3; ++i) d[i] = p[i] - centre[i];
  const double along = d[0] * a[0] + d[1] * a[1] + d[2] * a[2];
  for (int i = 0; i < 3; ++i) n[i] = d[i] - along * a[i];
  const double r = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  Normalize(n);
  for (int i = 0; i < 3; ++i) M[i] = centre[i] + along * a[i] + radius * n[i];
  Cross(a, n, x0);
  Cross(n, x0, y0);
  for (int i = 0; i < 3; ++i) R[i] = x0[i], R[3 + i] = y0[i], R[6 + i] = n[i];
  return r - radius;
}

double ContactPlaneFrame(const double point[3], const double normal[3], const double p[3], double M[3], double R[9]) {
  double n[3] = {normal[0], normal[1], normal[2]}, x0[3], y0[3];
  Normalize(n);
  int least = 0;
  for (int i = 1; i < 3; ++i)
    if (std::fabs(n[i]) < std::fabs(n[least])) least = i;
  const double e[3] = {least == 0 ? 1.0 : 0.0, least == 1 ? 1.0 : 0.0, least == 2 ? 1.0 : 0.0};
  Cross(n, e, x0);
  Normalize(x0);
  Cross(n, x0, y0);
  const double d = (p[0] - point[0]) * n[0] + (p[1] - point[1]) * n[1] + (p[2] - point[2]) * n[2];
  for (int i = 0; i < 3; ++i) M[i] = p[i] - d * n[i], R[i] = x0[i], R[3 + i] = y0[i], R[6 + i] = n[i];
  return d;
}

void ContactToLocal(const double R[9], const double v[3], double out[3]) {
  for (int i = 0; i < 3; ++i) out[i] = R[3 * i] * v[0] + R[3 * i + 1] * v[1] + R[3 * i + 2] * v[2];
}

void ContactToGlobal(const double R[9], const double v[3], double out[3]) {
  for (int i = 0; i < 3; ++i) out[i] = R[i] * v[0] + R[3 + i] * v[1] + R[6 + i] * v[2];
}

void ContactRotateTangent(const double R[9], const double K[9], double Kg[9]) {
  double KR[9];
  for (int a = 0; a < 3; ++a)
    for (int j = 0; j < 3; ++j)
      KR[3 * a + j] = K[3 * a] * R[j] + K[3 * a + 1] * R[3 + j] + K[3 * a + 2] * R[6 + j];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      Kg[3 * i + j] = R[i] * KR[j] + R[3 + i] * KR[3 + j] + R[6 + i] * KR[6 + j];
}

} // namespace etfe
