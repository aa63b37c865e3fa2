// Membrane element kernels (src/kernels/membrane.cpp) with the elastic law
// (src/kernels/elastic.cpp): tangent = derivative of the force, objectivity, exact strains of
// homogeneous deformations, degenerate input, the MD frame rule, output measures, equilibrium.
#include "etfe/kernels/elastic.h"
#include "etfe/kernels/membrane.h"
#include "etfe/kernels/status.h"

#include "check.h"
#include "fd_tangent.h"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>

namespace {

using etfe::MembraneReference;

const double kX[3] = {1.0, 0.0, 0.0};
constexpr double kYoung = 800.0;  // ETFE, MPa
constexpr double kNu = 0.43;
constexpr double kH = 0.25;  // mm

double Dot(const double *a, const double *b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

void Cross(const double *a, const double *b, double *c) {
  c[0] = a[1] * b[2] - a[2] * b[1];
  c[1] = a[2] * b[0] - a[0] * b[2];
  c[2] = a[0] * b[1] - a[1] * b[0];
}

// A random, not too flat triangle of size ~scale around a random centre.
void RandomTriangle(Rng &rng, double scale, double X[9]) {
  for (;;) {
    double c[3];
    for (int i = 0; i < 3; ++i) c[i] = 10.0 * scale * rng.Next();
    for (int k = 0; k < 9; ++k) X[k] = c[k % 3] + scale * rng.Next();
    double a[3], b[3], n[3];
    for (int i = 0; i < 3; ++i) {
      a[i] = X[3 + i] - X[i];
      b[i] = X[6 + i] - X[i];
    }
    Cross(a, b, n);
    // Keep triangles whose area is a fair fraction of the longest edge squared.
    const double l2 = std::fmax(Dot(a, a), Dot(b, b));
    if (std::sqrt(Dot(n, n)) > 0.2 * l2) return;
  }
}

// Rotation matrix (row-major) about a random axis by a random finite angle (Rodrigues).
void RandomRotation(Rng &rng, double Q[9]) {
  double k[3] = {rng.Next(), rng.Next(), rng.Next()};
  const double kn = std::sqrt(Dot(k, k));
  for (int i = 0; i < 3; ++i) k[i] /= kn;
  const double th = 3.0 * rng.Next();
  const double c = std::cos(th), s = std::sin(th);
  const double K[9] = {0, -k[2], k[1], k[2], 0, -k[0], -k[1], k[0], 0};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      double kk = 0.0;
      for (int m = 0; m < 3; ++m) kk += K[3 * i + m] * K[3 * m + j];
      Q[3 * i + j] = (i == j ? 1.0 : 0.0) + s * K[3 * i + j] + (1.0 - c) * kk;
    }
}

void Rotate(const double Q[9], const double *v, double *w) {
  for (int i = 0; i < 3; ++i) w[i] = Q[3 * i] * v[0] + Q[3 * i + 1] * v[1] + Q[3 * i + 2] * v[2];
}

// Stress laws used to build f(x) = force(S(E(x))) and its exact tangent.
enum class Law { kFixed, kAffine, kElastic };

struct Setup {
  MembraneReference ref;
  Law law;
  double S0[3];  // fixed part of the stress
  double D[9];   // dS/dE (kAffine: any matrix, not necessarily symmetric)
};

void Evaluate(const Setup &st, const double x[9], double f[9], double K[81]) {
  double F[6], E[3], S[3], D[9];
  etfe::MembraneKinematics(st.ref, x, F, E);
  const double *Dp = nullptr;
  switch (st.law) {
  case Law::kFixed:
    for (int i = 0; i < 3; ++i) S[i] = st.S0[i];
    break;
  case Law::kAffine:
    for (int i = 0; i < 3; ++i)
      S[i] = st.S0[i] + st.D[3 * i] * E[0] + st.D[3 * i + 1] * E[1] + st.D[3 * i + 2] * E[2];
    Dp = st.D;
    break;
  case Law::kElastic:
    etfe::ElasticPlaneStress(kYoung, kNu, E, S, D);
    Dp = D;
    break;
  }
  etfe::MembraneForce(st.ref, kH, F, S, Dp, f, K);
}

// max |K - K_fd| / max |K| with central differences of f.
double TangentError(const Setup &st, const double x[9], double scale) {
  double f[9], K[81], Kfd[81];
  Evaluate(st, x, f, K);
  etfe_test::CentralDifferenceJacobian([&](const double *y, double *fy) { Evaluate(st, y, fy, nullptr); }, x, 9, 9,
                                       1e-5 * scale, Kfd);
  double diff[81];
  for (int k = 0; k < 81; ++k) diff[k] = K[k] - Kfd[k];
  return MaxAbs(diff, 81) / MaxAbs(K, 81);
}

void TestTangent(Rng &rng) {
  for (int trial = 0; trial < 12; ++trial) {
    const double scale = trial % 2 ? 1.0 : 500.0;  // unit and saddle-sized (mm) elements
    double X[9], x[9];
    RandomTriangle(rng, scale, X);
    Setup st;
    const double md[3] = {rng.Next(), rng.Next(), rng.Next()};
    CHECK(etfe::MembraneReferenceBuild(X, md, 0.0, &st.ref) == etfe::KERNEL_OK, "trial %d", trial);
    // Finite deformation: displacements ~20 % of the element size.
    for (int k = 0; k < 9; ++k) x[k] = X[k] + 0.2 * scale * rng.Next();
    for (int i = 0; i < 3; ++i) st.S0[i] = 10.0 * rng.Next();

    st.law = Law::kFixed;  // constant S: only the geometric term survives (D = nullptr)
    double err = TangentError(st, x, scale);
    CHECK(err < 1e-6, "trial %d fixed S: rel. error %g", trial, err);

    st.law = Law::kAffine;  // S = S0 + D E with D the elastic tangent
    etfe::ElasticPlaneStressTangent(kYoung, kNu, st.D);
    err = TangentError(st, x, scale);
    CHECK(err < 1e-6, "trial %d affine elastic D: rel. error %g", trial, err);

    // A non-symmetric D (like a non-associated or lagged tangent) must be used as given.
    for (int k = 0; k < 9; ++k) st.D[k] = 500.0 * rng.Next();
    err = TangentError(st, x, scale);
    CHECK(err < 1e-6, "trial %d affine random D: rel. error %g", trial, err);

    st.law = Law::kElastic;  // full residual -> tangent consistency through ElasticPlaneStress
    err = TangentError(st, x, scale);
    CHECK(err < 1e-6, "trial %d elastic law: rel. error %g", trial, err);

    // Symmetric D gives a symmetric tangent.
    double f[9], K[81];
    Evaluate(st, x, f, K);
    double asym = 0.0;
    for (int r = 0; r < 9; ++r)
      for (int c = 0; c < r; ++c) asym = std::fmax(asym, std::fabs(K[9 * r + c] - K[9 * c + r]));
    CHECK(asym <= 1e-13 * MaxAbs(K, 81), "trial %d: asymmetry %g", trial, asym);
  }
}

void TestRigidBody(Rng &rng) {
  for (int trial = 0; trial < 10; ++trial) {
    const double scale = trial % 2 ? 1.0 : 500.0;
    double X[9], x[9], Q[9], t[3];
    RandomTriangle(rng, scale, X);
    RandomRotation(rng, Q);
    for (int i = 0; i < 3; ++i) t[i] = 20.0 * scale * rng.Next();
    for (int a = 0; a < 3; ++a) {
      Rotate(Q, X + 3 * a, x + 3 * a);
      for (int i = 0; i < 3; ++i) x[3 * a + i] += t[i];
    }
    MembraneReference ref;
    CHECK(etfe::MembraneReferenceBuild(X, kX, 0.0, &ref) == etfe::KERNEL_OK, "trial %d", trial);
    double F[6], E[3], S[3], D[9], f[9], K[81];
    etfe::MembraneKinematics(ref, x, F, E);
    CHECK(MaxAbs(E, 3) < 1e-12, "trial %d: rigid motion strain %g", trial, MaxAbs(E, 3));
    etfe::ElasticPlaneStress(kYoung, kNu, E, S, D);
    etfe::MembraneForce(ref, kH, F, S, D, f, K);
    // Force scale of a unit strain: E h L.
    const double fscale = kYoung * kH * scale;
    CHECK(MaxAbs(f, 9) < 1e-12 * fscale, "trial %d: rigid motion force %g", trial,
          MaxAbs(f, 9) / fscale);
    CHECK(std::fabs(etfe::MembraneAreaRatio(ref, x, nullptr) - 1.0) < 1e-13, "trial %d", trial);

    // Objectivity of a stressed state: superposing a rotation keeps E and rotates f, K.
    double x1[9], x2[9];
    for (int k = 0; k < 9; ++k) x1[k] = X[k] + 0.1 * scale * rng.Next();
    for (int a = 0; a < 3; ++a) {
      Rotate(Q, x1 + 3 * a, x2 + 3 * a);
      for (int i = 0; i < 3; ++i) x2[3 * a + i] += t[i];
    }
    double F1[6], E1[3], S1[3], f1[9], K1[81], F2[6], E2[3], S2[3], f2[9], K2[81];
    etfe::MembraneKinematics(ref, x1, F1, E1);
    etfe::MembraneKinematics(ref, x2, F2, E2);
    for (int i = 0; i < 3; ++i) CHECK_CLOSE(E2[i], E1[i], 0.0, 1e-12);
    etfe::ElasticPlaneStress(kYoung, kNu, E1, S1, D);
    etfe::MembraneForce(ref, kH, F1, S1, D, f1, K1);
    etfe::ElasticPlaneStress(kYoung, kNu, E2, S2, D);
    etfe::MembraneForce(ref, kH, F2, S2, D, f2, K2);
    const double fmax = MaxAbs(f1, 9), kmax = MaxAbs(K1, 81);
    for (int a = 0; a < 3; ++a) {
      double qf[3];
      Rotate(Q, f1 + 3 * a, qf);
      for (int i = 0; i < 3; ++i) CHECK_CLOSE(f2[3 * a + i], qf[i], 0.0, 1e-10 * fmax);
      for (int b = 0; b < 3; ++b) {
        // Block K2_ab = Q K1_ab Q^T.
        for (int i = 0; i < 3; ++i)
          for (int j = 0; j < 3; ++j) {
            double v = 0.0;
            for (int m = 0; m < 3; ++m)
              for (int n = 0; n < 3; ++n)
                v += Q[3 * i + m] * K1[9 * (3 * a + m) + 3 * b + n] * Q[3 * j + n];
            CHECK_CLOSE(K2[9 * (3 * a + i) + 3 * b + j], v, 0.0, 1e-10 * kmax);
          }
      }
    }
  }
}

void TestHomogeneous(Rng &rng) {
  for (int trial = 0; trial < 6; ++trial) {
    double X[9];
    RandomTriangle(rng, trial % 2 ? 1.0 : 300.0, X);
    MembraneReference ref;
    CHECK(etfe::MembraneReferenceBuild(X, kX, 0.0, &ref) == etfe::KERNEL_OK, "trial %d", trial);
    const double *e1 = ref.frame, *e2 = ref.frame + 3, *e3 = ref.frame + 6;

    // At the reference configuration F = [e1 e2] and E = 0.
    double F[6], E[3];
    etfe::MembraneKinematics(ref, X, F, E);
    for (int i = 0; i < 3; ++i) {
      CHECK_CLOSE(F[2 * i], e1[i], 0.0, 1e-12);
      CHECK_CLOSE(F[2 * i + 1], e2[i], 0.0, 1e-12);
    }
    CHECK(MaxAbs(E, 3) < 1e-12, "reference strain %g", MaxAbs(E, 3));

    // Stretch by lambda along e1 (uniaxial), then biaxial lambda1, lambda2.
    const double l1 = 1.0 + 0.3 * (1.0 + rng.Next()), l2 = 1.0 + 0.2 * rng.Next();
    double x[9];
    for (int a = 0; a < 3; ++a) {
      double d[3];
      for (int i = 0; i < 3; ++i) d[i] = X[3 * a + i] - X[i];
      const double s1 = Dot(d, e1);
      for (int i = 0; i < 3; ++i) x[3 * a + i] = X[3 * a + i] + (l1 - 1.0) * s1 * e1[i];
    }
    etfe::MembraneKinematics(ref, x, F, E);
    CHECK_CLOSE(E[0], 0.5 * (l1 * l1 - 1.0), 1e-13, 1e-14);
    CHECK(std::fabs(E[1]) < 1e-13 && std::fabs(E[2]) < 1e-13, "uniaxial E = %g %g %g", E[0], E[1],
          E[2]);

    for (int a = 0; a < 3; ++a) {
      double d[3];
      for (int i = 0; i < 3; ++i) d[i] = X[3 * a + i] - X[i];
      const double s1 = Dot(d, e1), s2 = Dot(d, e2);
      for (int i = 0; i < 3; ++i)
        x[3 * a + i] = X[3 * a + i] + (l1 - 1.0) * s1 * e1[i] + (l2 - 1.0) * s2 * e2[i];
    }
    etfe::MembraneKinematics(ref, x, F, E);
    CHECK_CLOSE(E[0], 0.5 * (l1 * l1 - 1.0), 1e-13, 1e-14);
    CHECK_CLOSE(E[1], 0.5 * (l2 * l2 - 1.0), 1e-13, 1e-14);
    CHECK(std::fabs(E[2]) < 1e-13, "biaxial shear %g", E[2]);
    double n[3];
    CHECK_CLOSE(etfe::MembraneAreaRatio(ref, x, n), l1 * l2, 1e-13, 0.0);
    for (int i = 0; i < 3; ++i) CHECK_CLOSE(n[i], e3[i], 0.0, 1e-13);

    // Simple shear x = X + gamma (eta) e1: Exx = 0, Eyy = gamma^2/2, 2Exy = gamma.
    const double g = 0.4 * rng.Next();
    for (int a = 0; a < 3; ++a) {
      double d[3];
      for (int i = 0; i < 3; ++i) d[i] = X[3 * a + i] - X[i];
      const double s2 = Dot(d, e2);
      for (int i = 0; i < 3; ++i) x[3 * a + i] = X[3 * a + i] + g * s2 * e1[i];
    }
    etfe::MembraneKinematics(ref, x, F, E);
    CHECK(std::fabs(E[0]) < 1e-13, "shear Exx %g", E[0]);
    CHECK_CLOSE(E[1], 0.5 * g * g, 1e-12, 1e-14);
    CHECK_CLOSE(E[2], g, 1e-12, 1e-14);
  }

  // Hand case: unit right triangle in the XY plane, stretched 10 % in X: membrane force
  // N = S h per unit length on the edge x = 1 is carried by nodes 2 and 3 (lumped).
  {
    const double X[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    MembraneReference ref;
    CHECK(etfe::MembraneReferenceBuild(X, kX, 0.0, &ref) == etfe::KERNEL_OK, "hand case");
    CHECK_CLOSE(ref.area, 0.5, 1e-15, 0.0);
    const double S[3] = {10.0, 0.0, 0.0};
    const double x[9] = {0, 0, 0, 1.1, 0, 0, 0, 1, 0};
    double F[6], E[3], f[9];
    etfe::MembraneKinematics(ref, x, F, E);
    CHECK_CLOSE(E[0], 0.5 * (1.21 - 1.0), 1e-14, 0.0);
    etfe::MembraneForce(ref, kH, F, S, nullptr, f, nullptr);
    // f_a = h A0 F S gradN_a, gradN = (-1,-1), (1,0), (0,1); F S = [[1.1*10, 0], ...].
    CHECK_CLOSE(f[0], -kH * 0.5 * 11.0, 1e-14, 0.0);
    CHECK_CLOSE(f[3], kH * 0.5 * 11.0, 1e-14, 0.0);
    CHECK(f[6] == 0.0 && f[1] == 0.0 && f[4] == 0.0, "hand case off-axis forces");
  }
}

void TestDegenerate() {
  MembraneReference ref;
  const int kDeg = etfe::KERNEL_DEGENERATE;
  const double collinear[9] = {0, 0, 0, 1, 1, 1, 2, 2, 2};
  CHECK(etfe::MembraneReferenceBuild(collinear, kX, 1e-12, &ref) == kDeg, "collinear");
  CHECK(etfe::MembraneReferenceBuild(collinear, kX, 0.0, &ref) == kDeg, "collinear, min 0");
  // Collinear up to rounding: the cross product is not exactly zero.
  const double nearly[9] = {0.1, 0.3, 0.7, 0.2, 0.6, 1.4, 0.7, 2.1, 4.9};
  CHECK(etfe::MembraneReferenceBuild(nearly, kX, 0.0, &ref) == kDeg, "rounding-collinear");
  const double repeated[9] = {0, 0, 0, 1, 0, 0, 1, 0, 0};
  CHECK(etfe::MembraneReferenceBuild(repeated, kX, 0.0, &ref) == kDeg, "repeated node");
  const double all_same[9] = {3, 4, 5, 3, 4, 5, 3, 4, 5};
  CHECK(etfe::MembraneReferenceBuild(all_same, kX, 0.0, &ref) == kDeg, "all nodes equal");
  double bad[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  for (int k = 0; k < 9; ++k) {
    const double keep = bad[k];
    bad[k] = std::numeric_limits<double>::quiet_NaN();
    CHECK(etfe::MembraneReferenceBuild(bad, kX, 0.0, &ref) == kDeg, "NaN at %d", k);
    bad[k] = std::numeric_limits<double>::infinity();
    CHECK(etfe::MembraneReferenceBuild(bad, kX, 0.0, &ref) == kDeg, "Inf at %d", k);
    bad[k] = keep;
  }
  // The area threshold is absolute: a 0.5 mm^2 triangle passes 0.4 and fails 0.6.
  CHECK(etfe::MembraneReferenceBuild(bad, kX, 0.4, &ref) == etfe::KERNEL_OK, "area 0.5 > 0.4");
  CHECK(etfe::MembraneReferenceBuild(bad, kX, 0.6, &ref) == kDeg, "area 0.5 < 0.6");
  // A thin but honest sliver (aspect 1e6) is still accepted.
  const double sliver[9] = {0, 0, 0, 1, 0, 0, 0.5, 1e-6, 0};
  CHECK(etfe::MembraneReferenceBuild(sliver, kX, 0.0, &ref) == etfe::KERNEL_OK, "sliver");
}

void CheckFrameOrthonormal(const MembraneReference &ref, const double X[9]) {
  const double *e1 = ref.frame, *e2 = ref.frame + 3, *e3 = ref.frame + 6;
  CHECK_CLOSE(Dot(e1, e1), 1.0, 0.0, 1e-14);
  CHECK_CLOSE(Dot(e2, e2), 1.0, 0.0, 1e-14);
  CHECK_CLOSE(Dot(e3, e3), 1.0, 0.0, 1e-14);
  CHECK(std::fabs(Dot(e1, e2)) < 1e-14 && std::fabs(Dot(e1, e3)) < 1e-14 &&
            std::fabs(Dot(e2, e3)) < 1e-14,
        "frame not orthogonal");
  double a[3], b[3], n[3], c[3];
  for (int i = 0; i < 3; ++i) {
    a[i] = X[3 + i] - X[i];
    b[i] = X[6 + i] - X[i];
  }
  Cross(a, b, n);
  CHECK(Dot(n, e3) > 0.0, "e3 not along (X2-X1)x(X3-X1)");
  Cross(e1, e2, c);  // right-handed
  for (int i = 0; i < 3; ++i) CHECK_CLOSE(c[i], e3[i], 0.0, 1e-14);
}

void TestFrame(Rng &rng) {
  MembraneReference ref;
  // Plane containing global X (spanned by X and d = (0,1,2)/sqrt5): e1 = X exactly.
  {
    const double d[3] = {0.0, 1.0 / std::sqrt(5.0), 2.0 / std::sqrt(5.0)};
    const double p0[3] = {100.0, 200.0, 30.0};
    const double u[3] = {2.0, -0.3, 0.7}, v[3] = {0.5, 1.5, -0.2};  // in-plane (X, d) coords
    double X[9];
    for (int i = 0; i < 3; ++i) {
      X[i] = p0[i] + u[0] * kX[i] + v[0] * d[i];
      X[3 + i] = p0[i] + u[1] * kX[i] + v[1] * d[i];
      X[6 + i] = p0[i] + u[2] * kX[i] + v[2] * d[i];
    }
    CHECK(etfe::MembraneReferenceBuild(X, kX, 0.0, &ref) == etfe::KERNEL_OK, "plane with X");
    for (int i = 0; i < 3; ++i) CHECK_CLOSE(ref.frame[i], kX[i], 0.0, 1e-14);
    CheckFrameOrthonormal(ref, X);
  }
  // YZ plane: global X is the normal, so e1 falls back to the edge 1->2.
  {
    const double X[9] = {5.0, 0.0, 0.0, 5.0, 1.0, 0.5, 5.0, 0.2, 1.3};
    const double l = std::sqrt(1.25);
    for (int pass = 0; pass < 3; ++pass) {
      // Exactly normal, within the 1e-3 tolerance, and no MD axis at all.
      const double tilted[3] = {1.0, 5e-4, 0.0};
      const double *md = pass == 0 ? kX : pass == 1 ? tilted : nullptr;
      CHECK(etfe::MembraneReferenceBuild(X, md, 0.0, &ref) == etfe::KERNEL_OK, "YZ pass %d", pass);
      CHECK_CLOSE(ref.frame[0], 0.0, 0.0, 1e-14);
      CHECK_CLOSE(ref.frame[1], 1.0 / l, 0.0, 1e-14);
      CHECK_CLOSE(ref.frame[2], 0.5 / l, 0.0, 1e-14);
      CheckFrameOrthonormal(ref, X);
    }
    // Beyond the tolerance (sine 1e-2) the projection of md is used: e1 = +Y.
    const double md[3] = {1.0, 1e-2, 0.0};
    CHECK(etfe::MembraneReferenceBuild(X, md, 0.0, &ref) == etfe::KERNEL_OK, "YZ tilted md");
    CHECK_CLOSE(ref.frame[1], 1.0, 0.0, 1e-14);
  }
  // Generic planes: e1 is the normalised in-plane projection of X, pointing along +X.
  for (int trial = 0; trial < 10; ++trial) {
    double X[9];
    RandomTriangle(rng, 100.0, X);
    CHECK(etfe::MembraneReferenceBuild(X, kX, 0.0, &ref) == etfe::KERNEL_OK, "trial %d", trial);
    CheckFrameOrthonormal(ref, X);
    const double *e1 = ref.frame, *e3 = ref.frame + 6;
    double p[3];
    for (int i = 0; i < 3; ++i) p[i] = kX[i] - e3[0] * e3[i];
    const double pn = std::sqrt(Dot(p, p));
    for (int i = 0; i < 3; ++i) CHECK_CLOSE(e1[i], p[i] / pn, 0.0, 1e-13);
    // The shape-function gradients sum to zero (a constant field has no gradient).
    CHECK(std::fabs(ref.dNdx[0] + ref.dNdx[1] + ref.dNdx[2]) < 1e-14 / 100.0, "sum dNdx");
    CHECK(std::fabs(ref.dNdy[0] + ref.dNdy[1] + ref.dNdy[2]) < 1e-14 / 100.0, "sum dNdy");
  }
}

// The axis carried by a triangle's own affine map: exact for any linear map of an in-plane axis,
// the normal component dropped, slivers refused.
void TestCarryAxis(Rng &rng) {
  for (int trial = 0; trial < 20; ++trial) {
    double X[9], A[9], Y[9], n[3], axis[3], out[3];
    RandomTriangle(rng, 100.0, X);
    for (double &a : A) a = rng.Next();
    for (int i = 0; i < 3; ++i) A[4 * i] += 2.0;  // diagonal dominance: A invertible
    for (int a = 0; a < 3; ++a) Rotate(A, X + 3 * a, Y + 3 * a);
    for (int i = 0; i < 3; ++i) Y[i] += 7.0 * i;  // a translation changes nothing
    for (int i = 3; i < 9; ++i) Y[i] += 7.0 * (i % 3);
    double e1[3], e2[3];
    for (int i = 0; i < 3; ++i) e1[i] = X[3 + i] - X[i], e2[i] = X[6 + i] - X[i];
    Cross(e1, e2, n);
    const double s = rng.Next(), t = rng.Next(), r = rng.Next();
    for (int i = 0; i < 3; ++i) axis[i] = s * e1[i] + t * e2[i] + r * n[i] / std::sqrt(Dot(n, n)) * 50.0;
    CHECK(etfe::MembraneCarryAxis(X, Y, axis, out) == etfe::KERNEL_OK, "carry trial %d", trial);
    double in_plane[3], expect[3];
    for (int i = 0; i < 3; ++i) in_plane[i] = s * e1[i] + t * e2[i];
    Rotate(A, in_plane, expect);
    for (int i = 0; i < 3; ++i) CHECK_CLOSE(out[i], expect[i], 1e-12, 1e-12 * 100.0);
  }
  // A flat pattern stretched 2:1 along X: MD (X) doubles, TD (Y) is kept, the normal is dropped.
  const double X[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0}, Y[9] = {0, 0, 0, 2, 0, 0, 0, 1, 0};
  const double ax[3] = {1, 0, 0}, ay[3] = {0, 1, 0}, az[3] = {0, 0, 1};
  double out[3];
  CHECK(etfe::MembraneCarryAxis(X, Y, ax, out) == etfe::KERNEL_OK && std::fabs(out[0] - 2.0) < 1e-15 &&
            std::fabs(out[1]) < 1e-15, "MD stretched");
  CHECK(etfe::MembraneCarryAxis(X, Y, ay, out) == etfe::KERNEL_OK && std::fabs(out[1] - 1.0) < 1e-15 &&
            std::fabs(out[0]) < 1e-15, "TD kept");
  CHECK(etfe::MembraneCarryAxis(X, Y, az, out) == etfe::KERNEL_OK && Dot(out, out) < 1e-30, "normal dropped");
  const double sliver[9] = {0, 0, 0, 1, 0, 0, 2, 0, 0};
  CHECK(etfe::MembraneCarryAxis(sliver, Y, ax, out) == etfe::KERNEL_DEGENERATE, "sliver X");
  CHECK(etfe::MembraneCarryAxis(X, sliver, ax, out) == etfe::KERNEL_DEGENERATE, "sliver Y");
}

void TestOutputs() {
  const double s1[3] = {100.0, 0.0, 0.0};
  CHECK_CLOSE(etfe::MisesPlaneStress(s1), 100.0, 1e-15, 0.0);
  const double s2[3] = {50.0, 50.0, 0.0};  // equibiaxial: Mises = S
  CHECK_CLOSE(etfe::MisesPlaneStress(s2), 50.0, 1e-15, 0.0);
  const double s3[3] = {0.0, 0.0, 10.0};  // pure shear: sqrt(3) tau, principal -tau
  CHECK_CLOSE(etfe::MisesPlaneStress(s3), 10.0 * std::sqrt(3.0), 1e-15, 0.0);
  CHECK_CLOSE(etfe::MinPrincipalStress(s3), -10.0, 1e-15, 0.0);
  const double s4[3] = {3.0, -2.0, 1.0};  // 9 + 4 + 6 + 3 = 22
  CHECK_CLOSE(etfe::MisesPlaneStress(s4), std::sqrt(22.0), 1e-15, 0.0);
  CHECK_CLOSE(etfe::MinPrincipalStress(s4), 0.5 - std::sqrt(7.25), 1e-15, 0.0);
  const double s5[3] = {13.28, 4.0, 0.0};
  CHECK_CLOSE(etfe::MinPrincipalStress(s5), 4.0, 1e-15, 0.0);
  const double zero[3] = {0.0, 0.0, 0.0};
  CHECK(etfe::MisesPlaneStress(zero) == 0.0, "Mises of zero stress");

  // Strain uses the tensor shear: E = (0.01, -0.02, 2Exy = 0.03) -> Exy = 0.015.
  const double e1[3] = {0.01, -0.02, 0.03};
  CHECK_CLOSE(etfe::MinPrincipalStrain(e1), -0.005 - 0.015 * std::sqrt(2.0), 1e-14, 0.0);
  const double e2[3] = {0.0, 0.0, 0.02};  // pure engineering shear 0.02 -> principal -0.01
  CHECK_CLOSE(etfe::MinPrincipalStrain(e2), -0.01, 1e-14, 0.0);
  const double e3[3] = {0.03, 0.01, 0.0};
  CHECK_CLOSE(etfe::MinPrincipalStrain(e3), 0.01, 1e-14, 0.0);

  // Elastic law by hand: uniaxial strain (1e-3, 0, 0) with nu = 0.43 and engineering shear.
  double S[3], D[9];
  const double E[3] = {1e-3, 0.0, 2e-3};
  etfe::ElasticPlaneStress(kYoung, kNu, E, S, D);
  const double c = kYoung / (1.0 - kNu * kNu);
  CHECK_CLOSE(S[0], c * 1e-3, 1e-15, 0.0);
  CHECK_CLOSE(S[1], c * kNu * 1e-3, 1e-15, 0.0);
  CHECK_CLOSE(S[2], kYoung / (2.0 * (1.0 + kNu)) * 2e-3, 1e-14, 0.0);  // G * gamma
  CHECK(D[2] == 0.0 && D[5] == 0.0 && D[6] == 0.0 && D[7] == 0.0, "D coupling");
  etfe::ElasticPlaneStress(kYoung, kNu, E, S, nullptr);  // D is optional
}

void TestEquilibrium(Rng &rng) {
  for (int trial = 0; trial < 20; ++trial) {
    const double scale = trial % 2 ? 1.0 : 1000.0;
    double X[9], x[9];
    RandomTriangle(rng, scale, X);
    MembraneReference ref;
    const double md[3] = {rng.Next(), rng.Next(), rng.Next()};
    CHECK(etfe::MembraneReferenceBuild(X, md, 0.0, &ref) == etfe::KERNEL_OK, "trial %d", trial);
    for (int k = 0; k < 9; ++k) x[k] = X[k] + 0.3 * scale * rng.Next();
    double F[6], E[3], S[3], f[9];
    etfe::MembraneKinematics(ref, x, F, E);
    for (int i = 0; i < 3; ++i) S[i] = 20.0 * rng.Next();
    etfe::MembraneForce(ref, kH, F, S, nullptr, f, nullptr);
    const double fmax = MaxAbs(f, 9);
    double sum[3] = {0.0, 0.0, 0.0}, mom[3] = {0.0, 0.0, 0.0};
    for (int a = 0; a < 3; ++a) {
      double r[3], m[3];
      for (int i = 0; i < 3; ++i) {
        sum[i] += f[3 * a + i];
        r[i] = x[3 * a + i] - x[i];  // moments about node 1
      }
      Cross(r, f + 3 * a, m);
      for (int i = 0; i < 3; ++i) mom[i] += m[i];
    }
    CHECK(MaxAbs(sum, 3) < 1e-13 * fmax, "trial %d: force sum %g", trial, MaxAbs(sum, 3) / fmax);
    // Symmetric S makes the nodal forces moment-free as well.
    CHECK(MaxAbs(mom, 3) < 1e-12 * fmax * scale, "trial %d: moment %g", trial,
          MaxAbs(mom, 3) / (fmax * scale));
  }
}

} // namespace

// The Jacobian loop asks for K without the force (f == nullptr): the same K bit for bit, for a
// full (unsymmetric) D and for the geometric stiffness alone (D == nullptr); and K's entries are
// the formula's, evaluated entry by entry in its order, to the bit (zeros up to their sign, which
// no sum into a zeroed matrix sees).
void TestTangentWithoutForce(Rng &rng) {
  for (int trial = 0; trial < 50; ++trial) {
    double X[9], x[9];
    const double scale = 10.0 * (1.0 + rng.Next());
    RandomTriangle(rng, scale, X);
    for (int k = 0; k < 9; ++k) x[k] = X[k] + 0.1 * scale * rng.Next();
    MembraneReference ref;
    CHECK(etfe::MembraneReferenceBuild(X, kX, 0.0, &ref) == etfe::KERNEL_OK, "trial %d", trial);
    double F[6], E[3], S[3], D[9];
    etfe::MembraneKinematics(ref, x, F, E);
    for (int i = 0; i < 3; ++i) S[i] = 10.0 * rng.Next();
    for (int k = 0; k < 9; ++k) D[k] = 1000.0 * rng.Next();
    for (const double *Dp : {(const double *)D, (const double *)nullptr}) {
      double f[9], K[81], K1[81];
      etfe::MembraneForce(ref, kH, F, S, Dp, f, K);
      etfe::MembraneForce(ref, kH, F, S, Dp, nullptr, K1);
      CHECK(std::memcmp(K, K1, sizeof K) == 0, "trial %d (D %s): K without f differs", trial,
            Dp ? "given" : "nullptr");
      // Entry by entry as the formula reads, K_ab = w [B_a^T D B_b + (gradN_a . S gradN_b) I3]
      // with the sums in that order: the kernel's vectorized rows must give these very bits.
      const double w = kH * ref.area;
      bool same = true;
      for (int a = 0; a < 3; ++a)
        for (int i = 0; i < 3; ++i)
          for (int b = 0; b < 3; ++b)
            for (int j = 0; j < 3; ++j) {
              const double ba[3] = {ref.dNdx[a] * F[2 * i], ref.dNdy[a] * F[2 * i + 1],
                                    ref.dNdx[a] * F[2 * i + 1] + ref.dNdy[a] * F[2 * i]};
              const double bb[3] = {ref.dNdx[b] * F[2 * j], ref.dNdy[b] * F[2 * j + 1],
                                    ref.dNdx[b] * F[2 * j + 1] + ref.dNdy[b] * F[2 * j]};
              double v = 0.0;
              if (Dp) {
                double db[3];
                for (int r = 0; r < 3; ++r) db[r] = Dp[3 * r] * bb[0] + Dp[3 * r + 1] * bb[1] + Dp[3 * r + 2] * bb[2];
                v = w * (ba[0] * db[0] + ba[1] * db[1] + ba[2] * db[2]);
              }
              if (i == j) {
                const double sg0 = S[0] * ref.dNdx[b] + S[2] * ref.dNdy[b];
                const double sg1 = S[2] * ref.dNdx[b] + S[1] * ref.dNdy[b];
                v += w * (ref.dNdx[a] * sg0 + ref.dNdy[a] * sg1);
              }
              const double k = K[9 * (3 * a + i) + 3 * b + j];
              same = same && (k == v && std::signbit(k) == std::signbit(v) ? true : k == 0.0 && v == 0.0);
            }
      CHECK(same, "trial %d (D %s): K differs in some bit from the formula entry by entry", trial,
            Dp ? "given" : "nullptr");
    }
  }
}

int main() {
  Rng rng{20190925};
  TestTangent(rng);
  TestTangentWithoutForce(rng);
  TestRigidBody(rng);
  TestHomogeneous(rng);
  TestDegenerate();
  TestFrame(rng);
  TestCarryAxis(rng);
  TestOutputs();
  TestEquilibrium(rng);
  TEST_MAIN_END();
}
