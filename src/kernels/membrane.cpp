// Three-node total-Lagrangian membrane (CST) element, docs/theory.md §2 / thesis §4.2.1 (eqs.
// 4.4-4.13). Reference data: an orthonormal frame (e1 = MD axis projected on the element, e3 =
// normal) and the constant shape-function gradients dN/dxi = [eta23, eta31, eta12]/(2A0),
// dN/deta = [xi32, xi13, xi21]/(2A0). Kinematics F = sum_a x_a (x) gradN_a (3x2),
// E = 1/2 (F^T F - I) (Voigt, engineering shear) -- the thesis's a2..a9 form of eq. 4.6 written
// without rotating the displacements. Force f_a = h0 A0 F S gradN_a and tangent
// K_ab = h0 A0 [(gradN_a . S gradN_b) I3 + B_a^T D B_b].
// These run once per element per Newton iteration on meshes of 10^6 triangles: fixed-size
// arrays and plain loops only, no heap, no exceptions.
#include "etfe/kernels/membrane.h"
#include "etfe/kernels/vec3.h"

#include "etfe/kernels/status.h"

#include <cmath>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace etfe {

namespace {

inline double Dot3(const double *a, const double *b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

// Below this sine of the angle between md_axis and the normal the projection has no reliable
// direction (header contract: "within ~1e-3 of the normal").
constexpr double kMdParallelTol = 1e-3;
// A sliver whose doubled area is below this fraction of its longest edge squared has no
// numerically meaningful in-plane gradients, whatever min_area the caller passed (exactly
// collinear nodes give a rounding-level, not a zero, cross product).
constexpr double kSliverTol = 1e-10;

} // namespace

int MembraneReferenceBuild(const double X[9], const double md_axis[3], double min_area,
                           MembraneReference *ref) {
  for (int k = 0; k < 9; ++k)
    if (!std::isfinite(X[k])) return KERNEL_DEGENERATE;

  double a[3], b[3], c[3], n[3];
  for (int i = 0; i < 3; ++i) {
    a[i] = X[3 + i] - X[i];
    b[i] = X[6 + i] - X[i];
    c[i] = X[6 + i] - X[3 + i];
  }
  Cross(a, b, n);
  const double twice_area = std::sqrt(Dot3(n, n));
  const double lmax2 = std::fmax(Dot3(a, a), std::fmax(Dot3(b, b), Dot3(c, c)));
  // The negated comparisons also reject NaN from overflowing coordinates.
  if (!(0.5 * twice_area >= min_area) || !(twice_area > kSliverTol * lmax2))
    return KERNEL_DEGENERATE;

  double e1[3], e2[3], e3[3];
  for (int i = 0; i < 3; ++i) e3[i] = n[i] / twice_area;

  // e1: md_axis projected on the element plane; the edge 1->2 when md_axis is (nearly) normal,
  // missing or not finite, so every element still gets a frame.
  bool use_edge = true;
  if (md_axis && std::isfinite(md_axis[0]) && std::isfinite(md_axis[1]) &&
      std::isfinite(md_axis[2])) {
    const double md_norm = std::sqrt(Dot3(md_axis, md_axis));
    const double dn = Dot3(md_axis, e3);
    for (int i = 0; i < 3; ++i) e1[i] = md_axis[i] - dn * e3[i];
    const double pn = std::sqrt(Dot3(e1, e1));
    if (md_norm > 0.0 && pn > kMdParallelTol * md_norm) {
      for (int i = 0; i < 3; ++i) e1[i] /= pn;
      use_edge = false;
    }
  }
  if (use_edge) {
    const double la = std::sqrt(Dot3(a, a));  // > 0: the area test passed
    for (int i = 0; i < 3; ++i) e1[i] = a[i] / la;
  }
  Cross(e3, e1, e2);

  // Local coordinates relative to node 1 (xi_1 = eta_1 = 0): differences keep full precision for
  // elements far from the origin.
  const double xi2 = Dot3(a, e1), eta2 = Dot3(a, e2);
  const double xi3 = Dot3(b, e1), eta3 = Dot3(b, e2);
  // Same value as twice_area up to rounding; taken from the local coordinates so the gradients
  // sum to zero and reproduce a linear field exactly.
  const double det = xi2 * eta3 - xi3 * eta2;
  const double inv = 1.0 / det;

  ref->dNdx[0] = (eta2 - eta3) * inv;  // eta23
  ref->dNdx[1] = eta3 * inv;           // eta31 (eta1 = 0)
  ref->dNdx[2] = -eta2 * inv;          // eta12
  ref->dNdy[0] = (xi3 - xi2) * inv;    // xi32
  ref->dNdy[1] = -xi3 * inv;           // xi13
  ref->dNdy[2] = xi2 * inv;            // xi21
  ref->area = 0.5 * det;
  for (int i = 0; i < 3; ++i) {
    ref->frame[i] = e1[i];
    ref->frame[3 + i] = e2[i];
    ref->frame[6 + i] = e3[i];
  }
  return KERNEL_OK;
}

int MembraneCarryAxis(const double X[9], const double Y[9], const double axis[3], double out[3]) {
  double a[3], b[3], n[3], ya[3], yb[3];
  for (int i = 0; i < 3; ++i) {
    a[i] = X[3 + i] - X[i], b[i] = X[6 + i] - X[i];
    ya[i] = Y[3 + i] - Y[i], yb[i] = Y[6 + i] - Y[i];
  }
  Cross(a, b, n);
  double ny[3];
  Cross(ya, yb, ny);
  const double aa = Dot3(a, a), bb = Dot3(b, b), ab = Dot3(a, b), det = aa * bb - ab * ab;
  if (!(det > kSliverTol * kSliverTol * std::fmax(aa, bb) * std::fmax(aa, bb)) ||
      !(Dot3(ny, ny) > kSliverTol * kSliverTol * std::fmax(Dot3(ya, ya), Dot3(yb, yb)) *
                             std::fmax(Dot3(ya, ya), Dot3(yb, yb))))
    return KERNEL_DEGENERATE;
  // The in-plane part of axis as alpha a + beta b (normal equations of the edge basis), then the
  // same combination of Y's edges: the triangle's own affine map X -> Y applied to the axis.
  const double ra = Dot3(axis, a), rb = Dot3(axis, b);
  const double alpha = (bb * ra - ab * rb) / det, beta = (aa * rb - ab * ra) / det;
  for (int i = 0; i < 3; ++i) out[i] = alpha * ya[i] + beta * yb[i];
  for (int i = 0; i < 3; ++i)
    if (!std::isfinite(out[i])) return KERNEL_NONFINITE;
  return KERNEL_OK;
}

void MembraneKinematics(const MembraneReference &ref, const double x[9], double F[6],
                        double E[3]) {
  // sum_a gradN_a = 0, so F only depends on the edge vectors: using them avoids cancellation
  // when the element sits far from the origin.
  for (int i = 0; i < 3; ++i) {
    const double d1 = x[3 + i] - x[i];
    const double d2 = x[6 + i] - x[i];
    F[2 * i] = d1 * ref.dNdx[1] + d2 * ref.dNdx[2];
    F[2 * i + 1] = d1 * ref.dNdy[1] + d2 * ref.dNdy[2];
  }
  const double c00 = F[0] * F[0] + F[2] * F[2] + F[4] * F[4];
  const double c11 = F[1] * F[1] + F[3] * F[3] + F[5] * F[5];
  const double c01 = F[0] * F[1] + F[2] * F[3] + F[4] * F[5];
  E[0] = 0.5 * (c00 - 1.0);
  E[1] = 0.5 * (c11 - 1.0);
  E[2] = c01;  // 2 Exy
}

void MembraneForce(const MembraneReference &ref, double thickness, const double F[6],
                   const double S[3], const double D[9], double f[9], double K[81]) {
  const double w = thickness * ref.area;

  // S gradN_a (2-vectors).
  double sg[3][2];
  for (int a = 0; a < 3; ++a) {
    sg[a][0] = S[0] * ref.dNdx[a] + S[2] * ref.dNdy[a];
    sg[a][1] = S[2] * ref.dNdx[a] + S[1] * ref.dNdy[a];
    if (f)
      for (int i = 0; i < 3; ++i) f[3 * a + i] = w * (F[2 * i] * sg[a][0] + F[2 * i + 1] * sg[a][1]);
  }
  if (!K) return;

  // B[r][3b+j]: strain row r (xx, yy, 2xy) of node b's B matrix, displacement component j. Rows
  // of 9 contiguous values, so the products below run over whole rows of K, two entries per
  // baseline SSE2 instruction; every entry is still formed by the same operations in the same
  // order as B_a^T D B_b + geo written entry by entry (no FMA on baseline x86-64), so K is
  // unchanged (test_membrane checks it to the bit).
  double B[3][9];
  for (int b = 0; b < 3; ++b) {
    const double gx = ref.dNdx[b], gy = ref.dNdy[b];
    for (int j = 0; j < 3; ++j) {
      B[0][3 * b + j] = gx * F[2 * j];
      B[1][3 * b + j] = gy * F[2 * j + 1];
      B[2][3 * b + j] = gx * F[2 * j + 1] + gy * F[2 * j];
    }
  }

  // D == nullptr with K requested gives the geometric (initial-stress) stiffness alone, the
  // form-finding case.
  double DB[3][9];
  if (D) {
    for (int r = 0; r < 3; ++r) {
#if defined(__SSE2__)
      // As the loop below, two entries per instruction (see the rows of K).
      const __m128d d0 = _mm_set1_pd(D[3 * r]), d1 = _mm_set1_pd(D[3 * r + 1]), d2 = _mm_set1_pd(D[3 * r + 2]);
      for (int k = 0; k < 8; k += 2)
        _mm_storeu_pd(&DB[r][k], _mm_add_pd(_mm_add_pd(_mm_mul_pd(_mm_loadu_pd(&B[0][k]), d0),
                                                       _mm_mul_pd(_mm_loadu_pd(&B[1][k]), d1)),
                                            _mm_mul_pd(_mm_loadu_pd(&B[2][k]), d2)));
      DB[r][8] = D[3 * r] * B[0][8] + D[3 * r + 1] * B[1][8] + D[3 * r + 2] * B[2][8];
#else
      for (int k = 0; k < 9; ++k) DB[r][k] = D[3 * r] * B[0][k] + D[3 * r + 1] * B[1][k] + D[3 * r + 2] * B[2][k];
#endif
    }
  }

  for (int a = 0; a < 3; ++a) {
    double geo[3];
    for (int b = 0; b < 3; ++b) geo[b] = w * (ref.dNdx[a] * sg[b][0] + ref.dNdy[a] * sg[b][1]);
    for (int i = 0; i < 3; ++i) {
      double *row = K + 9 * (3 * a + i);
      if (D) {
        const double b0 = B[0][3 * a + i], b1 = B[1][3 * a + i], b2 = B[2][3 * a + i];
#if defined(__SSE2__)
        // The same products and sums as the loop below, two entries per instruction: each DB
        // pair is loaded into the register it is multiplied in, which spares the register copies
        // the compiler's own vectorization made (the 2-operand SSE2 forms overwrite an operand).
        const __m128d v0 = _mm_set1_pd(b0), v1 = _mm_set1_pd(b1), v2 = _mm_set1_pd(b2), vw = _mm_set1_pd(w);
        for (int k = 0; k < 8; k += 2) {
          const __m128d t = _mm_add_pd(_mm_add_pd(_mm_mul_pd(_mm_loadu_pd(&DB[0][k]), v0),
                                                  _mm_mul_pd(_mm_loadu_pd(&DB[1][k]), v1)),
                                       _mm_mul_pd(_mm_loadu_pd(&DB[2][k]), v2));
          _mm_storeu_pd(row + k, _mm_mul_pd(t, vw));
        }
        row[8] = w * (b0 * DB[0][8] + b1 * DB[1][8] + b2 * DB[2][8]);
#else
        for (int k = 0; k < 9; ++k) row[k] = w * (b0 * DB[0][k] + b1 * DB[1][k] + b2 * DB[2][k]);
#endif
      } else {
        for (int k = 0; k < 9; ++k) row[k] = 0.0;
      }
      // The geometric part sits on the diagonal of every 3x3 block (zero elsewhere: adding it
      // only there changes at most the sign of a zero, which no sum into the matrix sees).
      for (int b = 0; b < 3; ++b) row[3 * b + i] += geo[b];
    }
  }
}

double MembraneAreaRatio(const MembraneReference &ref, const double x[9], double n[3]) {
  double a[3], b[3], c[3];
  for (int i = 0; i < 3; ++i) {
    a[i] = x[3 + i] - x[i];
    b[i] = x[6 + i] - x[i];
  }
  Cross(a, b, c);
  const double twice_area = std::sqrt(Dot3(c, c));
  if (n) {
    // A collapsed triangle has no normal; zeros let the caller see it instead of NaN.
    const double inv = twice_area > 0.0 ? 1.0 / twice_area : 0.0;
    for (int i = 0; i < 3; ++i) n[i] = c[i] * inv;
  }
  return 0.5 * twice_area / ref.area;
}

double MisesPlaneStress(const double S[3]) {
  const double q = S[0] * S[0] + S[1] * S[1] - S[0] * S[1] + 3.0 * S[2] * S[2];
  return std::sqrt(std::fmax(q, 0.0));  // q >= 0 in exact arithmetic
}

double MinPrincipalStress(const double S[3]) {
  const double m = 0.5 * (S[0] + S[1]);
  const double d = 0.5 * (S[0] - S[1]);
  return m - std::sqrt(d * d + S[2] * S[2]);
}

double MinPrincipalStrain(const double E[3]) {
  const double m = 0.5 * (E[0] + E[1]);
  const double d = 0.5 * (E[0] - E[1]);
  const double g = 0.5 * E[2];  // tensor shear
  return m - std::sqrt(d * d + g * g);
}

} // namespace etfe
