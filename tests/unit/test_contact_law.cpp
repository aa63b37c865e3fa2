// Unit tests of the node-to-rigid friction contact laws (docs/theory.md §5, thesis eqs. 4.25-4.31).
#include "etfe/kernels/contact_law.h"

#include "check.h"
#include "fd_tangent.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

using namespace etfe;

namespace {

const double kPi = 3.14159265358979323846;

// Deterministic generator so that failures reproduce.
struct Rng {
  std::uint64_t s = 0x9E3779B97F4A7C15ull;
  double Uniform() {  // [0, 1)
    s ^= s << 13;
    s ^= s >> 7;
    s ^= s << 17;
    return static_cast<double>(s >> 11) * (1.0 / 9007199254740992.0);
  }
  double Range(double a, double b) { return a + (b - a) * Uniform(); }
};

ContactState State(double gx, double gy, double gz, double fx, double fy, double fz, int status) {
  ContactState s;
  s.g[0] = gx;
  s.g[1] = gy;
  s.g[2] = gz;
  s.f[0] = fx;
  s.f[1] = fy;
  s.f[2] = fz;
  s.status = status;
  return s;
}

// Largest |dfdg - central FD| relative to max |dfdg| (or absolute when the tangent is zero).
double ImplicitTangentError(const ContactParameters &p, const ContactState &c, const double g[3],
                            double h) {
  double f[3], K[9];
  ContactImplicitForce(p, c, g, f, K);
  double Kfd[9];
  etfe_test::CentralDifferenceJacobian([&](const double *gx, double *fx) { ContactImplicitForce(p, c, gx, fx, nullptr); },
                                       g, 3, 3, h, Kfd);
  double err = 0.0;
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i) err = std::max(err, std::fabs(Kfd[3 * i + j] - K[3 * i + j]));
  const double scale = MaxAbs(K, 9);
  return scale > 0.0 ? err / scale : err;
}

bool InsideCone(const ContactParameters &p, const double f[3]) {
  return std::hypot(f[0], f[1]) <= p.mu * std::fabs(f[2]) * (1.0 + 1e-12);
}

// ---------------------------------------------------------------------------------------------
// Implicit law: consistent tangent against central differences over the penalty range.
void TestImplicitTangent() {
  Rng rng;
  const double F = 10.0;  // force scale [N]
  const int statuses[3] = {CONTACT_STICK, CONTACT_SLIP, CONTACT_OPEN};
  int cases = 0, expected_status_ok = 0;
  double worst = 0.0;
  for (double mu : {0.3, 1.0}) {
    for (double kn = 1e2; kn <= 1.0001e12; kn *= 100.0) {
      for (double kt_ratio : {1.0, 0.05}) {
        const ContactParameters p{kn, kt_ratio * kn, mu};
        const double L = F / kn;  // gap scale
        for (int committed_status : statuses) {
          for (double depth : {1.0, 1e-3}) {  // 1e-3: just before lift-off
            for (double rho : {0.5, 2.0}) {   // trial/limit: stick, slip
              for (int k = 0; k < 6; ++k) {
                const double theta = 2.0 * kPi * (k + rng.Uniform()) / 6.0;
                // A committed state inside the cone, at a random committed gap.
                const double a = 2.0 * kPi * rng.Uniform(), r = rng.Uniform();
                ContactState c = committed_status == CONTACT_OPEN
                                     ? State(rng.Range(-1, 1) * L, rng.Range(-1, 1) * L,
                                             rng.Range(0, 1) * L, 0, 0, 0, CONTACT_OPEN)
                                     : State(rng.Range(-1, 1) * L, rng.Range(-1, 1) * L, -L,
                                             r * mu * F * std::cos(a), r * mu * F * std::sin(a),
                                             -F, committed_status);
                const double w = -depth * L;
                const double want = rho * mu * kn * depth * L;  // |f_t*| wanted
                const double base[2] = {committed_status == CONTACT_OPEN ? 0.0 : c.f[0],
                                        committed_status == CONTACT_OPEN ? 0.0 : c.f[1]};
                const double g[3] = {c.g[0] + (want * std::cos(theta) - base[0]) / p.kt,
                                     c.g[1] + (want * std::sin(theta) - base[1]) / p.kt, w};
                // Small against |w| so no difference crosses the open/stick/slip boundaries.
                const double h = 1e-5 * depth * L;
                double f[3], K[9];
                const int st = ContactImplicitForce(p, c, g, f, K);
                if (st == (rho < 1.0 ? CONTACT_STICK : CONTACT_SLIP)) ++expected_status_ok;
                const double e = ImplicitTangentError(p, c, g, h);
                worst = std::max(worst, e);
                CHECK(e < 1e-6, "FD tangent error %.3g (kn %g mu %g kt/kn %g status %d depth %g "
                                "rho %g theta %g)", e, kn, mu, kt_ratio, committed_status, depth,
                      rho, theta);
                ++cases;
              }
            }
          }
        }
      }
    }
  }
  CHECK(expected_status_ok == cases, "%d of %d cases found the expected stick/slip status",
        expected_status_ok, cases);
  std::printf("implicit tangent: %d FD cases, worst relative error %.3g\n", cases, worst);
}

// Slip tangent in closed form for one direction: the structure the assembler relies on.
void TestImplicitSlipTangentForm() {
  const ContactParameters p{1000.0, 400.0, 0.3};
  const ContactState c = State(0, 0, 0, 0, 0, 0, CONTACT_OPEN);
  const double g[3] = {0.3, 0.4, -0.1};  // f_t* = 400 (0.3, 0.4) = 200 (0.6, 0.8); limit 30
  double f[3], K[9];
  CHECK(ContactImplicitForce(p, c, g, f, K) == CONTACT_SLIP, "slip expected");
  CHECK_CLOSE(f[0], 30.0 * 0.6, 1e-14, 0.0);
  CHECK_CLOSE(f[1], 30.0 * 0.8, 1e-14, 0.0);
  CHECK_CLOSE(f[2], -100.0, 1e-14, 0.0);
  const double r = 400.0 * 30.0 / 200.0;
  CHECK_CLOSE(K[0], r * (1 - 0.36), 1e-13, 0.0);
  CHECK_CLOSE(K[1], -r * 0.48, 1e-13, 0.0);
  CHECK_CLOSE(K[3], -r * 0.48, 1e-13, 0.0);
  CHECK_CLOSE(K[4], r * (1 - 0.64), 1e-13, 0.0);
  // More compression (w down) must raise |f_t|: d f_t/d w points against t.
  CHECK_CLOSE(K[2], -0.3 * 1000.0 * 0.6, 1e-13, 0.0);
  CHECK_CLOSE(K[5], -0.3 * 1000.0 * 0.8, 1e-13, 0.0);
  CHECK(K[6] == 0.0 && K[7] == 0.0, "normal row has no tangential coupling");
  CHECK_CLOSE(K[8], 1000.0, 0.0, 0.0);
}

// Implicit law: cone, lift-off, frictionless.
void TestImplicitCone() {
  Rng rng;
  int n = 0, open = 0, stick = 0, slip = 0;
  for (int it = 0; it < 20000; ++it) {
    const double kn = std::pow(10.0, rng.Range(2, 13));
    const double mu = rng.Uniform() < 0.1 ? 0.0 : rng.Range(0.0, 1.5);
    const ContactParameters p{kn, kn * std::pow(10.0, rng.Range(-2, 1)), mu};
    const double L = std::pow(10.0, rng.Range(-6, 2)) / kn;
    const int cs = static_cast<int>(rng.Uniform() * 3.0);
    const double fz = -rng.Range(0, 2) * kn * L;
    const double a = rng.Range(0, 2 * kPi), r = rng.Range(0, 1) * mu * std::fabs(fz);
    const ContactState c =
        cs == CONTACT_OPEN
            ? State(rng.Range(-1, 1) * L, rng.Range(-1, 1) * L, rng.Range(0, 1) * L, 0, 0, 0, cs)
            : State(rng.Range(-1, 1) * L, rng.Range(-1, 1) * L, fz / kn, r * std::cos(a),
                    r * std::sin(a), fz, cs);
    const double g[3] = {rng.Range(-5, 5) * L, rng.Range(-5, 5) * L, rng.Range(-3, 1) * L};
    double f[3], K[9];
    const int st = ContactImplicitForce(p, c, g, f, K);
    ++n;
    if (g[2] >= 0.0) {
      ++open;
      CHECK(st == CONTACT_OPEN, "lift-off must be OPEN, got %d", st);
      CHECK(MaxAbs(f, 3) == 0.0 && MaxAbs(K, 9) == 0.0, "lift-off must give zero force/tangent");
      continue;
    }
    st == CONTACT_STICK ? ++stick : ++slip;
    CHECK(st != CONTACT_OPEN, "closed gap reported OPEN");
    CHECK_CLOSE(f[2], kn * g[2], 1e-15, 0.0);
    CHECK(InsideCone(p, f), "outside the cone: |f_t| %.17g mu|f_z| %.17g", std::hypot(f[0], f[1]),
          mu * std::fabs(f[2]));
    if (mu == 0.0) {
      CHECK(f[0] == 0.0 && f[1] == 0.0, "mu = 0 must give f_t = 0");
      CHECK(K[0] == 0.0 && K[1] == 0.0 && K[2] == 0.0 && K[3] == 0.0 && K[4] == 0.0 &&
                K[5] == 0.0,
            "mu = 0 must give no tangential stiffness");
    }
  }
  CHECK(open > 1000 && stick > 1000 && slip > 1000, "coverage open %d stick %d slip %d", open,
        stick, slip);
  std::printf("implicit cone: %d random gaps (open %d, stick %d, slip %d)\n", n, open, stick, slip);

  // Beyond w = 0: open. Exactly at w = 0 the pair is closed with zero force and keeps its
  // normal spring, so a film laid on a support starts with a non-singular tangent.
  const ContactParameters p{1e6, 1e6, 0.3};
  const ContactState c = State(0, 0, -1e-6, 0.1, 0.0, -1.0, CONTACT_STICK);
  {
    const double g[3] = {0.0, 0.0, 0.0};
    double f[3], K[9];
    CHECK(ContactImplicitForce(p, c, g, f, K) != CONTACT_OPEN, "w = 0 must be closed");
    CHECK(f[2] == 0.0 && K[8] == p.kn, "w = 0: zero normal force, normal spring kn");
  }
  for (double w : {1e-12, 1e-3}) {
    const double g[3] = {1e-6, 2e-6, w};
    double f[3], K[9];
    CHECK(ContactImplicitForce(p, c, g, f, K) == CONTACT_OPEN, "w = %g must be open", w);
    CHECK(MaxAbs(f, 3) == 0.0 && MaxAbs(K, 9) == 0.0, "w = %g must give zero force", w);
  }
}

// Re-closing of an open pair sticks at the committed gap, whatever f the state holds.
void TestImplicitReclose() {
  const ContactParameters p{1000.0, 500.0, 0.5};
  const ContactState c = State(0.2, -0.1, 0.05, 7.0, 7.0, 7.0, CONTACT_OPEN);
  const double g[3] = {0.21, -0.1, -0.04};
  double f[3], K[9];
  CHECK(ContactImplicitForce(p, c, g, f, K) == CONTACT_STICK, "re-close must stick");
  CHECK_CLOSE(f[0], 500.0 * 0.01, 1e-12, 0.0);
  CHECK_CLOSE(f[1], 0.0, 0.0, 1e-12);
  CHECK_CLOSE(f[2], -40.0, 1e-14, 0.0);
  CHECK(K[0] == 500.0 && K[4] == 500.0 && K[8] == 1000.0, "stick tangent diag(kt, kt, kn)");
}

// ---------------------------------------------------------------------------------------------
// Lagged law: a hand-worked sequence against eqs. 4.26-4.31 and the Fig. 4.4 correction.
// kn = 1000, kt = 500, mu = 0.3.
void TestLaggedSequence() {
  const ContactParameters p{1000.0, 500.0, 0.3};
  ContactState s = State(0, 0, 0, 0, 0, 0, CONTACT_STICK);
  double f[3], K[9];
  const double tol = 1e-13;

  // 1. Stick (4.27): f = diag(kt, kt, kn) dg.
  {
    const double g[3] = {0.01, 0.0, -0.1};
    ContactLaggedForce(p, s, g, f, K);
    CHECK_CLOSE(f[0], 5.0, tol, 0.0);
    CHECK_CLOSE(f[1], 0.0, 0.0, 1e-15);
    CHECK_CLOSE(f[2], -100.0, tol, 0.0);
    const double Kst[9] = {500, 0, 0, 0, 500, 0, 0, 0, 1000};
    for (int i = 0; i < 9; ++i) CHECK(K[i] == Kst[i], "stick tangent entry %d = %g", i, K[i]);
    ContactLaggedCommit(p, s, g, f, &s);
    CHECK(s.status == CONTACT_STICK, "5 < 30: stick, got %d", s.status);
    CHECK(s.g[0] == g[0] && s.g[1] == g[1] && s.g[2] == g[2], "commit stores the gap");
  }
  // 2. Stick increments are linear springs from the committed force.
  {
    const double g[3] = {0.05, 0.02, -0.12};
    ContactLaggedForce(p, s, g, f, K);
    CHECK_CLOSE(f[0], 25.0, tol, 0.0);
    CHECK_CLOSE(f[1], 10.0, tol, 0.0);
    CHECK_CLOSE(f[2], -120.0, tol, 0.0);
    ContactLaggedCommit(p, s, g, f, &s);
    CHECK(s.status == CONTACT_STICK, "26.9 < 36: stick");
  }
  // 3. Stick overshoots the cone; the commit puts it back on the cone, same direction, SLIP.
  const double n3 = std::sqrt(55.0 * 55.0 + 30.0 * 30.0), c = 55.0 / n3, sn = 30.0 / n3;
  {
    const double g[3] = {0.11, 0.06, -0.12};
    ContactLaggedForce(p, s, g, f, K);
    CHECK_CLOSE(f[0], 55.0, tol, 0.0);
    CHECK_CLOSE(f[1], 30.0, tol, 0.0);
    CHECK(s.status == CONTACT_STICK, "status of the step is the committed one");
    ContactLaggedCommit(p, s, g, f, &s);
    CHECK(s.status == CONTACT_SLIP, "62.6 >= 36: slip");
    CHECK_CLOSE(s.f[0], 36.0 * c, tol, 0.0);
    CHECK_CLOSE(s.f[1], 36.0 * sn, tol, 0.0);
    CHECK_CLOSE(s.f[2], -120.0, tol, 0.0);
  }
  // 4. Slip (4.29): more compression adds mu kn |dw| along a; the tangent is eq. 4.31.
  {
    const double g[3] = {0.2, 0.1, -0.13};  // dw = -0.01
    ContactLaggedForce(p, s, g, f, K);
    CHECK_CLOSE(f[2], -130.0, tol, 0.0);
    CHECK_CLOSE(f[0], 39.0 * c, tol, 0.0);
    CHECK_CLOSE(f[1], 39.0 * sn, tol, 0.0);
    CHECK_CLOSE(std::hypot(f[0], f[1]), 0.3 * 130.0, tol, 0.0);
    // Eq. 4.31: T^T [[0,0,mu kn],[0,0,0],[0,0,kn]] T with T = [[c,s,0],[-s,c,0],[0,0,1]] written
    // for compression-positive (g_t, -w) -> (f_t, -f_z); ours is D k_g D with D = diag(1,1,-1).
    const double T[9] = {c, sn, 0, -sn, c, 0, 0, 0, 1};
    const double M[9] = {0, 0, 0.3 * 1000.0, 0, 0, 0, 0, 0, 1000.0};
    const double D[3] = {1, 1, -1};
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) {
        double kg = 0.0;
        for (int a = 0; a < 3; ++a)
          for (int b = 0; b < 3; ++b) kg += T[3 * a + i] * M[3 * a + b] * T[3 * b + j];
        CHECK_CLOSE(K[3 * i + j], D[i] * kg * D[j], 1e-13, 1e-12);
      }
    // The lagged force is linear within the step: f = f_n + K dg exactly (eq. 4.30).
    const double dg[3] = {g[0] - s.g[0], g[1] - s.g[1], g[2] - s.g[2]};
    for (int i = 0; i < 3; ++i)
      CHECK_CLOSE(f[i], s.f[i] + K[3 * i] * dg[0] + K[3 * i + 1] * dg[1] + K[3 * i + 2] * dg[2],
                  1e-13, 1e-12);
    // Commit: elastic trial f_n,t + kt dg_t = 36 (c, s) + 500 (0.09, 0.04), outside 39: slip along
    // the trial (the direction follows the motion), on the cone.
    const double tr[2] = {36.0 * c + 45.0, 36.0 * sn + 20.0}, ntr = std::hypot(tr[0], tr[1]);
    ContactLaggedCommit(p, s, g, f, &s);
    CHECK(s.status == CONTACT_SLIP, "trial %g outside 39 stays slip", ntr);
    CHECK_CLOSE(s.f[0], 39.0 * tr[0] / ntr, tol, 0.0);
    CHECK_CLOSE(s.f[1], 39.0 * tr[1] / ntr, tol, 0.0);
  }
  const double c4 = s.f[0] / 39.0, s4 = s.f[1] / 39.0;  // committed slip direction
  // 5. Slip ignores tangential motion (thesis law: f_t follows the normal force only), even when
  //    the node reverses.
  {
    const double g[3] = {0.0, -0.2, -0.13};
    ContactLaggedForce(p, s, g, f, K);
    CHECK_CLOSE(f[0], 39.0 * c4, tol, 0.0);
    CHECK_CLOSE(f[1], 39.0 * s4, tol, 0.0);
    CHECK(K[0] == 0.0 && K[1] == 0.0 && K[3] == 0.0 && K[4] == 0.0, "no tangential stiffness");
  }
  // 6. Normal unloading in slip slides down the cone.
  {
    const double g[3] = {0.2, 0.1, -0.10};  // dw = +0.03
    ContactLaggedForce(p, s, g, f, K);
    CHECK_CLOSE(f[2], -100.0, tol, 0.0);
    CHECK_CLOSE(f[0], 30.0 * c4, tol, 0.0);
    CHECK_CLOSE(f[1], 30.0 * s4, tol, 0.0);
    ContactLaggedCommit(p, s, g, f, &s);
    CHECK(s.status == CONTACT_SLIP, "no tangential motion, trial 39 outside 30: still slip");
    CHECK_CLOSE(s.f[0], 30.0 * c4, tol, 0.0);
  }
  // 7. Lift-off within the step (f_z would become >= 0): zero force and tangent, then OPEN.
  {
    const double g[3] = {0.3, 0.1, 0.01};
    ContactLaggedForce(p, s, g, f, K);
    CHECK(MaxAbs(f, 3) == 0.0 && MaxAbs(K, 9) == 0.0, "lift-off: zero force and tangent");
    ContactLaggedCommit(p, s, g, f, &s);
    CHECK(s.status == CONTACT_OPEN, "lift-off commits OPEN, got %d", s.status);
    CHECK(MaxAbs(s.f, 3) == 0.0, "open pair has no force");
  }
  // 8. An open pair is force-free for the step even if it penetrates; the commit re-closes it,
  //    sticking, with the normal spring force at the converged gap.
  {
    const double g[3] = {0.3, 0.1, -0.02};
    ContactLaggedForce(p, s, g, f, K);
    CHECK(MaxAbs(f, 3) == 0.0 && MaxAbs(K, 9) == 0.0, "open: zero force within the step");
    ContactLaggedCommit(p, s, g, f, &s);
    CHECK(s.status == CONTACT_STICK, "re-closed pair sticks, got %d", s.status);
    CHECK_CLOSE(s.f[2], -20.0, tol, 0.0);
    CHECK(s.f[0] == 0.0 && s.f[1] == 0.0, "no tangential memory on re-closing");
  }
  // 9. Stick loading inside the cone, then tangential unloading: |f_t| decreases linearly.
  {
    const double g[3] = {0.31, 0.1, -0.05};
    ContactLaggedForce(p, s, g, f, K);
    CHECK_CLOSE(f[0], 5.0, 1e-12, 0.0);
    CHECK_CLOSE(f[2], -50.0, tol, 0.0);
    ContactLaggedCommit(p, s, g, f, &s);
    CHECK(s.status == CONTACT_STICK, "5 < 15: stick");
    const double g2[3] = {0.305, 0.1, -0.05};
    ContactLaggedForce(p, s, g2, f, K);
    CHECK_CLOSE(f[0], 2.5, 1e-11, 0.0);
    CHECK(std::hypot(f[0], f[1]) < 5.0, "unloading reduces |f_t|");
    const double g3[3] = {0.29, 0.1, -0.05};
    ContactLaggedForce(p, s, g3, f, K);
    CHECK_CLOSE(f[0], -5.0, 1e-11, 0.0);
  }
}

// Lagged law, stick -> slip -> stick (thesis Fig. 4.4 narrative): a pair pushed past the cone
// slips; once its motion stops while the pressure grows, the elastic trial falls inside the cone
// and it sticks again, its force then following the springs (4.27).
// kn = 1000, kt = 500, mu = 0.3, pressed to f_z = -100 (limit 30).
void TestLaggedStickSlipStick() {
  const ContactParameters p{1000.0, 500.0, 0.3};
  ContactState s = State(0, 0, -0.1, 0, 0, -100.0, CONTACT_STICK);
  double f[3], K[9];
  const double tol = 1e-13;
  int statuses[5], k = 0;
  // Stick springs overshoot (50 > 30): slip, corrected onto the cone.
  {
    const double g[3] = {0.1, 0.0, -0.1};
    ContactLaggedForce(p, s, g, f, K);
    CHECK_CLOSE(f[0], 50.0, tol, 0.0);
    ContactLaggedCommit(p, s, g, f, &s);
    CHECK_CLOSE(s.f[0], 30.0, tol, 0.0);
    statuses[k++] = s.status;
  }
  // Sliding on: the slip law (no tangential stiffness), trial 30 + 500 * 0.1 = 80 > 30: slip.
  {
    const double g[3] = {0.2, 0.0, -0.1};
    ContactLaggedForce(p, s, g, f, K);
    CHECK(K[0] == 0.0 && K[4] == 0.0, "slip step: no tangential stiffness");
    CHECK_CLOSE(f[0], 30.0, tol, 0.0);
    ContactLaggedCommit(p, s, g, f, &s);
    CHECK_CLOSE(s.f[0], 30.0, tol, 0.0);
    statuses[k++] = s.status;
  }
  // The node stops, the pressure grows to 120 (limit 36): the slip law gives 36 along x, the
  // trial stays 30 < 36: stick again, keeping the force it converged with (no jump).
  {
    const double g[3] = {0.2, 0.0, -0.12};
    ContactLaggedForce(p, s, g, f, K);
    CHECK_CLOSE(f[0], 36.0, tol, 0.0);
    CHECK_CLOSE(f[2], -120.0, tol, 0.0);
    ContactLaggedCommit(p, s, g, f, &s);
    CHECK_CLOSE(s.f[0], 36.0, tol, 0.0);
    CHECK_CLOSE(s.f[2], -120.0, tol, 0.0);
    statuses[k++] = s.status;
  }
  // Sticking: the springs carry the next (backward) motion, 36 - 500 * 0.01 = 31 < 36, stick.
  {
    const double g[3] = {0.19, 0.0, -0.12};
    ContactLaggedForce(p, s, g, f, K);
    CHECK(K[0] == 500.0 && K[4] == 500.0, "stick step: tangential springs");
    CHECK_CLOSE(f[0], 31.0, 1e-12, 0.0);
    ContactLaggedCommit(p, s, g, f, &s);
    CHECK_CLOSE(s.f[0], 31.0, 1e-12, 0.0);
    statuses[k++] = s.status;
  }
  // And past the cone again (31 + 20 = 51 > 36): slip.
  {
    const double g[3] = {0.23, 0.0, -0.12};
    ContactLaggedForce(p, s, g, f, K);
    ContactLaggedCommit(p, s, g, f, &s);
    CHECK_CLOSE(s.f[0], 36.0, tol, 0.0);
    statuses[k++] = s.status;
  }
  const int want[5] = {CONTACT_SLIP, CONTACT_SLIP, CONTACT_STICK, CONTACT_STICK, CONTACT_SLIP};
  for (int i = 0; i < 5; ++i) CHECK(statuses[i] == want[i], "commit %d: status %d, want %d", i, statuses[i], want[i]);
}

// Lagged law, slip reversal: a pair sliding in +x whose node turns back sticks (trial inside the
// cone, or pointing back), its springs unload through zero and it slips in -x with its force on
// the other side of the cone; a sideways turn rotates the slip direction toward the motion (it no
// longer stays frozen at the first slip).
void TestLaggedReversal() {
  const ContactParameters p{1000.0, 500.0, 0.3};
  const ContactState sliding = State(0.2, 0, -0.1, 30.0, 0, -100.0, CONTACT_SLIP);  // in +x
  ContactState s = sliding;
  double f[3], K[9];
  const double tol = 1e-13;
  {
    // Back by 0.05: the step's slip law keeps +30, the trial 30 - 25 = 5 is inside: stick, with
    // the converged force.
    const double g[3] = {0.15, 0.0, -0.1};
    ContactLaggedForce(p, s, g, f, K);
    CHECK_CLOSE(f[0], 30.0, tol, 0.0);
    ContactLaggedCommit(p, s, g, f, &s);
    CHECK(s.status == CONTACT_STICK, "reversal: sticks first, got %d", s.status);
    CHECK_CLOSE(s.f[0], 30.0, tol, 0.0);
  }
  {
    // Back by 0.1 more: springs 30 - 50 = -20, inside: stick.
    const double g[3] = {0.05, 0.0, -0.1};
    ContactLaggedForce(p, s, g, f, K);
    CHECK_CLOSE(f[0], -20.0, 1e-12, 0.0);
    ContactLaggedCommit(p, s, g, f, &s);
    CHECK(s.status == CONTACT_STICK, "unloading through zero: stick, got %d", s.status);
  }
  {
    // Back by 0.05 more: -20 - 25 = -45, past -30: slip in -x, on the cone.
    const double g[3] = {0.0, 0.0, -0.1};
    ContactLaggedForce(p, s, g, f, K);
    ContactLaggedCommit(p, s, g, f, &s);
    CHECK(s.status == CONTACT_SLIP && std::fabs(s.f[0] + 30.0) <= 1e-12 * 30.0 && s.f[1] == 0.0,
          "reversed slip: f = (-30, 0), got (%g, %g) status %d", s.f[0], s.f[1], s.status);
  }
  {
    // Sideways while slipping in -x: trial (-30, 500 * 0.1) turns the slip direction.
    const double g[3] = {0.0, 0.1, -0.1};
    ContactLaggedForce(p, s, g, f, K);
    CHECK_CLOSE(f[0], -30.0, tol, 0.0);
    CHECK(f[1] == 0.0, "within the step the direction is the committed one (4.28)");
    ContactLaggedCommit(p, s, g, f, &s);
    const double n = std::hypot(30.0, 50.0);
    CHECK(s.status == CONTACT_SLIP, "sideways: slip");
    CHECK_CLOSE(s.f[0], -30.0 * 30.0 / n, tol, 0.0);
    CHECK_CLOSE(s.f[1], 30.0 * 50.0 / n, tol, 0.0);
  }
  {
    // A large turn-back within one slip step (trial 30 - 100 = -70, outside but pointing back)
    // sticks with the converged force; the next step's springs (30 - 100) send it into slip in -x.
    s = sliding;
    const double g[3] = {0.0, 0.0, -0.1};
    ContactLaggedForce(p, s, g, f, K);
    ContactLaggedCommit(p, s, g, f, &s);
    CHECK(s.status == CONTACT_STICK && s.f[0] == 30.0, "turned back: stick at +30, got %d, %g", s.status, s.f[0]);
    const double g2[3] = {-0.2, 0.0, -0.1};
    ContactLaggedForce(p, s, g2, f, K);
    ContactLaggedCommit(p, s, g2, f, &s);
    CHECK(s.status == CONTACT_SLIP && std::fabs(s.f[0] + 30.0) <= 1e-12 * 30.0, "then slips in -x, got %d, %g",
          s.status, s.f[0]);
  }
}

// A random gap history (stick, slip, reversals, lift-offs): the committed force is inside or on
// the cone, a slip commit puts it on the cone, a pair that sticks keeps the force it converged
// with, and the history shows what the frozen law never did: slipping pairs that stick again and
// slip directions that turn.
void TestLaggedRandomHistory() {
  Rng rng;
  const ContactParameters p{1e5, 3e4, 0.4};
  int n_restick = 0, n_turn = 0, n_slip = 0, bad_cone = 0, bad_keep = 0;
  ContactState s = State(0, 0, 0, 0, 0, 0, CONTACT_STICK);
  double g[3] = {0, 0, -1e-4};
  for (int it = 0; it < 10000; ++it) {
    for (int i = 0; i < 2; ++i) g[i] += rng.Range(-1, 1) * 2e-4;
    g[2] = std::min(g[2] + rng.Range(-1, 0.9) * 5e-5, 2e-5);
    double f[3];
    const ContactState before = s;
    ContactLaggedForce(p, s, g, f, nullptr);
    ContactLaggedCommit(p, s, g, f, &s);
    if (s.status == CONTACT_OPEN) continue;
    const double limit = p.mu * std::fabs(s.f[2]), ft = std::hypot(s.f[0], s.f[1]);
    if (ft > limit * (1 + 1e-12)) ++bad_cone;
    if (s.status == CONTACT_SLIP) {
      ++n_slip;
      if (std::fabs(ft - limit) > 1e-12 * limit) ++bad_cone;
    } else if (f[2] < 0.0 && (s.f[0] != f[0] || s.f[1] != f[1])) {
      ++bad_keep;
    }
    if (before.status == CONTACT_SLIP && s.status == CONTACT_STICK) ++n_restick;
    if (before.status == CONTACT_SLIP && s.status == CONTACT_SLIP) {
      const double c = (before.f[0] * s.f[0] + before.f[1] * s.f[1]) /
                       (std::hypot(before.f[0], before.f[1]) * ft);
      if (c < std::cos(kPi / 180.0)) ++n_turn;
    }
  }
  CHECK(bad_cone == 0, "%d commits off the cone", bad_cone);
  CHECK(bad_keep == 0, "%d sticking commits changed the converged force", bad_keep);
  CHECK(n_slip > 200 && n_restick > 50 && n_turn > 50, "coverage slip %d slip->stick %d turns %d", n_slip,
        n_restick, n_turn);
  std::printf("lagged random history: 10000 steps, %d slip commits, %d slip->stick, %d slip directions turned "
              "by > 1 deg\n", n_slip, n_restick, n_turn);
}

// Lagged special cases: slip with no committed direction, frictionless, no lift-off when the
// compression stays.
void TestLaggedSpecial() {
  double f[3], K[9];
  {
    // Slip with f_t = 0 and mu > 0 (a pair that starts at f = 0): tangential springs this step.
    const ContactParameters p{1000.0, 500.0, 0.3};
    const ContactState s = State(0, 0, 0, 0, 0, -10.0, CONTACT_SLIP);
    const double g[3] = {0.01, -0.02, -0.01};
    ContactLaggedForce(p, s, g, f, K);
    CHECK_CLOSE(f[0], 5.0, 1e-13, 0.0);
    CHECK_CLOSE(f[1], -10.0, 1e-13, 0.0);
    CHECK_CLOSE(f[2], -20.0, 1e-13, 0.0);
    CHECK(K[0] == 500.0 && K[4] == 500.0 && K[8] == 1000.0 && K[2] == 0.0 && K[5] == 0.0,
          "stick tangent for an undirected slip");
    ContactState n;
    ContactLaggedCommit(p, s, g, f, &n);
    CHECK(n.status == CONTACT_SLIP && InsideCone(p, n.f), "commit projects it");
  }
  {
    // Frictionless: the commit is always slip with f_t = 0 and the force has no f_t.
    const ContactParameters p{1000.0, 500.0, 0.0};
    ContactState s = State(0, 0, 0, 0, 0, 0, CONTACT_STICK);
    const double g[3] = {0.01, 0.0, -0.01};
    ContactLaggedForce(p, s, g, f, K);
    ContactLaggedCommit(p, s, g, f, &s);
    CHECK(s.status == CONTACT_SLIP && s.f[0] == 0.0 && s.f[1] == 0.0, "mu = 0 commits f_t = 0");
    const double g2[3] = {0.5, -0.3, -0.02};
    ContactLaggedForce(p, s, g2, f, K);
    CHECK(f[0] == 0.0 && f[1] == 0.0, "mu = 0 slip: f_t = 0");
    CHECK(K[0] == 0.0 && K[4] == 0.0 && K[2] == 0.0 && K[5] == 0.0, "mu = 0: no tangential K");
    CHECK_CLOSE(f[2], -20.0, 1e-13, 0.0);
  }
}

// After the commit the force is inside or on the cone, on the cone with its direction kept when
// it overshot, and zero when open.
void TestCommitCone() {
  Rng rng;
  int n_open = 0, n_reclose = 0, n_stick = 0, n_slip = 0;
  for (int it = 0; it < 20000; ++it) {
    const double kn = std::pow(10.0, rng.Range(2, 13));
    const double mu = rng.Uniform() < 0.1 ? 0.0 : rng.Range(0.0, 1.5);
    const ContactParameters p{kn, kn, mu};
    const double F = std::pow(10.0, rng.Range(-4, 4));
    const double f[3] = {rng.Range(-2, 2) * F, rng.Range(-2, 2) * F, rng.Range(-2, 0.5) * F};
    const double g[3] = {rng.Range(-1, 1) * F / kn, rng.Range(-1, 1) * F / kn,
                         rng.Range(-1, 1) * F / kn};
    // From a sticking state the trial is the converged force itself.
    ContactState s = State(0, 0, 0, rng.Range(-1, 1) * F, 0, -F, CONTACT_STICK);
    ContactLaggedCommit(p, s, g, f, &s);
    CHECK(s.g[0] == g[0] && s.g[1] == g[1] && s.g[2] == g[2], "commit stores the gap");
    if (f[2] >= 0.0) {
      if (g[2] < 0.0) {
        ++n_reclose;
        CHECK(s.status == CONTACT_STICK && s.f[0] == 0.0 && s.f[1] == 0.0 &&
                  s.f[2] == kn * g[2],
              "re-closing: stick with f = kn w normal");
      } else {
        ++n_open;
        CHECK(s.status == CONTACT_OPEN && MaxAbs(s.f, 3) == 0.0, "open: f = 0");
      }
      continue;
    }
    CHECK(InsideCone(p, s.f), "committed force outside the cone");
    CHECK(s.f[2] == f[2], "the normal force is not corrected");
    const double ft = std::hypot(f[0], f[1]);
    if (ft < mu * std::fabs(f[2])) {
      ++n_stick;
      CHECK(s.status == CONTACT_STICK && s.f[0] == f[0] && s.f[1] == f[1], "stick: unchanged");
    } else {
      ++n_slip;
      CHECK(s.status == CONTACT_SLIP, "overshoot must be slip");
      CHECK_CLOSE(std::hypot(s.f[0], s.f[1]), mu * std::fabs(f[2]), 1e-14, 1e-300);
      // Same direction: the cross product vanishes and the dot product is non-negative.
      CHECK(std::fabs(s.f[0] * f[1] - s.f[1] * f[0]) <= 1e-14 * ft * std::hypot(s.f[0], s.f[1]) &&
                s.f[0] * f[0] + s.f[1] * f[1] >= 0.0,
            "projection keeps the direction");
    }
  }
  CHECK(n_open > 100 && n_reclose > 100 && n_stick > 1000 && n_slip > 1000,
        "coverage open %d re-close %d stick %d slip %d", n_open, n_reclose, n_stick, n_slip);
  std::printf("commit cone: 20000 random forces (open %d, re-close %d, stick %d, slip %d)\n",
              n_open, n_reclose, n_stick, n_slip);

  // A long lagged history: the committed force never leaves the cone.
  const ContactParameters p{1e5, 3e4, 0.4};
  ContactState s = State(0, 0, 0, 0, 0, 0, CONTACT_STICK);
  double g[3] = {0, 0, 0};
  int bad = 0;
  for (int it = 0; it < 5000; ++it) {
    for (int i = 0; i < 2; ++i) g[i] += rng.Range(-1, 1) * 1e-4;
    g[2] = std::min(g[2] + rng.Range(-1.2, 1) * 1e-4, 1e-4);
    double f[3], K[9];
    ContactLaggedForce(p, s, g, f, K);
    ContactLaggedCommit(p, s, g, f, &s);
    if (s.status != CONTACT_OPEN && !InsideCone(p, s.f)) ++bad;
  }
  CHECK(bad == 0, "%d committed forces outside the cone in a random history", bad);
}

// ---------------------------------------------------------------------------------------------
void TestFixed() {
  Rng rng;
  const ContactParameters p{1e9, 2e7, 0.3};
  for (int it = 0; it < 100; ++it) {
    const double g[3] = {rng.Range(-1, 1), rng.Range(-1, 1), rng.Range(-1, 1)};
    const double a = rng.Range(-3, 3);
    const double ga[3] = {a * g[0], a * g[1], a * g[2]};
    double f[3], fa[3], K[9];
    ContactFixedForce(p, g, f, K);
    ContactFixedForce(p, ga, fa, nullptr);
    CHECK(f[0] == p.kt * g[0] && f[1] == p.kt * g[1] && f[2] == p.kn * g[2], "f = diag g");
    for (int i = 0; i < 3; ++i) CHECK_CLOSE(fa[i], a * f[i], 1e-15, 1e-300);
    const double Kf[9] = {p.kt, 0, 0, 0, p.kt, 0, 0, 0, p.kn};
    for (int i = 0; i < 9; ++i) CHECK(K[i] == Kf[i], "fixed tangent entry %d", i);
  }
  // No lift-off: a positive gap pulls back.
  const double g[3] = {0, 0, 1e-6};
  double f[3], K[9];
  ContactFixedForce(p, g, f, K);
  CHECK(f[2] > 0.0, "fixed support holds the node in tension too");
}

// ---------------------------------------------------------------------------------------------
// Block on a plane: pressed by w = -d, pushed tangentially by g_x in small steps.
void TestBlockOnPlane() {
  const ContactParameters p{1e6, 1e5, 0.3};
  const double d = 1e-4;                  // f_z = -100 N, Coulomb limit 30 N at g_x = 3e-4
  const double limit = p.mu * p.kn * d;
  // 199 steps: the limit falls between two steps, so the lagged law does overshoot.
  const int steps = 199;
  const double h = 1e-3 / steps;          // kt h ~ 0.5 N: the lagged law's one-step lag
  ContactState imp = State(0, 0, 0, 0, 0, 0, CONTACT_OPEN);
  ContactState lag = State(0, 0, -d, 0, 0, -p.kn * d, CONTACT_STICK);
  int imp_bad = 0, lag_bad = 0, lag_commit_bad = 0;
  double max_lag = 0.0;
  for (int k = 1; k <= steps; ++k) {
    const double g[3] = {k * h, 0.0, -d};
    const double exact = std::min(p.kt * g[0], limit);
    double f[3], K[9];
    const int st = ContactImplicitForce(p, imp, g, f, K);
    if (std::fabs(f[0] - exact) > 1e-12 * limit || f[1] != 0.0) ++imp_bad;
    imp = State(g[0], g[1], g[2], f[0], f[1], f[2], st);  // the implicit law commits what it found

    // Single shot from the untouched state gives the same force (path independence).
    if (k == steps) {
      const ContactState fresh = State(0, 0, 0, 0, 0, 0, CONTACT_OPEN);
      double f1[3];
      ContactImplicitForce(p, fresh, g, f1, nullptr);
      CHECK_CLOSE(f1[0], limit, 1e-12, 0.0);
    }

    ContactLaggedForce(p, lag, g, f, K);
    const double over = f[0] - exact;
    max_lag = std::max(max_lag, over);
    if (over < -1e-12 * limit || over > p.kt * h * (1 + 1e-9)) ++lag_bad;
    ContactLaggedCommit(p, lag, g, f, &lag);
    if (std::fabs(lag.f[0] - exact) > 1e-12 * limit) ++lag_commit_bad;
  }
  CHECK(imp_bad == 0, "implicit differs from min(kt g_x, mu kn d) in %d steps", imp_bad);
  CHECK(lag_bad == 0, "lagged force outside [exact, exact + kt h] in %d steps", lag_bad);
  CHECK(lag_commit_bad == 0, "committed lagged force differs from Coulomb in %d steps",
        lag_commit_bad);
  CHECK(lag.status == CONTACT_SLIP && imp.status == CONTACT_SLIP, "both end sliding");
  CHECK(max_lag > 0.0 && max_lag <= p.kt * h * (1 + 1e-9), "lagged overshoot %g (bound %g)",
        max_lag, p.kt * h);
  std::printf("block on a plane: Coulomb limit %g N, lagged overshoot %g N (one step = %g N)\n",
              limit, max_lag, p.kt * h);
}

} // namespace

// A lagged step from s to the gap g, committed by the thesis's rule and by the settled one.
void BothCommits(const ContactParameters &p, const ContactState &s, const double g[3], ContactState *plain,
                 ContactState *settled) {
  double f[3];
  ContactLaggedForce(p, s, g, f, nullptr);
  ContactLaggedCommit(p, s, g, f, plain);
  ContactLaggedCommitSettled(p, s, g, f, settled);
}

// Lagged law solved to a status fixed point (-contact_lagged_repeat): which law a step runs, the
// state a step is solved again from, and the commit that keeps a slipping pair's direction.
// kn = 1000, kt = 500, mu = 0.3.
void TestLaggedSettled() {
  const ContactParameters p{1000.0, 500.0, 0.3};
  const double tol = 1e-13;
  // Only a directed slip with friction runs the slip law.
  CHECK(ContactLaggedRunsSlip(p, State(0, 0, 0, 30, 0, -100, CONTACT_SLIP)), "directed slip runs 4.29");
  CHECK(!ContactLaggedRunsSlip(p, State(0, 0, 0, 0, 0, -100, CONTACT_SLIP)), "slip without direction: springs");
  CHECK(!ContactLaggedRunsSlip(p, State(0, 0, 0, 10, 0, -100, CONTACT_STICK)), "stick: springs");
  CHECK(!ContactLaggedRunsSlip(ContactParameters{1000.0, 500.0, 0.0}, State(0, 0, 0, 1, 0, -100, CONTACT_SLIP)),
        "frictionless: no slip law");

  // Restart in slip: the start's tangential force (10, 0) raised to the cone of its pressure,
  // 0.3 * 100 = 30, along the direction the commit found (3, 4) -> (18, 24); g and f_z kept.
  const ContactState start = State(0.5, 0.25, -0.1, 10, 0, -100, CONTACT_STICK);
  ContactState step;
  const double dir[2] = {3.0, 4.0};
  ContactLaggedRestartState(p, start, CONTACT_SLIP, dir, &step);
  CHECK(step.status == CONTACT_SLIP, "restart status slip");
  CHECK_CLOSE(step.f[0], 18.0, tol, 0.0);
  CHECK_CLOSE(step.f[1], 24.0, tol, 0.0);
  CHECK_CLOSE(step.f[2], -100.0, tol, 0.0);
  CHECK(step.g[0] == 0.5 && step.g[1] == 0.25 && step.g[2] == -0.1, "restart keeps the start's gap");
  // The slip law from there keeps the force on the cone through the step: pressed to 120 -> 36.
  {
    const double g[3] = {0.9, 0.0, -0.12};
    double f[3];
    ContactLaggedForce(p, step, g, f, nullptr);
    CHECK_CLOSE(std::hypot(f[0], f[1]), 36.0, tol, 0.0);
  }
  // Restart in stick: the start as it was; no direction or no pressure: tangential force kept.
  ContactLaggedRestartState(p, State(0.5, 0, -0.1, 30, 0, -100, CONTACT_SLIP), CONTACT_STICK, dir, &step);
  CHECK(step.status == CONTACT_STICK && step.f[0] == 30.0 && step.f[1] == 0.0, "restart in stick: the start");
  const double none[2] = {0.0, 0.0};
  ContactLaggedRestartState(p, start, CONTACT_SLIP, none, &step);
  CHECK(step.status == CONTACT_SLIP && step.f[0] == 10.0 && step.f[1] == 0.0, "no direction: force kept");
  ContactLaggedRestartState(p, State(0, 0, 0, 0, 0, 0, CONTACT_STICK), CONTACT_SLIP, dir, &step);
  CHECK(step.f[0] == 0.0 && step.f[1] == 0.0, "no pressure: force kept");

  // Settled commit: a pair slipping along x whose step moved it sideways as well keeps the
  // direction x and the converged force; the thesis's commit turns it toward the trial.
  ContactState plain, settled;
  {
    const double g[3] = {0.1, 0.1, -0.1};
    BothCommits(p, State(0, 0, -0.1, 30, 0, -100, CONTACT_SLIP), g, &plain, &settled);
    CHECK(plain.status == CONTACT_SLIP && settled.status == CONTACT_SLIP, "both slip on");
    CHECK(plain.f[1] > 1.0, "the thesis's commit follows the trial sideways (%g)", plain.f[1]);
    CHECK_CLOSE(settled.f[0], 30.0, tol, 0.0);
    CHECK(settled.f[1] == 0.0, "the settled commit keeps the direction");
  }
  // Otherwise the settled commit is the thesis's: a stick overshoot is projected along its force,
  // a reversal sticks.
  {
    const double g[3] = {0.1, 0.0, -0.1}, back[3] = {-0.1, 0.0, -0.1};
    BothCommits(p, State(0, 0, -0.1, 0, 0, -100, CONTACT_STICK), g, &plain, &settled);
    CHECK(settled.status == plain.status && settled.f[0] == plain.f[0] && settled.f[1] == plain.f[1],
          "stick step: the same commit");
    BothCommits(p, State(0, 0, -0.1, 30, 0, -100, CONTACT_SLIP), back, &plain, &settled);
    CHECK(settled.status == CONTACT_STICK && plain.status == CONTACT_STICK, "reversal sticks");
  }
}

int main() {
  TestImplicitTangent();
  TestImplicitSlipTangentForm();
  TestImplicitCone();
  TestImplicitReclose();
  TestLaggedSequence();
  TestLaggedStickSlipStick();
  TestLaggedReversal();
  TestLaggedRandomHistory();
  TestLaggedSpecial();
  TestLaggedSettled();
  TestCommitCone();
  TestFixed();
  TestBlockOnPlane();
  TEST_MAIN_END();
}
