// Gas chamber kernels (src/kernels/chamber.cpp, include/etfe/kernels/chamber.h):
//  * the tetrahedra sum is the exact volume of a closed polyhedron (a unit cube of 12 triangles,
//    normals out: 1; a box 2 x 3 x 5: 30), whatever the origin; normals in give minus it;
//  * its gradient per node is the follower-pressure load per unit pressure (kernels/pressure.h),
//    checked by central differences of the volume on a skewed octahedron;
//  * the sealed gas law: the amount reproduces the gauge pressure it was made from, the gauge
//    pressure at another volume follows p_abs V^kappa = C, and the stiffness kappa p_abs / V is
//    minus the derivative of the gauge pressure (central differences), for kappa 1 and 1.4.
#include "etfe/kernels/chamber.h"
#include "etfe/kernels/pressure.h"

#include "check.h"

#include <cmath>
#include <vector>

namespace {

struct Poly {
  std::vector<double> x;  // 3 per node
  std::vector<int> t;     // 3 per triangle, normals out
};

double Volume(const Poly &p, const double o[3]) {
  double V = 0;
  for (size_t e = 0; e < p.t.size() / 3; ++e) {
    double x[9];
    for (int a = 0; a < 3; ++a)
      for (int i = 0; i < 3; ++i) x[3 * a + i] = p.x[3 * p.t[3 * e + a] + i];
    V += etfe::ChamberTetVolume(x, o);
  }
  return V;
}

Poly Box(double a, double b, double c) {
  Poly p;
  for (int k = 0; k < 8; ++k) p.x.insert(p.x.end(), {a * (k & 1), b * ((k >> 1) & 1), c * ((k >> 2) & 1)});
  // faces as quads (counterclockwise seen from outside), two triangles each
  const int q[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto &f : q) p.t.insert(p.t.end(), {f[0], f[1], f[2], f[0], f[2], f[3]});
  return p;
}

} // namespace

int main() {
  const double origins[3][3] = {{0, 0, 0}, {0.3, -2.0, 7.5}, {100, 200, -300}};
  for (const auto &o : origins) {
    CHECK_CLOSE(Volume(Box(1, 1, 1), o), 1.0, 1e-12, 0.0);
    CHECK_CLOSE(Volume(Box(2, 3, 5), o), 30.0, 1e-12, 0.0);
  }
  {  // inward normals: minus the volume
    Poly p = Box(2, 3, 5);
    for (size_t e = 0; e < p.t.size(); e += 3) std::swap(p.t[e + 1], p.t[e + 2]);
    CHECK_CLOSE(Volume(p, origins[1]), -30.0, 1e-12, 0.0);
  }
  {  // gradient: the pressure load per unit pressure, against central differences
    Poly p;
    p.x = {1.1, 0.1, -0.2, -0.9, 0.2, 0.1, 0.1, 1.3, 0.2, -0.1, -1.0, 0.1, 0.2, -0.1, 1.4, 0.1, 0.2, -1.2};
    const int tri[8][3] = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4}, {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
    for (const auto &t : tri) p.t.insert(p.t.end(), {t[0], t[1], t[2]});
    const double o[3] = {0.2, -0.4, 0.3};
    CHECK(Volume(p, o) > 0, "the octahedron's normals point out (V = %g)", Volume(p, o));
    std::vector<double> g(p.x.size(), 0.0);
    for (size_t e = 0; e < p.t.size() / 3; ++e) {
      double x[9], f[9];
      for (int a = 0; a < 3; ++a)
        for (int i = 0; i < 3; ++i) x[3 * a + i] = p.x[3 * p.t[3 * e + a] + i];
      etfe::PressureLoad(1.0, x, f, nullptr);
      for (int a = 0; a < 3; ++a)
        for (int i = 0; i < 3; ++i) g[3 * p.t[3 * e + a] + i] += f[3 * a + i];
    }
    for (size_t k = 0; k < p.x.size(); ++k) {
      const double h = 1e-6, keep = p.x[k];
      p.x[k] = keep + h;
      const double vp = Volume(p, o);
      p.x[k] = keep - h;
      const double vm = Volume(p, o);
      p.x[k] = keep;
      CHECK_CLOSE(g[k], (vp - vm) / (2 * h), 0.0, 1e-8);
    }
  }
  for (double kappa : {1.0, 1.4}) {  // the sealed gas law
    const double patm = 0.101325, V0 = 7.3e8, p0 = 3e-4;
    const double C = etfe::SealedAmount(p0, patm, V0, kappa);
    CHECK_CLOSE(etfe::SealedGauge(C, patm, V0, kappa), p0, 1e-12, 0.0);
    const double V1 = 0.97 * V0;
    CHECK_CLOSE(etfe::SealedGauge(C, patm, V1, kappa) + patm, (p0 + patm) * std::pow(V0 / V1, kappa), 1e-12, 0.0);
    const double h = 1e-4 * V1;
    const double dp = (etfe::SealedGauge(C, patm, V1 + h, kappa) - etfe::SealedGauge(C, patm, V1 - h, kappa)) / (2 * h);
    CHECK_CLOSE(etfe::SealedStiffness(C, V1, kappa), -dp, 1e-7, 0.0);
  }
  TEST_MAIN_END();
}
