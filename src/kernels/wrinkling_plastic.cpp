// Tension-field membrane with the ETFE elasto-plastic law: the formulation is in
// include/etfe/kernels/wrinkling_plastic.h. Pure arithmetic, no allocation.
#include "etfe/kernels/wrinkling_plastic.h"

#include <cmath>

#include "etfe/kernels/elastic.h"
#include "etfe/kernels/status.h"

namespace etfe {

namespace {

constexpr int kMaxUniaxialIterations = 60;

double MinorPrincipal(const double S[3]) {
  const double m = 0.5 * (S[0] + S[1]), d = 0.5 * (S[0] - S[1]);
  return m - std::sqrt(d * d + S[2] * S[2]);
}

// No stress, the committed history and the elastic tangent.
void Unstressed(const PlasticMaterial &m, const PlasticState &c, PlasticState *trial, double S[3], double D[9]) {
  *trial = c;
  S[0] = S[1] = S[2] = 0.0;
  ElasticPlaneStressTangent(m.young, m.nu, D);
}

// The uniaxial return along the wrinkle direction: the plastic strain dl with
// f(dl) = Y (e1 - dl) - Sy(ep_n + dl) = 0, and *H the hardening slope there; dl = 0 and *plastic
// false when Y e1 is inside the yield stress. f decreases (slope -(Y + H) < 0) and Sy is piecewise
// linear, so Newton is exact on each segment. False when it does not converge.
bool UniaxialReturn(const PlasticMaterial &m, double ep_n, double e1, double *dl_out, double *H_out, bool *plastic) {
  const double Y = m.young;
  double H;
  double dl = 0.0;
  double sy = PlasticYieldStress(m, ep_n, &H);
  *plastic = Y * e1 > sy * (1.0 + 1e-10);
  if (*plastic) {
    bool converged = false;
    for (int it = 0; it < kMaxUniaxialIterations; ++it) {
      sy = PlasticYieldStress(m, ep_n + dl, &H);
      const double f = Y * (e1 - dl) - sy;
      if (std::fabs(f) <= 1e-13 * sy) {
        converged = true;
        break;
      }
      dl += f / (Y + H);
      if (dl < 0.0) dl = 0.0;
    }
    if (!converged || !std::isfinite(dl)) return false;
  }
  *dl_out = dl;
  *H_out = H;
  return true;
}

} // namespace

int TensionFieldPlastic(const PlasticMaterial &m, const double E[3], const PlasticState &committed,
                        PlasticState *trial, double S[3], double D[9], WrinkleInfo *info) {
  WrinkleInfo local;
  if (!info) info = &local;
  const PlasticState c = committed;  // trial may alias committed
  const double Ee[3] = {E[0] - c.ep[0], E[1] - c.ep[1], E[2] - c.ep[2]};
  const double md = 0.5 * (Ee[0] + Ee[1]), dd = 0.5 * (Ee[0] - Ee[1]), g = 0.5 * Ee[2];
  const double r = std::sqrt(dd * dd + g * g);
  const double e1 = md + r, e2 = md - r;
  info->dir[0] = info->dir[1] = 0.0;
  info->strain = 0.0;
  if (!(std::isfinite(e1) && std::isfinite(e2))) {
    info->state = WRINKLE_TAUT;
    return PlasticReturnMap(m, E, c, trial, S, D);
  }

  // Taut when the plane-stress return map leaves no compression (the common case first).
  if (e2 + m.nu * e1 >= -kTautStrainTolerance) {
    info->state = WRINKLE_TAUT;
    return PlasticReturnMap(m, E, c, trial, S, D);
  }
  if (e1 > 0.0) {
    PlasticState t;
    double St[3], Dt[9];
    const int st = PlasticReturnMap(m, E, c, &t, St, Dt);
    if (st == KERNEL_OK && MinorPrincipal(St) >= -m.young * kTautStrainTolerance) {
      info->state = WRINKLE_TAUT;
      *trial = t;
      for (int i = 0; i < 3; ++i) S[i] = St[i];
      for (int i = 0; i < 9; ++i) D[i] = Dt[i];
      return KERNEL_OK;
    }
  } else {
    info->state = WRINKLE_SLACK;
    info->strain = -e2;
    Unstressed(m, c, trial, S, D);
    for (int k = 0; k < 9; ++k) D[k] *= kSlackTangentFraction;
    return KERNEL_OK;
  }

  // Wrinkled: uniaxial return along n.
  const double th = 0.5 * std::atan2(g, dd);
  const double cs = std::cos(th), sn = std::sin(th);
  const double Y = m.young;
  double H, dl;
  bool plastic;
  if (!UniaxialReturn(m, c.ep_bar, e1, &dl, &H, &plastic)) {
    Unstressed(m, c, trial, S, D);
    return KERNEL_NO_CONVERGENCE;
  }
  const double s = Y * (e1 - dl);
  const double Et = plastic ? Y * H / (Y + H) : Y;
  const double N[3] = {cs * cs, sn * sn, cs * sn};
  const double W[3] = {-cs * sn, cs * sn, 0.5 * (cs * cs - sn * sn)};
  const double k = 2.0 * s / (e1 - e2);
  for (int i = 0; i < 3; ++i) {
    S[i] = s * N[i];
    for (int j = 0; j < 3; ++j) D[3 * i + j] = Et * N[i] * N[j] + k * W[i] * W[j];
  }
  // Plastic strain of a uniaxial stress along n: dl (n n - 1/2 m m), engineering shear.
  PlasticState out = c;
  out.ep[0] += dl * (cs * cs - 0.5 * sn * sn);
  out.ep[1] += dl * (sn * sn - 0.5 * cs * cs);
  out.ep[2] += dl * 3.0 * cs * sn;
  out.ep_bar += dl;
  *trial = out;
  info->state = WRINKLE_WRINKLED;
  info->dir[0] = cs;
  info->dir[1] = sn;
  // Lost length across n: the strain there minus the elastic (Poisson) and plastic contraction
  // of the uniaxial state.
  info->strain = -((e2 + 0.5 * dl) + m.nu * s / Y);
  return KERNEL_OK;
}

} // namespace etfe
