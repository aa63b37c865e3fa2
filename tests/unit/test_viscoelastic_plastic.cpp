// Unit tests of the ETFE viscoelastic-plastic kernel (viscoelastic_plastic.h): the algorithmic tangent
// against finite differences in every state (viscoelastic, on each yield segment, unloading);
// the standard linear solid in relaxation (step and ramp) and in creep against its closed forms;
// no Maxwell branch == the plastic law bit for bit; very short relaxation times == the plastic
// law at the relaxed modulus; the stress as the sum of the branches; the material checks; the
// Biot measures' tangent, and a uniaxial relaxation test against the published model in its own
// measures (engineering strain, nominal stress) in both measures.
#include "etfe/kernels/viscoelastic_plastic.h"

#include <cmath>
#include <cstdio>
#include <cstring>
#include <vector>

#include "check.h"
#include "fd_tangent.h"
#include "etfe/kernels/status.h"

using namespace etfe;

namespace {

ViscoelasticPlasticMaterial EtfeTwoBranches() {  // thesis Table 4.2 hardening, two Maxwell branches
  ViscoelasticPlasticMaterial m{};
  m.plastic.young = 800.0;
  m.plastic.nu = 0.43;
  m.plastic.nseg = 2;
  m.plastic.yield[0] = 13.28;
  m.plastic.yield[1] = 23.04;
  m.plastic.H[0] = 80.5;
  m.plastic.H[1] = 3.0;
  m.nterms = 2;
  m.tau[0] = 10.0, m.tau[1] = 1000.0;
  m.g[0] = 0.2, m.g[1] = 0.15;
  return m;
}

// One Maxwell branch, no yield within reach: the standard linear solid.
ViscoelasticPlasticMaterial StandardLinearSolid() {
  ViscoelasticPlasticMaterial m = EtfeTwoBranches();
  m.plastic.nseg = 1;
  m.plastic.yield[0] = 1e9;
  m.plastic.H[0] = 0.0;
  m.nterms = 1;
  m.tau[0] = 50.0;
  m.g[0] = 0.4;
  return m;
}

struct State {
  std::vector<double> h;
  explicit State(const ViscoelasticPlasticMaterial &m) : h((size_t)ViscoelasticPlasticHistorySize(m.nterms), 0.0) {}
};

// Uniaxial stress along x: with one Poisson's ratio for every branch, E = (e, -nu e, 0) keeps Syy = 0.
void Uniaxial(const ViscoelasticPlasticMaterial &m, double e, double E[3]) {
  E[0] = e, E[1] = -m.plastic.nu * e, E[2] = 0.0;
}

// The tangent at (dt, E, history) against central differences of the stress.
void CheckTangent(const ViscoelasticPlasticMaterial &m, double dt, const double E[3], const State &s, const char *what) {
  double S[3], D[9], Dfd[9], scratch[ViscoelasticPlasticHistorySize(kMaxPronyTerms)];
  CHECK(ViscoelasticPlasticUpdate(m, dt, E, s.h.data(), scratch, S, D) == KERNEL_OK, "%s: update failed", what);
  auto f = [&](const double *x, double *out) {
    double Dx[9], hx[ViscoelasticPlasticHistorySize(kMaxPronyTerms)];
    ViscoelasticPlasticUpdate(m, dt, x, s.h.data(), hx, out, Dx);
  };
  etfe_test::CentralDifferenceJacobian(f, E, 3, 3, 1e-8, Dfd);
  double scale = 0.0;
  for (double d : D) scale = std::fmax(scale, std::fabs(d));
  for (int k = 0; k < 9; ++k)
    CHECK(std::fabs(D[k] - Dfd[k]) <= 2e-6 * scale, "%s: D[%d] = %.10g, FD %.10g", what, k, D[k], Dfd[k]);
}

// Advances the state by one step and returns S.
void Step(const ViscoelasticPlasticMaterial &m, double dt, const double E[3], State *s, double S[3]) {
  double D[9];
  CHECK(ViscoelasticPlasticUpdate(m, dt, E, s->h.data(), s->h.data(), S, D) == KERNEL_OK, "step failed");
}

void TestTangentEveryState(int measure) {
  ViscoelasticPlasticMaterial m = EtfeTwoBranches();
  m.measure = measure;
  State s(m);
  double S[3];
  // Biaxial loading in steps of 5 s, staying elastic: viscoelastic state with internal stresses.
  const double dir[3] = {1.0, 0.6, 0.3};
  for (int k = 1; k <= 4; ++k) {
    const double E[3] = {0.002 * k * dir[0], 0.002 * k * dir[1], 0.002 * k * dir[2]};
    Step(m, 5.0, E, &s, S);
  }
  CHECK(s.h[3] == 0.0 && s.h[7] != 0.0, "still elastic with internal stresses (ep_bar %g, h %g)", s.h[3], s.h[7]);
  const double Eve[3] = {0.0085 * dir[0], 0.0085 * dir[1], 0.0085 * dir[2]};
  CheckTangent(m, 5.0, Eve, s, "viscoelastic");

  // First yield segment: a step just past yield.
  const double Ey1[3] = {0.03 * dir[0], 0.03 * dir[1], 0.03 * dir[2]};
  double scratch[ViscoelasticPlasticHistorySize(kMaxPronyTerms)], D[9];
  ViscoelasticPlasticUpdate(m, 5.0, Ey1, s.h.data(), scratch, S, D);
  const double ep_break = (m.plastic.yield[1] - m.plastic.yield[0]) / m.plastic.H[0];
  CHECK(scratch[3] > 0.0 && scratch[3] < ep_break, "segment 0: ep_bar %g in (0, %g)", scratch[3], ep_break);
  CheckTangent(m, 5.0, Ey1, s, "first yield segment");

  // Second segment: a large step.
  const double Ey2[3] = {0.25 * dir[0], 0.25 * dir[1], 0.25 * dir[2]};
  ViscoelasticPlasticUpdate(m, 5.0, Ey2, s.h.data(), scratch, S, D);
  CHECK(scratch[3] > ep_break, "segment 1: ep_bar %g > %g", scratch[3], ep_break);
  CheckTangent(m, 5.0, Ey2, s, "second yield segment");

  // Unloading from a yielded state: commit the large step, then step back.
  Step(m, 5.0, Ey2, &s, S);
  const double Eun[3] = {0.24 * dir[0], 0.24 * dir[1], 0.24 * dir[2]};
  ViscoelasticPlasticUpdate(m, 5.0, Eun, s.h.data(), scratch, S, D);
  CHECK(scratch[3] == s.h[3], "unloading is elastic (ep_bar %g -> %g)", s.h[3], scratch[3]);
  CheckTangent(m, 5.0, Eun, s, "unloading");
  // Relaxation under held strain: yielded, then held for 100 s, the stress falls inside the surface.
  CheckTangent(m, 100.0, Ey2, s, "held after yield");
  // Shear and a large stretch (the Biot measures' stretch U differs most from 1 + E there).
  const double Esh[3] = {0.3, -0.05, 0.4};
  CheckTangent(m, 5.0, Esh, s, "shear and stretch");
}

// A uniaxial test in the published model's measures: the engineering strain e held along x, y
// free (Syy = 0 by Newton on Eyy), the nominal stress P = (1 + e) Sxx returned. E_xx = e + e^2/2.
double UniaxialNominal(const ViscoelasticPlasticMaterial &m, double dt, double e, State *s) {
  const double exx = e + 0.5 * e * e;
  double E[3] = {exx, -m.plastic.nu * exx, 0.0}, S[3], D[9];
  std::vector<double> scratch(s->h.size());
  for (int it = 0; it < 30; ++it) {
    CHECK(ViscoelasticPlasticUpdate(m, dt, E, s->h.data(), scratch.data(), S, D) == KERNEL_OK, "uniaxial step");
    if (std::fabs(S[1]) <= 1e-14 * std::fabs(S[0])) break;
    E[1] -= S[1] / D[4];
  }
  CHECK(std::fabs(S[1]) <= 1e-12 * std::fabs(S[0]), "uniaxial: Syy = %g with Sxx = %g", S[1], S[0]);
  s->h = scratch;
  return (1.0 + e) * S[0];
}

// The published model in its own measures: a relaxation test at engineering strain e gives the
// nominal stress P(t) = E(t) e, E(t) = E0 (1 - sum g_i (1 - exp(-t/tau_i))). With the Biot measures
// the law gives it to round-off at any strain; with Green-Lagrange/PK2 it is (1 + e)(1 + e/2) too
// high: 1.16 % at 0.77 % strain (the measure mapping docs/viscoelastic.md states).
void TestNominalAgainstPublished() {
  ViscoelasticPlasticMaterial m = EtfeTwoBranches();
  m.plastic.yield[0] = m.plastic.yield[1] = 1e9;  // the linear viscoelastic model: no yield within reach
  const double E0 = m.plastic.young;
  for (const double e : {0.0077, 0.02, 0.05}) {
    for (const int measure : {kMeasureBiot, kMeasureGreenLagrange}) {
      m.measure = measure;
      State s(m);
      double t = 0.0, worst = 0.0, P0 = 0.0;
      for (int k = 0; k <= 12; ++k) {
        const double dt = k == 0 ? 0.0 : 0.5 * std::pow(2.0, k - 1);  // the step, then held: 0.5 s ... 1024 s
        t += dt;
        const double P = UniaxialNominal(m, dt, e, &s);
        const double published = E0 * ViscoelasticPlasticRelaxationFraction(m, t) * e;
        if (k == 0) P0 = P;
        worst = std::fmax(worst, std::fabs(P / published - 1.0));
      }
      const double mapping = (1.0 + e) * (1.0 + 0.5 * e) - 1.0;  // GL/PK2 against the lab measures
      std::printf("  uniaxial relaxation at e = %.4f, %s: nominal stress against the published model's, worst %.3e "
                  "(instantaneous %.6f MPa against %.6f)\n",
                  e, measure == kMeasureBiot ? "Biot" : "Green-Lagrange/PK2", worst, P0, E0 * e);
      if (measure == kMeasureBiot)
        CHECK(worst <= 1e-12, "Biot measures: P(t) = E(t) e to round-off at e = %g (worst %g)", e, worst);
      else
        CHECK(std::fabs(worst - mapping) <= 0.02 * mapping,
              "Green-Lagrange/PK2: P(t) / (E(t) e) - 1 = %g at e = %g, the mapping error (1+e)(1+e/2)-1 = %g",
              worst, e, mapping);
    }
  }
}

// Step strain e at t = 0, held: S(t) = E0 e (g_inf + g exp(-t/tau)) for any step sizes.
void TestRelaxationStep() {
  const ViscoelasticPlasticMaterial m = StandardLinearSolid();
  State s(m);
  const double e = 0.004, E0 = m.plastic.young, ginf = 1.0 - m.g[0];
  double E[3], S[3], t = 0.0;
  Uniaxial(m, e, E);
  Step(m, 0.0, E, &s, S);
  CHECK_CLOSE(S[0], E0 * e, 1e-12, 0.0);
  double worst = 0.0;
  for (int k = 0; k < 60; ++k) {
    const double dt = 0.3 * std::pow(1.15, k);
    t += dt;
    Step(m, dt, E, &s, S);
    const double exact = E0 * e * (ginf + m.g[0] * std::exp(-t / m.tau[0]));
    worst = std::fmax(worst, std::fabs(S[0] - exact) / (E0 * e));
    CHECK(std::fabs(S[1]) <= 1e-12 * E0 * e, "uniaxial: Syy = %g", S[1]);
  }
  std::printf("relaxation after a step strain: largest error %.2e of E0 e over t = 0 .. %.0f s\n", worst, t);
  CHECK(worst <= 1e-6, "relaxation: error %g", worst);
}

// Strain ramp at rate r to T0, then held: the recursion is exact for piecewise-linear strain.
void TestRelaxationRamp() {
  const ViscoelasticPlasticMaterial m = StandardLinearSolid();
  State s(m);
  const double r = 1e-4, T0 = 40.0, E0 = m.plastic.young, tau = m.tau[0], g = m.g[0], ginf = 1.0 - g;
  auto exact = [&](double t) {
    if (t <= T0) return E0 * r * (ginf * t + g * tau * (1.0 - std::exp(-t / tau)));
    return E0 * r * (ginf * T0 + g * tau * (std::exp(-(t - T0) / tau) - std::exp(-t / tau)));
  };
  double E[3], S[3], t = 0.0, worst = 0.0;
  const int nramp = 7;
  for (int k = 1; k <= nramp; ++k) {
    const double tn = T0 * k / nramp;
    Uniaxial(m, r * tn, E);
    Step(m, tn - t, E, &s, S);
    t = tn;
    worst = std::fmax(worst, std::fabs(S[0] - exact(t)) / (E0 * r * T0));
  }
  for (int k = 0; k < 30; ++k) {
    const double dt = 2.0 * std::pow(1.3, k);
    t += dt;
    Step(m, dt, E, &s, S);
    worst = std::fmax(worst, std::fabs(S[0] - exact(t)) / (E0 * r * T0));
  }
  std::printf("ramp then hold: largest error %.2e of the ramp's elastic stress\n", worst);
  CHECK(worst <= 1e-6, "ramp relaxation: error %g", worst);
}

// Stress s0 applied at t = 0 and held: e(t) = s0 J(t), J = 1/E_inf - g/(g_inf E0) exp(-t/tau_c),
// tau_c = tau/g_inf. The strain is not linear within a step, so small steps (error ~ (dt/tau)^2).
void TestCreep() {
  const ViscoelasticPlasticMaterial m = StandardLinearSolid();
  State s(m);
  const double s0 = 5.0, E0 = m.plastic.young, g = m.g[0], ginf = 1.0 - g, tau_c = m.tau[0] / ginf;
  auto J = [&](double t) { return 1.0 / (ginf * E0) - g / (ginf * E0) * std::exp(-t / tau_c); };
  double e = s0 / E0, t = 0.0, E[3], S[3], D[9], worst = 0.0;
  const double dt = m.tau[0] / 1000.0;
  double scratch[ViscoelasticPlasticHistorySize(kMaxPronyTerms)];
  for (int k = 0; k <= 10000; ++k) {
    const double h = k == 0 ? 0.0 : dt;
    for (int it = 0; it < 20; ++it) {  // Newton on the axial strain, Syy = 0 by construction
      Uniaxial(m, e, E);
      ViscoelasticPlasticUpdate(m, h, E, s.h.data(), scratch, S, D);
      if (std::fabs(S[0] - s0) <= 1e-14 * s0) break;
      e -= (S[0] - s0) / (D[0] - m.plastic.nu * D[1]);
    }
    Step(m, h, E, &s, S);
    t += h;
    worst = std::fmax(worst, std::fabs(e - s0 * J(t)) / (s0 * J(t)));
  }
  std::printf("creep: largest error %.2e of the strain over t = 0 .. %.0f s (%.1f retardation times)\n", worst, t,
              t / tau_c);
  CHECK(worst <= 1e-6, "creep: error %g", worst);
}

// A loading path that yields on both segments, unloads and reloads, with shear.
std::vector<std::vector<double>> Path() {
  std::vector<std::vector<double>> p;
  for (int k = 1; k <= 12; ++k) p.push_back({0.01 * k, 0.004 * k, 0.003 * k});
  for (int k = 1; k <= 5; ++k) p.push_back({0.12 - 0.01 * k, 0.048, 0.036 - 0.004 * k});
  for (int k = 1; k <= 5; ++k) p.push_back({0.07 + 0.03 * k, 0.048 + 0.01 * k, 0.016});
  return p;
}

void TestNoBranchIsPlastic() {
  ViscoelasticPlasticMaterial m = EtfeTwoBranches();
  m.nterms = 0;
  State s(m);
  PlasticState ps{};
  bool same = true;
  for (const auto &E : Path()) {
    double S[3], D[9], Sp[3], Dp[9];
    ViscoelasticPlasticUpdate(m, 7.0, E.data(), s.h.data(), s.h.data(), S, D);
    PlasticReturnMap(m.plastic, E.data(), ps, &ps, Sp, Dp);
    same = same && std::memcmp(S, Sp, sizeof S) == 0 && std::memcmp(D, Dp, sizeof D) == 0 &&
           std::memcmp(s.h.data(), &ps, sizeof ps) == 0;
  }
  CHECK(same, "no Maxwell branch: stress, tangent and plastic state equal the plastic law's bit for bit");
}

void TestShortTimesAreRelaxedPlastic() {
  ViscoelasticPlasticMaterial m = EtfeTwoBranches();
  m.tau[0] = 1e-13, m.tau[1] = 2e-13;  // the branches' weight in a step is g tau/dt
  State s(m);
  PlasticMaterial relaxed = m.plastic;
  relaxed.young = m.plastic.young * (1.0 - m.g[0] - m.g[1]);
  PlasticState ps{};
  double worst = 0.0;
  for (const auto &E : Path()) {
    double S[3], D[9], Sp[3], Dp[9];
    ViscoelasticPlasticUpdate(m, 1.0, E.data(), s.h.data(), s.h.data(), S, D);
    PlasticReturnMap(relaxed, E.data(), ps, &ps, Sp, Dp);
    for (int k = 0; k < 3; ++k) worst = std::fmax(worst, std::fabs(S[k] - Sp[k]) / 23.04);
    for (int k = 0; k < 9; ++k) worst = std::fmax(worst, std::fabs(D[k] - Dp[k]) / relaxed.young);
    worst = std::fmax(worst, std::fabs(s.h[3] - ps.ep_bar));
  }
  std::printf("relaxation times 1e-13 s, steps of 1 s: largest difference from the relaxed plastic law %.2e\n",
              worst);
  CHECK(worst <= 1e-11, "short relaxation times: %g", worst);
}

// After every step the stress is the sum of the branches, g_inf S0 + sum h_i.
void TestStressIsSumOfBranches() {
  const ViscoelasticPlasticMaterial m = EtfeTwoBranches();
  State s(m);
  double worst = 0.0;
  for (const auto &E : Path()) {
    double S[3];
    Step(m, 3.0, E.data(), &s, S);
    const double ginf = 1.0 - m.g[0] - m.g[1];
    for (int k = 0; k < 3; ++k) {
      const double sum = ginf * s.h[4 + k] + s.h[7 + k] + s.h[10 + k];
      worst = std::fmax(worst, std::fabs(S[k] - sum) / 23.04);
    }
  }
  CHECK(worst <= 1e-12, "S = g_inf S0 + sum h_i: %g", worst);
}

// The check rejects m with a message that contains `word`.
void ExpectRejected(const ViscoelasticPlasticMaterial &m, const char *word) {
  char msg[256] = "";
  CHECK(ViscoelasticPlasticMaterialCheck(m, msg, sizeof msg) != 0 && std::strstr(msg, word), "'%s' lacks '%s'", msg, word);
}

void TestChecks() {
  char msg[256];
  const ViscoelasticPlasticMaterial good = EtfeTwoBranches();
  CHECK(ViscoelasticPlasticMaterialCheck(good, msg, sizeof msg) == 0, "valid material rejected: %s", msg);
  ViscoelasticPlasticMaterial m = good;
  m.tau[0] = -1.0;
  ExpectRejected(m, "relaxation time");
  m = good, m.tau[1] = 5.0;
  ExpectRejected(m, "increase");
  m = good, m.g[1] = -0.1;
  ExpectRejected(m, "g[1]");
  m = good, m.g[1] = 0.8;
  ExpectRejected(m, "sum");
  CHECK_CLOSE(ViscoelasticPlasticRelaxationFraction(good, 0.0), 1.0, 1e-15, 0.0);
  CHECK_CLOSE(ViscoelasticPlasticRelaxationFraction(good, 1e12), 0.65, 1e-15, 0.0);
}

} // namespace

int main() {
  TestTangentEveryState(kMeasureGreenLagrange);
  TestTangentEveryState(kMeasureBiot);
  TestNominalAgainstPublished();
  TestRelaxationStep();
  TestRelaxationRamp();
  TestCreep();
  TestNoBranchIsPlastic();
  TestShortTimesAreRelaxedPlastic();
  TestStressIsSumOfBranches();
  TestChecks();
  TEST_MAIN_END();
}
