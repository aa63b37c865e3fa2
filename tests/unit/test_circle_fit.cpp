// Circle fit (src/kernels/circle_fit.cpp), which the general scene uses for a rigid support given
// as a curve of the mesh (-rigid_<name>_type curve):
//  * points on an exact arc (the saddle's arch: plane X = 1000, crown 300 mm over a 2000 mm span;
//    a skew circle in space; a short arc of 20 degrees) give its centre, axis and radius to
//    round-off and a deviation of round-off;
//  * noisy points give a deviation of the size of the noise;
//  * collinear points and fewer than three are refused;
//  * the long axis of a strip of points (3000 x 500 mm along (1, 2, 2)/3) is that direction.
#include "etfe/kernels/circle_fit.h"

#include "check.h"

#include <cmath>
#include <vector>

namespace {

// n points on the circle (centre c, unit axis a, radius r) between angles t0 and t1.
std::vector<double> Arc(const double c[3], const double a[3], double r, double t0, double t1, int n) {
  // e1, e2: an orthonormal pair in the plane normal to a.
  double h[3] = {1, 0, 0};
  if (std::fabs(a[0]) > 0.9) h[0] = 0, h[1] = 1;
  double e1[3] = {a[1] * h[2] - a[2] * h[1], a[2] * h[0] - a[0] * h[2], a[0] * h[1] - a[1] * h[0]};
  const double l = std::sqrt(e1[0] * e1[0] + e1[1] * e1[1] + e1[2] * e1[2]);
  for (double &x : e1) x /= l;
  const double e2[3] = {a[1] * e1[2] - a[2] * e1[1], a[2] * e1[0] - a[0] * e1[2], a[0] * e1[1] - a[1] * e1[0]};
  std::vector<double> p;
  for (int k = 0; k < n; ++k) {
    const double t = t0 + (t1 - t0) * k / (n - 1);
    for (int i = 0; i < 3; ++i) p.push_back(c[i] + r * (std::cos(t) * e1[i] + std::sin(t) * e2[i]));
  }
  return p;
}

void CheckExact(const char *what, const double c[3], const double a[3], double r, double t0, double t1, int n) {
  const std::vector<double> p = Arc(c, a, r, t0, t1, n);
  etfe::CircleFit f;
  CHECK(etfe::FitCircle(p.data(), n, &f), "%s: fitted", what);
  CHECK_CLOSE(f.radius, r, 1e-9, 0.0);
  for (int i = 0; i < 3; ++i) CHECK_CLOSE(f.centre[i], c[i], 0.0, 1e-9 * r);
  const double dot = f.axis[0] * a[0] + f.axis[1] * a[1] + f.axis[2] * a[2];
  CHECK_CLOSE(std::fabs(dot), 1.0, 1e-12, 0.0);
  CHECK(f.max_deviation < 1e-9 * r, "%s: deviation %g", what, f.max_deviation);
}

} // namespace

int main() {
  {  // the saddle's arch (r = 15 %): radius (1000^2 + 300^2)/600, centre 300 - radius below the crown
    const double R = (1e6 + 9e4) / 600.0, c[3] = {1000, 0, 300 - R}, a[3] = {1, 0, 0};
    const double half = std::asin(1000.0 / R);
    CheckExact("saddle arch", c, a, R, M_PI / 2 - half, M_PI / 2 + half, 20);
  }
  {
    const double s = 1 / std::sqrt(3.0), c[3] = {-250, 40, 3000}, a[3] = {s, -s, s};
    CheckExact("skew ring", c, a, 750.0, 0.0, 5.0, 37);
  }
  {
    const double c[3] = {0, 0, 0}, a[3] = {0, 0, 1};
    CheckExact("short arc", c, a, 21.35, 0.3, 0.3 + 20 * M_PI / 180, 9);
  }
  {  // noise of 0.01 mm on a radius of 500 mm
    const double c[3] = {0, 0, 0}, a[3] = {0, 1, 0};
    std::vector<double> p = Arc(c, a, 500.0, 0.0, 2.0, 25);
    for (size_t k = 0; k < p.size(); ++k) p[k] += 0.01 * std::sin(7.0 * k);
    etfe::CircleFit f;
    CHECK(etfe::FitCircle(p.data(), 25, &f), "noisy arc fitted");
    CHECK(f.max_deviation > 1e-3 && f.max_deviation < 0.05, "noisy arc: deviation %g of noise 0.01", f.max_deviation);
    CHECK_CLOSE(f.radius, 500.0, 1e-4, 0.0);
  }
  {
    const double line[9] = {0, 0, 0, 1, 1, 1, 2, 2, 2}, two[6] = {0, 0, 0, 1, 0, 0};
    etfe::CircleFit f;
    CHECK(!etfe::FitCircle(line, 3, &f), "collinear points refused");
    CHECK(!etfe::FitCircle(two, 2, &f), "two points refused");
  }
  {
    const double d[3] = {1.0 / 3, 2.0 / 3, 2.0 / 3}, across[3] = {2.0 / 3, 1.0 / 3, -2.0 / 3};
    std::vector<double> p;
    for (int i = 0; i <= 30; ++i)
      for (int j = 0; j <= 5; ++j)
        for (int k = 0; k < 3; ++k) p.push_back(100.0 * i * d[k] + 100.0 * j * across[k] - 7.0 * (k + 1));
    double axis[3];
    CHECK(etfe::LongAxis(p.data(), (int)p.size() / 3, axis), "long axis found");
    for (int k = 0; k < 3; ++k) CHECK_CLOSE(axis[k], d[k], 0.0, 1e-12);
    CHECK(!etfe::LongAxis(p.data(), 1, axis), "one point has no axis");
  }
  TEST_MAIN_END();
}
