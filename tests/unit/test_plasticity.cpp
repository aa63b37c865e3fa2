// Unit tests of the ETFE elasto-plasticity kernel (docs/theory.md §3.2, thesis eqs. 4.13-4.21,
// Table 4.2): the consistent tangent against finite differences of the return map, closed-form
// uniaxial, equibiaxial and pure-shear curves (with increments that straddle the hardening kinks),
// load-unload-reload cycles, non-finite input and material checks. The closed forms below use
// their own hardening routine so that they do not share code with the kernel.
#include "etfe/kernels/plasticity.h"

#include <cmath>
#include <cstdio>
#include <cstring>

#include "check.h"
#include "fd_tangent.h"
#include "etfe/kernels/status.h"

using namespace etfe;

namespace {

PlasticMaterial EtfeMaterial() {  // thesis Table 4.2, nu: docs/theory.md §3
  PlasticMaterial m{};
  m.young = 800.0;
  m.nu = 0.43;
  m.nseg = 2;
  m.yield[0] = 13.28;
  m.yield[1] = 23.04;
  m.H[0] = 80.5;
  m.H[1] = 3.0;
  return m;
}

// Three segments, the last one perfectly plastic.
PlasticMaterial FlatTailMaterial() {
  PlasticMaterial m{};
  m.young = 500.0;
  m.nu = 0.3;
  m.nseg = 3;
  m.yield[0] = 10.0;
  m.yield[1] = 15.0;
  m.yield[2] = 18.0;
  m.H[0] = 100.0;
  m.H[1] = 20.0;
  m.H[2] = 0.0;
  return m;
}

// A soft segment followed by a very stiff one: 1 - 2/3 H dl (= 1/gamma of eq. 4.21) turns
// negative on the second segment after a large step.
PlasticMaterial StiffeningMaterial() {
  PlasticMaterial m{};
  m.young = 800.0;
  m.nu = 0.3;
  m.nseg = 2;
  m.yield[0] = 1.0;
  m.yield[1] = 1.1;
  m.H[0] = 0.1;
  m.H[1] = 1000.0;
  return m;
}

double Mises(const double S[3]) {
  return std::sqrt(S[0] * S[0] + S[1] * S[1] - S[0] * S[1] + 3.0 * S[2] * S[2]);
}

// Independent hardening law for the closed forms: breakpoints and Sy(ep).
double Breakpoint(const PlasticMaterial &m, int k) {
  double ep = 0.0;
  for (int j = 0; j < k; ++j) ep += (m.yield[j + 1] - m.yield[j]) / m.H[j];
  return ep;
}

int SegmentAt(const PlasticMaterial &m, double ep) {
  int k = 0;
  while (k + 1 < m.nseg && ep >= Breakpoint(m, k + 1)) ++k;
  return k;
}

double HardeningRef(const PlasticMaterial &m, double ep) {
  const int k = SegmentAt(m, ep);
  return m.yield[k] + m.H[k] * (ep - Breakpoint(m, k));
}

// Distance of ep to the nearest breakpoint (the tangent jumps there, so FD must stay away).
double KinkDistance(const PlasticMaterial &m, double ep) {
  double d = 1e300;
  for (int k = 1; k < m.nseg; ++k) d = std::fmin(d, std::fabs(ep - Breakpoint(m, k)));
  return d;
}

void ElasticD(const PlasticMaterial &m, double D[9]) {
  const double f = m.young / (1.0 - m.nu * m.nu);
  const double v[9] = {f, f * m.nu, 0, f * m.nu, f, 0, 0, 0, 0.5 * f * (1.0 - m.nu)};
  for (int i = 0; i < 9; ++i) D[i] = v[i];
}

double TrialMises(const PlasticMaterial &m, const double E[3], const PlasticState &c) {
  double D[9];
  ElasticD(m, D);
  const double e[3] = {E[0] - c.ep[0], E[1] - c.ep[1], E[2] - c.ep[2]};
  const double S[3] = {D[0] * e[0] + D[1] * e[1], D[3] * e[0] + D[4] * e[1], D[8] * e[2]};
  return Mises(S);
}

// ||D - D_fd||_F / ||D||_F with central differences of S(E) from the fixed committed state c.
double TangentError(const PlasticMaterial &m, const double E[3], const PlasticState &c, double h,
                    PlasticState *out) {
  PlasticState tr;
  double S[3], D[9];
  int rc = PlasticReturnMap(m, E, c, &tr, S, D);
  CHECK(rc == KERNEL_OK, "return map failed: %d", rc);
  if (out) *out = tr;
  const auto stress = [&](const double *Ex, double *Sx) {
    PlasticState tx;
    double Dx[9];
    const int rcx = PlasticReturnMap(m, Ex, c, &tx, Sx, Dx);
    CHECK(rcx == KERNEL_OK, "return map at E +- h failed: %d", rcx);
  };
  double Dfd[9];
  etfe_test::CentralDifferenceJacobian(stress, E, 3, 3, h, Dfd);
  double num = 0.0, nrm = 0.0;
  for (int j = 0; j < 3; ++j) {
    for (int i = 0; i < 3; ++i) {
      const double fd = Dfd[3 * i + j];
      num += (fd - D[3 * i + j]) * (fd - D[3 * i + j]);
      nrm += D[3 * i + j] * D[3 * i + j];
    }
  }
  return std::sqrt(num / nrm);
}

PlasticState Commit(const PlasticMaterial &m, const double E[3], const PlasticState &c) {
  PlasticState tr;
  double S[3], D[9];
  const int rc = PlasticReturnMap(m, E, c, &tr, S, D);
  CHECK(rc == KERNEL_OK, "return map failed: %d", rc);
  return tr;
}

void TestTangent() {
  const PlasticMaterial m = EtfeMaterial();
  const double h = 1e-7;
  const double kink = Breakpoint(m, 1);
  const PlasticState virgin{};
  PlasticState out;
  double Dfd[9];

  {  // elastic: the tangent must be D itself
    const double E[3] = {0.005, 0.002, 0.003};
    const double err = TangentError(m, E, virgin, h, &out);
    std::printf("tangent elastic:             rel err %.2e\n", err);
    CHECK(err < 1e-6, "elastic tangent error %g", err);
    CHECK(out.ep_bar == 0.0, "elastic step changed ep_bar %g", out.ep_bar);
    PlasticState tr;
    double S[3], D[9];
    PlasticReturnMap(m, E, virgin, &tr, S, D);
    ElasticD(m, Dfd);
    bool same = true;
    for (int i = 0; i < 9; ++i) same = same && D[i] == Dfd[i];
    CHECK(same, "elastic step must return the elastic D exactly");
  }
  {  // first hardening segment from the virgin state
    const double E[3] = {0.05, -0.01, 0.02};
    const double err = TangentError(m, E, virgin, h, &out);
    std::printf("tangent segment 1:           rel err %.2e (ep_bar %.4f)\n", err, out.ep_bar);
    CHECK(err < 1e-6, "segment-1 tangent error %g", err);
    CHECK(out.ep_bar > 1e-3 && out.ep_bar < kink - 1e-3, "not on segment 1: ep_bar %g",
          out.ep_bar);
  }
  PlasticState c2;
  {  // second segment: committed already on it, further loading
    const double E0[3] = {0.25, -0.05, 0.05};
    c2 = Commit(m, E0, virgin);
    CHECK(c2.ep_bar > kink + 1e-3, "committed state not on segment 2: %g", c2.ep_bar);
    const double E[3] = {0.27, -0.04, 0.08};
    const double err = TangentError(m, E, c2, h, &out);
    std::printf("tangent segment 2:           rel err %.2e (ep_bar %.4f -> %.4f)\n", err,
                c2.ep_bar, out.ep_bar);
    CHECK(err < 1e-6, "segment-2 tangent error %g", err);
    CHECK(out.ep_bar > c2.ep_bar, "no plastic flow on segment 2");
  }
  PlasticState c1;
  {  // one increment from segment 1 across the kink into segment 2
    const double E0[3] = {0.04, 0.0, 0.01};
    c1 = Commit(m, E0, virgin);
    CHECK(c1.ep_bar > 1e-3 && c1.ep_bar < kink - 1e-3, "committed not on segment 1: %g",
          c1.ep_bar);
    const double E[3] = {0.22, -0.03, 0.06};
    const double err = TangentError(m, E, c1, h, &out);
    std::printf("tangent across the kink:     rel err %.2e (ep_bar %.4f -> %.4f, kink %.4f)\n",
                err, c1.ep_bar, out.ep_bar, kink);
    CHECK(err < 1e-6, "kink-crossing tangent error %g", err);
    CHECK(out.ep_bar > kink + 1e-3, "step did not cross the kink: %g", out.ep_bar);
  }
  {  // committed plastic state, loading in a different (shear-dominated) direction
    const double E[3] = {0.045, 0.005, 0.04};
    const double err = TangentError(m, E, c1, h, &out);
    std::printf("tangent from plastic state:  rel err %.2e (ep_bar %.4f -> %.4f)\n", err,
                c1.ep_bar, out.ep_bar);
    CHECK(err < 1e-6, "tangent error from committed plastic state %g", err);
    CHECK(out.ep_bar > c1.ep_bar && out.ep_bar < kink - 1e-3, "not a segment-1 plastic step");
  }
  {  // elastic unloading from a committed plastic state returns D
    const double E[3] = {0.035, 0.0, 0.008};
    const double err = TangentError(m, E, c1, h, &out);
    CHECK(err < 1e-6, "unloading tangent error %g", err);
    CHECK(out.ep_bar == c1.ep_bar, "unloading changed ep_bar");
  }
  {  // perfectly plastic tail (H = 0) and a steeply stiffening curve (1/gamma < 0)
    const PlasticMaterial f = FlatTailMaterial();
    const double E[3] = {0.4, 0.1, 0.1};
    double err = TangentError(f, E, virgin, h, &out);
    std::printf("tangent H = 0 segment:       rel err %.2e (segment %d)\n", err,
                SegmentAt(f, out.ep_bar));
    CHECK(err < 1e-6, "H = 0 tangent error %g", err);
    CHECK(SegmentAt(f, out.ep_bar) == 2, "not on the flat segment: ep_bar %g", out.ep_bar);

    const PlasticMaterial s = StiffeningMaterial();
    const double Es[3] = {2.2, 0.0, 0.0};
    err = TangentError(s, Es, virgin, 1e-8, &out);
    double Hs;
    const double sy = PlasticYieldStress(s, out.ep_bar, &Hs);
    const double a = 1.0 - 2.0 / 3.0 * Hs * (1.5 * (out.ep_bar) / sy);
    std::printf("tangent stiffening segment:  rel err %.2e (1 - 2/3 H dl = %.3f)\n", err, a);
    CHECK(err < 1e-6, "stiffening tangent error %g", err);
    CHECK(a < 0.0, "the stiffening case should have 1 - 2/3 H dl < 0 (got %g)", a);
  }
}

// Random committed states and increments, including compression and large steps; FD points too
// close to a kink or to the elastic/plastic switch are skipped (the tangent jumps there).
void TestTangentRandom() {
  unsigned long long s = 12345;
  auto rnd = [&s]() {  // uniform in [-1, 1)
    s = s * 6364136223846793005ULL + 1442695040888963407ULL;
    return (double)(s >> 11) / 4503599627370496.0 - 1.0;
  };
  const PlasticMaterial mats[3] = {EtfeMaterial(), FlatTailMaterial(), StiffeningMaterial()};
  int tested = 0, failed = 0;
  double worst = 0.0;
  for (int mi = 0; mi < 3; ++mi) {
    const PlasticMaterial &m = mats[mi];
    for (int n = 0; n < 400; ++n) {
      const double scale = mi == 2 ? 0.5 : 0.15;
      const double E0[3] = {scale * rnd(), scale * rnd(), scale * rnd()};
      const PlasticState c = Commit(m, E0, PlasticState{});
      const double E[3] = {E0[0] + scale * rnd(), E0[1] + scale * rnd(), E0[2] + scale * rnd()};
      const double sy = HardeningRef(m, c.ep_bar);
      if (std::fabs(TrialMises(m, E, c) - sy) < 1e-4 * sy) continue;
      PlasticState out;
      double S[3], D[9];
      const int rc = PlasticReturnMap(m, E, c, &out, S, D);
      CHECK(rc == KERNEL_OK, "random return map failed: %d", rc);
      CHECK(Mises(S) <= HardeningRef(m, out.ep_bar) * (1.0 + 1e-10), "outside the yield surface");
      if (KinkDistance(m, out.ep_bar) < 1e-4) continue;
      const double err = TangentError(m, E, c, 1e-7, nullptr);
      ++tested;
      if (err > worst) worst = err;
      if (!(err < 1e-6)) ++failed;
    }
  }
  std::printf("tangent random: %d states, worst rel err %.2e\n", tested, worst);
  CHECK(failed == 0, "%d random tangents off", failed);
  CHECK(tested > 800, "too few random states tested: %d", tested);
}

void TestYieldStress() {
  const PlasticMaterial m = EtfeMaterial();
  const double kink = (23.04 - 13.28) / 80.5;
  double H;
  CHECK_CLOSE(PlasticYieldStress(m, 0.0, &H), 13.28, 1e-15, 0.0);
  CHECK(H == 80.5, "slope at 0: %g", H);
  CHECK_CLOSE(PlasticYieldStress(m, 0.5 * kink, &H), 0.5 * (13.28 + 23.04), 1e-14, 0.0);
  CHECK_CLOSE(PlasticYieldStress(m, kink, &H), 23.04, 1e-14, 0.0);
  CHECK(H == 3.0, "slope at the kink must be the next segment's: %g", H);
  CHECK_CLOSE(PlasticYieldStress(m, kink + 1.0, &H), 26.04, 1e-14, 0.0);
  CHECK(PlasticYieldStress(m, 0.01, nullptr) > 13.28, "slope pointer may be null");
  CHECK_CLOSE(PlasticYieldStress(m, -1.0, &H), 13.28, 0.0, 0.0);
}

// ---- uniaxial stress -----------------------------------------------------------------------

struct MaterialPoint {
  PlasticState st{};
  double E[3] = {0.0, 0.0, 0.0};  // last converged strain (the start of the next Newton)
  double S[3] = {0.0, 0.0, 0.0};
};

// Imposes Exx and solves Syy = Sxy = 0 for (Eyy, 2Exy) with the consistent tangent, then commits.
bool UniaxialStep(const PlasticMaterial &m, MaterialPoint *p, double exx, int *iters) {
  double E[3] = {exx, p->E[1] - m.nu * (exx - p->E[0]), p->E[2]};
  for (int it = 0; it < 50; ++it) {
    PlasticState tr;
    double S[3], D[9];
    if (PlasticReturnMap(m, E, p->st, &tr, S, D) != KERNEL_OK) return false;
    if (std::fabs(S[1]) + std::fabs(S[2]) <= 1e-13 * m.yield[0]) {
      p->st = tr;
      for (int i = 0; i < 3; ++i) p->E[i] = E[i], p->S[i] = S[i];
      if (iters) *iters = it;
      return true;
    }
    const double a = D[4], b = D[5], c = D[7], d = D[8];
    const double det = a * d - b * c;
    E[1] -= (d * S[1] - b * S[2]) / det;
    E[2] -= (a * S[2] - c * S[1]) / det;
  }
  return false;
}

// docs/theory.md §3.2: slope E to yield[0], then E H_k/(E+H_k) on segment k (monotone loading).
double UniaxialMonotone(const PlasticMaterial &m, double exx) {
  const double E = m.young;
  if (exx <= m.yield[0] / E) return E * exx;
  int k = 0;
  while (k + 1 < m.nseg && exx >= m.yield[k + 1] / E + Breakpoint(m, k + 1)) ++k;
  const double start = m.yield[k] / E + Breakpoint(m, k);
  return m.yield[k] + E * m.H[k] / (E + m.H[k]) * (exx - start);
}

// Closed form with history: ep is the axial plastic strain (= ep_bar in uniaxial stress). Elastic
// with slope E while below the current yield stress, else back on the monotone curve.
double UniaxialClosedForm(const PlasticMaterial &m, double exx, double *ep) {
  const double s_el = m.young * (exx - *ep);
  if (s_el <= HardeningRef(m, *ep)) return s_el;
  const double s = UniaxialMonotone(m, exx);
  *ep = exx - s / m.young;
  return s;
}

struct UniaxialRun {
  const PlasticMaterial *m;
  MaterialPoint p;
  double ep_cf = 0.0;  // closed-form plastic strain
  double worst = 0.0;  // worst relative stress error
  int max_iters = 0;
  bool ok = true;
  bool print = false;
  const char *phase = "";

  void Step(double exx, bool row = false) {
    int it = 0;
    if (!UniaxialStep(*m, &p, exx, &it)) {
      ok = false;
      CHECK(false, "uniaxial driver did not converge at Exx = %g", exx);
      return;
    }
    if (it > max_iters) max_iters = it;
    const double cf = UniaxialClosedForm(*m, exx, &ep_cf);
    const double err = std::fabs(p.S[0] - cf) / m->yield[0];
    if (err > worst) worst = err;
    CHECK(std::fabs(p.S[0] - cf) <= 1e-8 * std::fmax(std::fabs(cf), m->yield[0]),
          "uniaxial Sxx(Exx = %.6f) = %.15g, closed form %.15g", exx, p.S[0], cf);
    CHECK_CLOSE(p.st.ep_bar, ep_cf, 1e-8, 1e-12);
    CHECK_CLOSE(p.st.ep[0], ep_cf, 1e-8, 1e-12);  // ep_bar is the axial plastic strain
    CHECK_CLOSE(p.st.ep[1], -0.5 * ep_cf, 1e-8, 1e-12);
    if (print && row) {
      std::printf("  %-8s %9.5f %12.6f %12.6f %9.2e %9.5f\n", phase, exx, p.S[0], cf,
                  std::fabs(p.S[0] - cf) / std::fmax(std::fabs(cf), m->yield[0]), p.st.ep_bar);
    }
  }
  // Unload to Sxx = 0 (closed form: Exx = axial plastic strain) and reload to emax and beyond.
  void Cycle(double emax, double ereload, int nsteps) {
    const double e0 = p.E[0];
    const double ep_zero = ep_cf;
    phase = "unload";
    for (int i = 1; i <= nsteps; ++i) Step(e0 + (ep_zero - e0) * i / nsteps, i == nsteps);
    CHECK(std::fabs(p.S[0]) <= 1e-8 * m->yield[0], "Sxx after unloading to the plastic strain: %g",
          p.S[0]);
    CHECK(p.st.ep_bar > 0.0, "no residual plastic strain after yielding");
    phase = "reload";
    for (int i = 1; i <= nsteps; ++i) Step(ep_zero + (emax - ep_zero) * i / nsteps, i == nsteps);
    CHECK_CLOSE(p.st.ep_bar, ep_zero, 1e-12, 0.0);  // elastic up to the previous maximum
    for (int i = 1; i <= nsteps; ++i) Step(emax + (ereload - emax) * i / nsteps, i == nsteps);
  }
};

void TestUniaxial() {
  const PlasticMaterial m = EtfeMaterial();
  const double e_y1 = m.yield[0] / m.young;
  const double e_y2 = m.yield[1] / m.young + Breakpoint(m, 1);
  std::printf("uniaxial kinks: Exx = %.6f (yield 1), %.6f (yield 2)\n", e_y1, e_y2);

  {  // small increments of 0.001 (straddling both kinks), with the table
    UniaxialRun r{&m, {}};
    r.print = true;
    r.phase = "load";
    std::printf("uniaxial stress, ETFE (E = 800, nu = 0.43, Sy = 13.28/23.04, H' = 80.5/3.0):\n");
    std::printf("  %-8s %9s %12s %12s %9s %9s\n", "phase", "Exx", "Sxx", "closed", "rel.err",
                "ep_bar");
    const int rows[] = {5, 10, 16, 17, 25, 50, 75, 100, 125, 150, 151, 175, 200};
    int next = 0;
    for (int i = 1; i <= 200; ++i) {
      const bool row = next < 13 && rows[next] == i;
      if (row) ++next;
      r.Step(0.001 * i, row);
    }
    r.Cycle(0.2, 0.25, 50);
    std::printf("uniaxial small steps: worst |dS|/Sy1 %.2e, max driver iterations %d\n", r.worst,
                r.max_iters);
    CHECK(r.ok, "small-step run failed");
  }
  {  // a few large increments, each straddling a kink, then one-step unload and reload
    const double seqs[4][6] = {{0.2, -1, -1, -1, -1, -1},
                               {0.01, 0.03, 0.14, 0.16, 0.2, -1},
                               {e_y1, e_y2, 0.2, -1, -1, -1},
                               {0.017, 0.151, 0.2, -1, -1, -1}};
    for (int q = 0; q < 4; ++q) {
      UniaxialRun r{&m, {}};
      for (int i = 0; i < 6 && seqs[q][i] > 0; ++i) r.Step(seqs[q][i]);
      r.Cycle(0.2, 0.3, 1);
      std::printf("uniaxial large steps (sequence %d): worst |dS|/Sy1 %.2e, max iterations %d\n",
                  q, r.worst, r.max_iters);
      CHECK(r.ok, "large-step run %d failed", q);
    }
  }
  {  // perfectly plastic tail: the curve flattens at yield[2]
    const PlasticMaterial f = FlatTailMaterial();
    UniaxialRun r{&f, {}};
    for (int i = 1; i <= 40; ++i) r.Step(0.01 * i);
    r.Cycle(0.4, 0.5, 3);
    r.Step(1.0);
    CHECK_CLOSE(r.p.S[0], 18.0, 1e-12, 0.0);
    std::printf("uniaxial flat tail: worst |dS|/Sy1 %.2e, max iterations %d\n", r.worst,
                r.max_iters);
  }
}

// ---- equibiaxial stretch and pure shear -----------------------------------------------------

// Equibiaxial Exx = Eyy = e: S = s(1,1,0), Mises = s, P S = s/3 (1,1,0), so Ep_xx = Ep_yy =
// ep_bar/2 and s = E/(1-nu) (e - ep_bar/2) = Sy(ep_bar). On segment k this is linear in ep_bar.
double EquibiaxialClosedForm(const PlasticMaterial &m, double e, double *ep) {
  const double Eb = m.young / (1.0 - m.nu);
  const double s_el = Eb * (e - 0.5 * *ep);
  if (s_el <= HardeningRef(m, *ep)) return s_el;
  for (int k = m.nseg - 1; k >= 0; --k) {
    const double epk = Breakpoint(m, k);
    const double x = (Eb * e - m.yield[k] + m.H[k] * epk) / (m.H[k] + 0.5 * Eb);
    if (x >= epk || k == 0) {
      *ep = x;
      return Eb * (e - 0.5 * x);
    }
  }
  return 0.0;
}

// Pure shear 2Exy = g, Exx = Eyy = 0: S = (0,0,t), Mises = sqrt3 |t|, P S = (0,0,2t), so
// gamma_p = sqrt3 ep_bar sign(t) and sqrt3 t = sqrt3 G (g - sqrt3 ep_bar) = Sy(ep_bar).
double ShearClosedForm(const PlasticMaterial &m, double g, double *ep) {
  const double G = 0.5 * m.young / (1.0 + m.nu);
  const double r3 = std::sqrt(3.0);
  const double t_el = G * (g - r3 * *ep);
  if (r3 * t_el <= HardeningRef(m, *ep)) return t_el;
  for (int k = m.nseg - 1; k >= 0; --k) {
    const double epk = Breakpoint(m, k);
    const double x = (r3 * G * g - m.yield[k] + m.H[k] * epk) / (m.H[k] + 3.0 * G);
    if (x >= epk || k == 0) {
      *ep = x;
      return G * (g - r3 * x);
    }
  }
  return 0.0;
}

void TestEquibiaxialAndShear() {
  const PlasticMaterial mats[2] = {EtfeMaterial(), FlatTailMaterial()};
  for (int mi = 0; mi < 2; ++mi) {
    const PlasticMaterial &m = mats[mi];
    // Fine steps, then coarse steps that jump over both kinks.
    const double steps[2] = {0.001, 0.037};
    for (int si = 0; si < 2; ++si) {
      PlasticState st{};
      double ep_cf = 0.0, worst = 0.0;
      for (double e = steps[si]; e <= 0.15 + 1e-12; e += steps[si]) {
        const double E[3] = {e, e, 0.0};
        double S[3], D[9];
        CHECK(PlasticReturnMap(m, E, st, &st, S, D) == KERNEL_OK, "equibiaxial failed");
        const double cf = EquibiaxialClosedForm(m, e, &ep_cf);
        CHECK_CLOSE(S[0], cf, 1e-8, 0.0);
        CHECK_CLOSE(S[1], S[0], 1e-12, 0.0);
        CHECK(std::fabs(S[2]) <= 1e-14 * std::fabs(S[0]), "equibiaxial Sxy = %g", S[2]);
        CHECK_CLOSE(st.ep_bar, ep_cf, 1e-8, 1e-14);
        CHECK_CLOSE(st.ep[0], 0.5 * ep_cf, 1e-8, 1e-14);
        worst = std::fmax(worst, std::fabs(S[0] - cf) / cf);
      }
      std::printf("equibiaxial material %d step %.3f: worst rel err %.2e, final ep_bar %.4f "
                  "(segment %d)\n", mi, steps[si], worst, ep_cf, SegmentAt(m, ep_cf));
      CHECK(SegmentAt(m, ep_cf) == m.nseg - 1, "equibiaxial run did not reach the last segment");
    }
    const double gsteps[2] = {0.002, 0.09};
    for (int si = 0; si < 2; ++si) {
      for (int sign = -1; sign <= 1; sign += 2) {
        PlasticState st{};
        double ep_cf = 0.0, worst = 0.0;
        for (double g = gsteps[si]; g <= 0.6 + 1e-12; g += gsteps[si]) {
          const double E[3] = {0.0, 0.0, sign * g};
          double S[3], D[9];
          CHECK(PlasticReturnMap(m, E, st, &st, S, D) == KERNEL_OK, "shear failed");
          const double cf = sign * ShearClosedForm(m, g, &ep_cf);
          CHECK_CLOSE(S[2], cf, 1e-8, 0.0);
          CHECK(std::fabs(S[0]) + std::fabs(S[1]) <= 1e-13 * std::fabs(S[2]), "shear normal S");
          CHECK_CLOSE(Mises(S), std::sqrt(3.0) * std::fabs(S[2]), 1e-14, 0.0);
          CHECK_CLOSE(st.ep_bar, ep_cf, 1e-8, 1e-14);
          CHECK_CLOSE(st.ep[2], sign * std::sqrt(3.0) * ep_cf, 1e-8, 1e-14);
          worst = std::fmax(worst, std::fabs(S[2] - cf) / std::fabs(cf));
        }
        if (sign > 0) {
          std::printf("pure shear material %d step %.3f: worst rel err %.2e, final ep_bar %.4f "
                      "(segment %d)\n", mi, gsteps[si], worst, ep_cf, SegmentAt(m, ep_cf));
        }
        CHECK(SegmentAt(m, ep_cf) == m.nseg - 1, "shear run did not reach the last segment");
      }
    }
  }
}

// ---- cycles, yield surface, bad input --------------------------------------------------------

// Proportional strain path 0 -> Emax -> 0 -> 1.3 Emax in n steps per leg; returns the residual
// plastic state at zero strain and checks the yield surface after every return map.
PlasticState Cycle(const PlasticMaterial &m, const double Emax[3], int n, double *max_mises) {
  PlasticState st{}, at_zero{};
  *max_mises = 0.0;
  const double legs[4] = {0.0, 1.0, 0.0, 1.3};
  for (int l = 0; l < 3; ++l) {
    for (int i = 1; i <= n; ++i) {
      const double t = legs[l] + (legs[l + 1] - legs[l]) * i / n;
      const double E[3] = {t * Emax[0], t * Emax[1], t * Emax[2]};
      double S[3], D[9];
      const int rc = PlasticReturnMap(m, E, st, &st, S, D);
      CHECK(rc == KERNEL_OK, "cycle return map failed: %d", rc);
      const double sy = HardeningRef(m, st.ep_bar);
      CHECK(Mises(S) <= sy * (1.0 + 1e-10), "Mises %.17g above the yield stress %.17g",
            Mises(S), sy);
      *max_mises = std::fmax(*max_mises, Mises(S));
      if (l == 1 && i == n) at_zero = st;
    }
  }
  return at_zero;
}

void TestCycles() {
  const PlasticMaterial m = EtfeMaterial();
  double smax;
  const double Ebig[3] = {0.08, 0.02, 0.06};
  const int nsteps[3] = {1, 3, 40};
  for (int n : nsteps) {
    const PlasticState r = Cycle(m, Ebig, n, &smax);
    CHECK(r.ep_bar > 0.0, "no residual equivalent plastic strain");
    CHECK(std::fabs(r.ep[0]) + std::fabs(r.ep[1]) + std::fabs(r.ep[2]) > 1e-3,
          "no residual plastic strain");
  }
  const double Esmall[3] = {0.008, 0.002, 0.006};
  const PlasticState r = Cycle(m, Esmall, 10, &smax);
  CHECK(smax < m.yield[0], "the small cycle should stay elastic (max Mises %g)", smax);
  CHECK(r.ep_bar == 0.0 && r.ep[0] == 0.0 && r.ep[1] == 0.0 && r.ep[2] == 0.0,
        "residual plastic strain below yield");

  // Large, compressive and mixed single steps: the local Newton must converge onto the surface.
  const double big[5][3] = {{2.0, -1.0, 3.0}, {-0.5, -0.4, 0.0}, {0.0, 0.0, -5.0},
                            {1e-3, 1e-3, 50.0}, {13.28 / 800 * 1.0000001, 0.0, 0.0}};
  for (const auto &E : big) {
    PlasticState st{};
    double S[3], D[9];
    const int rc = PlasticReturnMap(m, E, st, &st, S, D);
    CHECK(rc == KERNEL_OK, "large step failed: %d", rc);
    const double sy = HardeningRef(m, st.ep_bar);
    CHECK_CLOSE(Mises(S), sy, 1e-12, 0.0);
  }
  // Re-evaluating a converged state at its own strain reproduces it.
  {
    const double E[3] = {0.1, 0.03, -0.02};
    PlasticState st{}, again;
    double S[3], S2[3], D[9];
    PlasticReturnMap(m, E, st, &st, S, D);
    PlasticReturnMap(m, E, st, &again, S2, D);
    for (int i = 0; i < 3; ++i) CHECK_CLOSE(S2[i], S[i], 1e-12, 1e-12);
    CHECK_CLOSE(again.ep_bar, st.ep_bar, 1e-12, 0.0);
  }
}

void TestBadInput() {
  const PlasticMaterial m = EtfeMaterial();
  PlasticState st{}, tr;
  double S[3], D[9];
  const double nan = std::nan("");
  const double Enan[3] = {0.01, nan, 0.0};
  CHECK(PlasticReturnMap(m, Enan, st, &tr, S, D) == KERNEL_NONFINITE, "NaN strain");
  const double Einf[3] = {INFINITY, 0.0, 0.0};
  CHECK(PlasticReturnMap(m, Einf, st, &tr, S, D) == KERNEL_NONFINITE, "Inf strain");
  const double Eok[3] = {0.01, 0.0, 0.0};
  PlasticState bad{};
  bad.ep_bar = nan;
  CHECK(PlasticReturnMap(m, Eok, bad, &tr, S, D) == KERNEL_NONFINITE, "NaN history");
  const double Ehuge[3] = {1e300, 0.0, 0.0};
  CHECK(PlasticReturnMap(m, Ehuge, st, &tr, S, D) == KERNEL_NONFINITE, "overflowing strain");
  CHECK(tr.ep_bar == 0.0, "failed return map must leave the history as committed");

  char msg[128];
  CHECK(PlasticMaterialCheck(m, msg, sizeof msg) == 0, "ETFE rejected: %s", msg);
  CHECK(PlasticMaterialCheck(FlatTailMaterial(), msg, sizeof msg) == 0, "flat tail: %s", msg);
  CHECK(PlasticMaterialCheck(m, nullptr, 0) == 0, "null message buffer");
  struct Case {
    const char *what;
    PlasticMaterial m;
  } cases[] = {{"non-increasing yields", m}, {"equal yields", m}, {"negative H", m},
               {"E = 0", m},                 {"E < 0", m},        {"nu = 0.5", m},
               {"nu = -1", m},               {"nseg = 0", m},     {"nseg = 9", m},
               {"inner H = 0", m},           {"yield <= 0", m},   {"NaN E", m}};
  cases[0].m.yield[1] = 10.0;
  cases[1].m.yield[1] = 13.28;
  cases[2].m.H[1] = -1.0;
  cases[3].m.young = 0.0;
  cases[4].m.young = -800.0;
  cases[5].m.nu = 0.5;
  cases[6].m.nu = -1.0;
  cases[7].m.nseg = 0;
  cases[8].m.nseg = kMaxHardeningSegments + 1;
  cases[9].m.H[0] = 0.0;
  cases[10].m.yield[0] = 0.0;
  cases[11].m.young = nan;
  for (const Case &c : cases) {
    msg[0] = '\0';
    const int rc = PlasticMaterialCheck(c.m, msg, sizeof msg);
    CHECK(rc > 0, "%s accepted", c.what);
    CHECK(std::strlen(msg) > 0, "%s: no message", c.what);
    std::printf("  material check, %-22s -> %s\n", c.what, msg);
    CHECK(PlasticMaterialCheck(c.m, nullptr, 0) > 0, "%s accepted without a buffer", c.what);
  }
  char tiny[4];
  CHECK(PlasticMaterialCheck(cases[0].m, tiny, sizeof tiny) > 0 && std::strlen(tiny) < 4,
        "message must be truncated to the buffer");
}

} // namespace

int main() {
  TestYieldStress();
  TestTangent();
  TestTangentRandom();
  TestUniaxial();
  TestEquibiaxialAndShear();
  TestCycles();
  TestBadInput();
  TEST_MAIN_END();
}
