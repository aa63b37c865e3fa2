// Annular membrane under torsion with a tension field: the closed form of
// include/etfe/verification/annulus_closed_form.h (the derivation is there).
#include "etfe/verification/annulus_closed_form.h"

#include <cmath>

namespace etfe {

namespace {

constexpr int kSteps = 2000;       // RK4 steps over the wrinkled zone: error ~1e-12 relative
constexpr int kScanSteps = 100;    // coarser RK4 while bracketing the root in B

struct Zone {
  double A, B, C, K;
};

// Right-hand side of the wrinkled zone: y = (u, w = v/r).
void Rhs(const AnnulusTorsion &p, const Zone &z, double r, const double y[2], double dy[2]) {
  const double F2 = z.K - z.C * z.C / (r * r);
  const double sr = std::sqrt(std::fmax(F2, 0.0)) / r;
  const double tau = z.C / (r * r);
  const double s1 = sr + (sr > 0 ? tau * tau / sr : 0.0);
  const double h = std::hypot(sr, tau);
  const double c = sr / h, s = tau / h;
  const double e1 = s1 / p.young, ur = y[0] / r;
  dy[0] = ((e1 - s * s * ur) * (c * c - s * s) + 2.0 * c * c * s * s * ur) / (c * c);
  dy[1] = 2.0 * s * (e1 - ur) / c / r;
}

// Integrates from R down to a; returns (u(a), w(a)).
void Integrate(const AnnulusTorsion &p, const Zone &z, double R, double y[2], int steps = kSteps) {
  const double G = 0.5 * p.young / (1.0 + p.nu);
  y[0] = ((1 - p.nu) * z.A * R - (1 + p.nu) * z.B / R) / p.young;
  y[1] = z.C / (2 * G) * (1 / (p.b * p.b) - 1 / (R * R));
  const double h = (p.a - R) / steps;
  double r = R;
  for (int k = 0; k < steps; ++k) {
    double k1[2], k2[2], k3[2], k4[2], t[2];
    Rhs(p, z, r, y, k1);
    for (int i = 0; i < 2; ++i) t[i] = y[i] + 0.5 * h * k1[i];
    Rhs(p, z, r + 0.5 * h, t, k2);
    for (int i = 0; i < 2; ++i) t[i] = y[i] + 0.5 * h * k2[i];
    Rhs(p, z, r + 0.5 * h, t, k3);
    for (int i = 0; i < 2; ++i) t[i] = y[i] + h * k3[i];
    Rhs(p, z, r + h, t, k4);
    for (int i = 0; i < 2; ++i) y[i] += h / 6.0 * (k1[i] + 2 * k2[i] + 2 * k3[i] + k4[i]);
    r += h;
  }
}

// The zone for a given B at radius R (A from the outer edge, C from s_2(R) = 0); false when
// C^2 < 0 or the wrinkled zone's radial stress would vanish inside it.
bool ZoneOf(const AnnulusTorsion &p, double R, double B, Zone *z) {
  z->B = B;
  z->A = (p.young * p.eps0 + (1 + p.nu) * B / (p.b * p.b)) / (1 - p.nu);
  const double c2 = z->A * z->A * R * R * R * R - B * B;
  if (!(c2 >= 0.0) || z->A <= 0.0) return false;
  z->C = std::sqrt(c2);
  z->K = 2.0 * z->A * (z->A * R * R + B);
  return z->K - z->C * z->C / (p.a * p.a) > 0.0;
}

bool Valid(const AnnulusTorsion &p) {
  return p.a > 0 && p.b > p.a && p.young > 0 && p.nu > -1 && p.nu < 0.5 && p.eps0 > 0 &&
         std::isfinite(p.a + p.b + p.young + p.nu + p.eps0);
}

} // namespace

double AnnulusOnsetRotation(const AnnulusTorsion &p) {
  const double G = 0.5 * p.young / (1.0 + p.nu);
  const double sigma0 = p.young * p.eps0 / (1 - p.nu);
  return sigma0 * p.a * p.a / (2 * G) * (1 / (p.a * p.a) - 1 / (p.b * p.b));
}

int AnnulusStateAtRadius(const AnnulusTorsion &p, double R, AnnulusTorsionResult *res) {
  if (!Valid(p) || !(R >= p.a && R < p.b)) return 1;
  const double sigma0 = p.young * p.eps0 / (1 - p.nu);
  // g(B) = u(a) - eps0 a over the B for which a zone exists; scan for a sign change, bisect.
  auto g = [&](double B, Zone *z, bool *ok, int steps) {
    *ok = ZoneOf(p, R, B, z);
    if (!*ok) return 0.0;
    double y[2];
    Integrate(p, *z, R, y, steps);
    return y[0] - p.eps0 * p.a;
  };
  // Where a zone exists and the root lies: B within a few sigma0 R^2 (the taut side's s_2(R) = 0
  // bounds |B| <= A R^2).
  const double scale = 4.0 * sigma0 * R * R;
  const int nscan = 200;
  double lo = 0, hi = 0, glo = 0;
  bool found = false, have_prev = false;
  for (int k = 0; k <= nscan && !found; ++k) {
    const double B = scale * (-1.0 + 2.0 * k / nscan);
    Zone z;
    bool ok;
    const double gv = g(B, &z, &ok, kScanSteps);
    if (!ok) {
      have_prev = false;
      continue;
    }
    if (have_prev && (gv == 0.0 || (gv > 0) != (glo > 0))) {
      hi = B;
      found = true;
      break;
    }
    lo = B, glo = gv, have_prev = true;
  }
  if (!found) return 1;
  Zone z;
  bool ok;
  glo = g(lo, &z, &ok, kSteps);
  for (int it = 0; it < 200 && hi - lo > 1e-14 * scale; ++it) {
    const double mid = 0.5 * (lo + hi);
    const double gm = g(mid, &z, &ok, kSteps);
    if (!ok) return 1;
    if ((gm > 0) == (glo > 0)) lo = mid, glo = gm;
    else hi = mid;
  }
  g(0.5 * (lo + hi), &z, &ok, kSteps);
  double y[2];
  Integrate(p, z, R, y);
  res->wrinkle_radius = R;
  res->C = z.C;
  res->phi = -y[1];
  return 0;
}

// The wrinkled state whose field (rotation or torque, both increasing with the wrinkle radius R)
// equals target: R bracketed between a and b, then bisected.
static int RadiusWhere(const AnnulusTorsion &p, double AnnulusTorsionResult::*field, double target,
                       AnnulusTorsionResult *res) {
  double lo = p.a, hi = p.a;
  AnnulusTorsionResult r;
  for (int k = 1; k <= 60; ++k) {
    const double R = p.a + (p.b - p.a) * (1.0 - std::pow(0.5, k * 0.25));
    if (AnnulusStateAtRadius(p, R, &r) != 0) return 2;
    if (r.*field >= target) {
      hi = R;
      break;
    }
    lo = R;
  }
  if (hi == p.a) return 2;
  for (int it = 0; it < 100 && hi - lo > 1e-13 * p.b; ++it) {
    const double mid = 0.5 * (lo + hi);
    if (AnnulusStateAtRadius(p, mid, &r) != 0) return 2;
    if (r.*field < target) lo = mid;
    else hi = mid;
  }
  return AnnulusStateAtRadius(p, 0.5 * (lo + hi), res) == 0 ? 0 : 2;
}

int AnnulusStateAtRotation(const AnnulusTorsion &p, double phi, AnnulusTorsionResult *res) {
  if (!Valid(p) || !(phi >= 0)) return 1;
  const double G = 0.5 * p.young / (1.0 + p.nu);
  const double phi0 = AnnulusOnsetRotation(p);
  if (phi <= phi0) {
    res->wrinkle_radius = p.a;
    res->C = 2 * G * phi * p.a * p.a * p.b * p.b / (p.b * p.b - p.a * p.a);
    res->phi = phi;
    return 0;
  }
  return RadiusWhere(p, &AnnulusTorsionResult::phi, phi, res);
}

int AnnulusStateAtTorque(const AnnulusTorsion &p, double C, AnnulusTorsionResult *res) {
  if (!Valid(p) || !(C >= 0)) return 1;
  const double sigma0 = p.young * p.eps0 / (1 - p.nu);
  if (C <= sigma0 * p.a * p.a) {
    const double G = 0.5 * p.young / (1.0 + p.nu);
    res->wrinkle_radius = p.a;
    res->C = C;
    res->phi = C / (2 * G) * (1 / (p.a * p.a) - 1 / (p.b * p.b));
    return 0;
  }
  return RadiusWhere(p, &AnnulusTorsionResult::C, C, res);
}

} // namespace etfe
