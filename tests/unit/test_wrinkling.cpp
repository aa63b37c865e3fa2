// Tension-field membrane kernel (src/kernels/wrinkling.cpp): the state criterion, the relaxed
// stress against closed forms (uniaxial tension along the major principal strain, the uniform
// shear panel), continuity across the state boundaries, and the tangent against central finite
// differences in every state (taut, wrinkled at 0/30/45/90/-60 deg, slack with its documented
// regularization).
#include "etfe/kernels/elastic.h"
#include "etfe/kernels/wrinkling.h"

#include "check.h"
#include "fd_tangent.h"

#include <cmath>
#include <initializer_list>

namespace {

constexpr double kYoung = 800.0;  // ETFE, MPa
constexpr double kNu = 0.43;
const double kPi = std::acos(-1.0);

// Voigt strain with principal strains e1 >= e2, e1 along the angle th (rad) from the x axis.
void StrainFromPrincipal(double e1, double e2, double th, double E[3]) {
  const double c = std::cos(th), s = std::sin(th);
  E[0] = e1 * c * c + e2 * s * s;
  E[1] = e1 * s * s + e2 * c * c;
  E[2] = 2.0 * (e1 - e2) * c * s;
}

// Largest |D - dS/dE (central FD)| over the 9 entries, the FD step h per strain component.
double TangentMismatch(const double E[3], double h, double *dmax) {
  double S[3], D[9];
  etfe::TensionFieldStress(kYoung, kNu, E, S, D, nullptr);
  double Dfd[9];
  etfe_test::CentralDifferenceJacobian(
      [](const double *Ex, double *Sx) { etfe::TensionFieldStress(kYoung, kNu, Ex, Sx, nullptr, nullptr); }, E, 3, 3, h,
      Dfd);
  double worst = 0.0;
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i) worst = std::fmax(worst, std::fabs(D[3 * i + j] - Dfd[3 * i + j]));
  *dmax = MaxAbs(D, 9);
  return worst;
}

void TestTaut() {
  // Biaxial tension and a mildly sheared one: the plane-stress law itself.
  const double cases[2][3] = {{0.01, 0.005, 0.002}, {0.003, 0.0, 0.001}};
  for (const auto &E : cases) {
    double S[3], D[9], Se[3], De[9];
    etfe::WrinkleInfo info;
    etfe::TensionFieldStress(kYoung, kNu, E, S, D, &info);
    etfe::ElasticPlaneStress(kYoung, kNu, E, Se, De);
    CHECK(info.state == etfe::WRINKLE_TAUT, "state %d", info.state);
    for (int i = 0; i < 3; ++i) CHECK(S[i] == Se[i], "S[%d] %g vs %g", i, S[i], Se[i]);
    for (int i = 0; i < 9; ++i) CHECK(D[i] == De[i], "D[%d]", i);
    double dmax, mis = TangentMismatch(E, 1e-7, &dmax);
    CHECK(mis <= 1e-6 * dmax, "taut FD mismatch %g (|D| %g)", mis, dmax);
  }
  // E = 0 (every Newton start) is taut with the elastic tangent, not slack.
  const double Z[3] = {0, 0, 0};
  double S[3], D[9];
  CHECK(etfe::TensionFieldStress(kYoung, kNu, Z, S, D, nullptr) == etfe::WRINKLE_TAUT, "E = 0 not taut");
  // Round-off strains of an unloaded film, of any sign, are taut too (kTautStrainTolerance).
  const double R[4][3] = {{-3e-16, 1e-16, 4e-16}, {-5e-16, -5e-16, 0}, {2e-16, -6e-16, -1e-16}, {0, 0, 1e-15}};
  for (const auto &E : R)
    CHECK(etfe::TensionFieldStress(kYoung, kNu, E, S, D, nullptr) == etfe::WRINKLE_TAUT, "round-off strain not taut");
}

void TestWrinkled() {
  const double angles_deg[] = {0.0, 30.0, 45.0, 90.0, -60.0};
  for (double deg : angles_deg) {
    const double th = deg * kPi / 180.0;
    const double e1 = 0.02, e2 = -0.015;  // e2 + nu e1 < 0 < e1
    double E[3], S[3], D[9];
    StrainFromPrincipal(e1, e2, th, E);
    etfe::WrinkleInfo info;
    const int st = etfe::TensionFieldStress(kYoung, kNu, E, S, D, &info);
    CHECK(st == etfe::WRINKLE_WRINKLED && info.state == st, "%g deg: state %d", deg, st);
    // Direction up to sign, stress uniaxial Y e1 along it, lost length -(e2 + nu e1).
    const double c = std::cos(th), s = std::sin(th);
    CHECK_CLOSE(std::fabs(info.dir[0] * c + info.dir[1] * s), 1.0, 0.0, 1e-12);
    const double sig = kYoung * e1;
    CHECK_CLOSE(S[0], sig * c * c, 1e-12, 1e-12 * sig);
    CHECK_CLOSE(S[1], sig * s * s, 1e-12, 1e-12 * sig);
    CHECK_CLOSE(S[2], sig * c * s, 1e-12, 1e-12 * sig);
    CHECK_CLOSE(info.strain, -(e2 + kNu * e1), 1e-12, 0.0);
    double dmax, mis = TangentMismatch(E, 1e-8, &dmax);
    CHECK(mis <= 1e-6 * dmax, "%g deg: wrinkled FD mismatch %g (|D| %g)", deg, mis, dmax);
    // The tangent is not the elastic one: the wrinkle angle's dependence on E is in it.
    double De[9];
    etfe::ElasticPlaneStressTangent(kYoung, kNu, De);
    CHECK(std::fabs(D[8] - De[8]) > 1e-3 * De[8], "%g deg: wrinkled tangent equals elastic", deg);
  }
  // Near the taut boundary (small lost length) and near the slack one (small e1).
  const double near[2][2] = {{0.01, -kNu * 0.01 - 1e-5}, {1e-4, -0.01}};
  for (const auto &p : near) {
    double E[3];
    StrainFromPrincipal(p[0], p[1], 0.3, E);
    double dmax, mis = TangentMismatch(E, 1e-10, &dmax);
    CHECK(mis <= 1e-5 * dmax, "near-boundary FD mismatch %g (|D| %g)", mis, dmax);
  }
}

void TestSlack() {
  const double E[3] = {-0.01, -0.004, 0.003};
  double S[3], D[9], De[9];
  etfe::WrinkleInfo info;
  CHECK(etfe::TensionFieldStress(kYoung, kNu, E, S, D, &info) == etfe::WRINKLE_SLACK, "not slack");
  CHECK(S[0] == 0.0 && S[1] == 0.0 && S[2] == 0.0, "slack stress not zero");
  // The exact tangent is 0; the returned one is the documented regularization and nothing else.
  etfe::ElasticPlaneStressTangent(kYoung, kNu, De);
  for (int i = 0; i < 9; ++i) CHECK_CLOSE(D[i], etfe::kSlackTangentFraction * De[i], 1e-15, 0.0);
  double dmax, mis = TangentMismatch(E, 1e-7, &dmax);
  CHECK(mis <= etfe::kSlackTangentFraction * MaxAbs(De, 9) * (1 + 1e-9), "slack FD mismatch %g", mis);
  CHECK(info.strain > 0.0, "slack lost length %g", info.strain);
}

// Stress continuous across taut|wrinkled (e2 = -nu e1) and wrinkled|slack (e1 = 0).
void TestContinuity() {
  const double th = 0.7, e1 = 0.01, tol = etfe::kTautStrainTolerance, eps = 1e-12;
  double Ea[3], Eb[3], Sa[3], Sb[3];
  StrainFromPrincipal(e1, -kNu * e1 - tol + eps, th, Ea);
  StrainFromPrincipal(e1, -kNu * e1 - tol - eps, th, Eb);
  CHECK(etfe::TensionFieldStress(kYoung, kNu, Ea, Sa, nullptr, nullptr) == etfe::WRINKLE_TAUT, "a");
  CHECK(etfe::TensionFieldStress(kYoung, kNu, Eb, Sb, nullptr, nullptr) == etfe::WRINKLE_WRINKLED, "b");
  // The jump is the documented one: at most E tol/(1-nu^2) (the taut side's small minor stress).
  for (int i = 0; i < 3; ++i) CHECK_CLOSE(Sa[i], Sb[i], 0.0, 2.0 * kYoung * tol / (1 - kNu * kNu));
  StrainFromPrincipal(eps, -0.01, th, Ea);
  etfe::TensionFieldStress(kYoung, kNu, Ea, Sa, nullptr, nullptr);
  CHECK(MaxAbs(Sa, 3) <= 2 * kYoung * eps, "stress at the slack boundary %g", MaxAbs(Sa, 3));
}

// Uniform shear panel: pretension strain e0 in x and y plus the engineering shear 2 g. Closed
// form: principal strains e0 +- g at 45 deg; wrinkled once g > e0 (1+nu)/(1-nu); then
// S = Y (e0 + g)/2 (1, 1, 1) and the wrinkle angle is 45 deg.
void TestShearPanel() {
  const double e0 = 0.002;
  const double g_onset = e0 * (1 + kNu) / (1 - kNu);
  for (double g : {0.5 * g_onset, 1.5 * g_onset, 4.0 * g_onset}) {
    const double E[3] = {e0, e0, 2 * g};
    double S[3];
    etfe::WrinkleInfo info;
    etfe::TensionFieldStress(kYoung, kNu, E, S, nullptr, &info);
    if (g < g_onset) {
      CHECK(info.state == etfe::WRINKLE_TAUT, "below onset not taut");
      continue;
    }
    CHECK(info.state == etfe::WRINKLE_WRINKLED, "shear panel state %d", info.state);
    const double sig = kYoung * (e0 + g);
    for (int i = 0; i < 3; ++i) CHECK_CLOSE(S[i], 0.5 * sig, 1e-12, 0.0);
    CHECK_CLOSE(std::atan2(info.dir[1], info.dir[0]), 0.25 * kPi, 0.0, 1e-12);
    CHECK_CLOSE(info.strain, -(e0 - g + kNu * (e0 + g)), 1e-12, 0.0);
  }
}

} // namespace

int main() {
  TestTaut();
  TestWrinkled();
  TestSlack();
  TestContinuity();
  TestShearPanel();
  TEST_MAIN_END();
}
