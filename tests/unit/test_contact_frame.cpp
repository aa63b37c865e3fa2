// Contact pair frame (src/kernels/contact_frame.cpp) against closed forms, on the two supports
// the scenes use, a cylinder (capstan pipe: axis y through the origin) and an arch (saddle:
// axis x, centre below the crown), and on skew axes of any length:
//  * R is orthonormal and right-handed (R R^T = I, det R = +1);
//  * z0 is the radial direction of the point, y0 the unit axis, x0 = y0 x z0 the circumferential
//    direction; the distance is |radial| - r; M lies on the surface on the point's radial line;
//  * R^T (R v) = v, and the tangent rotation is R^T K R (checked on vectors: Kg R^T v = R^T K v);
//  * the follow frame's carry of the committed force into a new frame (R_new R_old^T f) keeps
//    its magnitude and gives the projections of the global force on the new axes; for a slide
//    around the axis by an angle t it is the plane rotation by t of (f_x, f_z), f_y unchanged;
//  * finite differences: grad distance = z0, dM/dp = a a^T + (r/rho) (I - a a^T - n n^T),
//    dn/dp = (I - a a^T - n n^T) / rho (rho the radial distance). The follow frame's Jacobian
//    leaves out dR/dp (see test_jacobian_fd.py); dn/dp is the term it leaves out.
#include "etfe/kernels/contact_frame.h"

#include "check.h"
#include "fd_tangent.h"

#include <cmath>
#include <cstdlib>

namespace {

struct Support {
  const char *name;
  double c[3], a[3], r;
};

double Dot(const double *u, const double *v) { return u[0] * v[0] + u[1] * v[1] + u[2] * v[2]; }

double Uniform(unsigned *s, double lo, double hi) {
  *s = *s * 1664525u + 1013904223u;  // a fixed LCG: the same points on every machine
  return lo + (hi - lo) * ((*s >> 8) / double(1u << 24));
}

// Radial unit vector n, radial distance rho and unit axis of p (independent of the kernel).
void Radial(const Support &s, const double p[3], double n[3], double *rho, double a[3]) {
  const double la = std::sqrt(Dot(s.a, s.a));
  for (int i = 0; i < 3; ++i) a[i] = s.a[i] / la;
  double d[3];
  for (int i = 0; i < 3; ++i) d[i] = p[i] - s.c[i];
  const double t = Dot(d, a);
  for (int i = 0; i < 3; ++i) n[i] = d[i] - t * a[i];
  *rho = std::sqrt(Dot(n, n));
  for (int i = 0; i < 3; ++i) n[i] /= *rho;
}

void CheckFrame(const Support &s, const double p[3]) {
  double M[3], R[9], n[3], a[3], rho;
  const double dist = etfe::ContactSupportFrame(s.c, s.a, s.r, p, M, R);
  Radial(s, p, n, &rho, a);
  const double *x0 = R, *y0 = R + 3, *z0 = R + 6;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      CHECK(std::fabs(Dot(R + 3 * i, R + 3 * j) - (i == j)) < 1e-14, "%s: R R^T [%d][%d]", s.name, i, j);
  const double det = x0[0] * (y0[1] * z0[2] - y0[2] * z0[1]) - x0[1] * (y0[0] * z0[2] - y0[2] * z0[0]) +
                     x0[2] * (y0[0] * z0[1] - y0[1] * z0[0]);
  CHECK_CLOSE(det, 1.0, 0.0, 1e-14);
  for (int i = 0; i < 3; ++i) {
    CHECK_CLOSE(z0[i], n[i], 0.0, 1e-14);  // the normal is the radial direction
    CHECK_CLOSE(y0[i], a[i], 0.0, 1e-14);
    CHECK_CLOSE(x0[i], a[(i + 1) % 3] * n[(i + 2) % 3] - a[(i + 2) % 3] * n[(i + 1) % 3], 0.0, 1e-14);
  }
  CHECK_CLOSE(dist, rho - s.r, 0.0, 1e-12 * s.r);
  double Mn[3], Mrho, Ma[3], pm[3];
  Radial(s, M, Mn, &Mrho, Ma);
  CHECK_CLOSE(Mrho, s.r, 0.0, 1e-12 * s.r);  // M on the surface
  for (int i = 0; i < 3; ++i) pm[i] = p[i] - M[i];
  for (int i = 0; i < 3; ++i) CHECK_CLOSE(pm[i], dist * n[i], 0.0, 1e-12 * s.r);  // on p's radial line

  // Rotations: round trip, and the tangent rotation against its definition on vectors.
  unsigned seed = 7;
  double v[3], K[9], vl[3], vg[3], Kg[9], Kv[3], RtKv[3], Rtv[3], KgRtv[3];
  for (int i = 0; i < 3; ++i) v[i] = Uniform(&seed, -1, 1);
  for (int i = 0; i < 9; ++i) K[i] = Uniform(&seed, -1, 1);  // non-symmetric, like slip
  etfe::ContactToLocal(R, v, vl);
  etfe::ContactToGlobal(R, vl, vg);
  for (int i = 0; i < 3; ++i) CHECK_CLOSE(vg[i], v[i], 0.0, 1e-15);
  for (int i = 0; i < 3; ++i) CHECK_CLOSE(vl[i], Dot(R + 3 * i, v), 0.0, 1e-15);
  etfe::ContactRotateTangent(R, K, Kg);
  for (int i = 0; i < 3; ++i) Kv[i] = Dot(K + 3 * i, v);
  etfe::ContactToGlobal(R, Kv, RtKv);
  etfe::ContactToGlobal(R, v, Rtv);
  for (int i = 0; i < 3; ++i) KgRtv[i] = Dot(Kg + 3 * i, Rtv);
  for (int i = 0; i < 3; ++i) CHECK_CLOSE(KgRtv[i], RtKv[i], 0.0, 1e-14);

  // Finite differences (central, h relative to the radius).
  const double h = 1e-6 * s.r;
  double P[9];  // I - a a^T - n n^T: projector on the circumferential direction
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) P[3 * i + j] = (i == j) - a[i] * a[j] - n[i] * n[j];
  // Differentiated: (distance, M, normal = third row of R) at p; J is 7 x 3.
  const auto frame = [&](const double *q, double *out) {
    double R[9];
    out[0] = etfe::ContactSupportFrame(s.c, s.a, s.r, q, out + 1, R);
    for (int i = 0; i < 3; ++i) out[4 + i] = R[6 + i];
  };
  double J[21];
  etfe_test::CentralDifferenceJacobian(frame, p, 3, 7, h, J);
  double worst_d = 0, worst_M = 0, worst_n = 0;
  for (int j = 0; j < 3; ++j) {
    worst_d = std::fmax(worst_d, std::fabs(J[j] - n[j]));
    for (int i = 0; i < 3; ++i) {
      const double dM = a[i] * a[j] + s.r / rho * P[3 * i + j];
      const double dn = P[3 * i + j] / rho;
      worst_M = std::fmax(worst_M, std::fabs(J[3 * (1 + i) + j] - dM));
      worst_n = std::fmax(worst_n, std::fabs(J[3 * (4 + i) + j] - dn) * rho);
    }
  }
  CHECK(worst_d < 1e-7, "%s: d distance/dp vs z0: %.3e", s.name, worst_d);
  CHECK(worst_M < 1e-7, "%s: dM/dp vs closed form: %.3e", s.name, worst_M);
  CHECK(worst_n < 1e-7, "%s: rho dn/dp vs closed form: %.3e", s.name, worst_n);
}

// Follow frame: the committed force, global, read in the frame at a point slid around the axis.
void CheckCarry(const Support &s, const double p[3], double t) {
  double M[3], R0[9], R1[9], n[3], a[3], rho;
  etfe::ContactSupportFrame(s.c, s.a, s.r, p, M, R0);
  Radial(s, p, n, &rho, a);
  // p rotated about the axis by t (Rodrigues; d has no axial part after removing it).
  double d[3], q[3], axn[3] = {a[1] * n[2] - a[2] * n[1], a[2] * n[0] - a[0] * n[2], a[0] * n[1] - a[1] * n[0]};
  for (int i = 0; i < 3; ++i) d[i] = p[i] - s.c[i];
  const double along = Dot(d, a);
  for (int i = 0; i < 3; ++i)
    q[i] = s.c[i] + along * a[i] + rho * (std::cos(t) * n[i] + std::sin(t) * axn[i]);
  etfe::ContactSupportFrame(s.c, s.a, s.r, q, M, R1);
  const double fl[3] = {3.0, -1.5, -40.0};  // stick/slip-like: tangential force, compression
  double fg[3], f1[3];
  etfe::ContactToGlobal(R0, fl, fg);
  etfe::ContactToLocal(R1, fg, f1);
  CHECK_CLOSE(std::sqrt(Dot(f1, f1)), std::sqrt(Dot(fl, fl)), 1e-14, 0.0);
  for (int i = 0; i < 3; ++i) CHECK_CLOSE(f1[i], Dot(R1 + 3 * i, fg), 0.0, 1e-13);
  // Around the axis by t: n1 = c n + s x0 and x1 = a x n1 = c x0 - s n, y0 unchanged, so the
  // local (f_x, f_z) turn by the plane rotation of angle t and f_y stays.
  const double c = std::cos(t), sn = std::sin(t);
  CHECK_CLOSE(f1[1], fl[1], 0.0, 1e-13);
  CHECK_CLOSE(f1[0], c * fl[0] - sn * fl[2], 0.0, 1e-12);
  CHECK_CLOSE(f1[2], sn * fl[0] + c * fl[2], 0.0, 1e-12);
}

} // namespace

int main() {
  const double rise = 1200.0, arch_r = 3000.0;
  const Support supports[] = {
      {"capstan pipe", {0, 0, 0}, {0, 1, 0}, 21.35},
      {"saddle arch", {1000, 0, rise - arch_r}, {1, 0, 0}, arch_r},
      {"skew cylinder", {1.5, -2.0, 0.25}, {0.3, -2.0, 0.7}, 5.0},  // axis not of unit length
  };
  unsigned seed = 12345;
  for (const Support &s : supports)
    for (int k = 0; k < 20; ++k) {
      double p[3];
      // points near the surface (contact candidates) and a few far from it
      const double scale = k < 15 ? 0.01 : 0.5;
      double n[3] = {Uniform(&seed, -1, 1), Uniform(&seed, -1, 1), Uniform(&seed, -1, 1)};
      for (int i = 0; i < 3; ++i) p[i] = s.c[i] + s.r * (1 + scale * Uniform(&seed, -1, 1)) * n[i];
      double rn[3], rho, a[3];
      Radial(s, p, rn, &rho, a);
      if (rho < 0.1 * s.r) continue;  // too near the axis for a meaningful frame
      CheckFrame(s, p);
      CheckCarry(s, p, 0.0);
      CheckCarry(s, p, 0.05);
      CheckCarry(s, p, -1.2);
    }
  {  // a plane support: foot point, signed distance, orthonormal right-handed frame with z0 = n
    const double point[3] = {10, -5, 2}, normal[3] = {0.0, 3.0, 4.0};  // |n| = 5
    const double p[3] = {7, 4, 9}, n[3] = {0.0, 0.6, 0.8};
    double M[9], R[9];
    const double d = etfe::ContactPlaneFrame(point, normal, p, M, R);
    CHECK_CLOSE(d, (p[1] - point[1]) * 0.6 + (p[2] - point[2]) * 0.8, 1e-14, 0.0);
    for (int i = 0; i < 3; ++i) {
      CHECK_CLOSE(M[i], p[i] - d * n[i], 0.0, 1e-12);
      CHECK_CLOSE(R[6 + i], n[i], 0.0, 1e-15);
    }
    CHECK_CLOSE((M[0] - point[0]) * n[0] + (M[1] - point[1]) * n[1] + (M[2] - point[2]) * n[2], 0.0, 0.0, 1e-12);
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) CHECK_CLOSE(Dot(&R[3 * a], &R[3 * b]), a == b ? 1.0 : 0.0, 0.0, 1e-15);
    const double det = R[0] * (R[4] * R[8] - R[5] * R[7]) - R[1] * (R[3] * R[8] - R[5] * R[6]) +
                       R[2] * (R[3] * R[7] - R[4] * R[6]);
    CHECK_CLOSE(det, 1.0, 0.0, 1e-14);
  }
  TEST_MAIN_END();
}
