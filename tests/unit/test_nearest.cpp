// Nearest-anchor distances (src/kernels/nearest.cpp) equal, bit for bit, the smallest hypot over
// every anchor: on a disc's nodes against its rim (the general scene's initial bulge), on random
// points against random anchors (duplicates, one anchor, points on the anchors, a flat set), and
// on a grid whose points tie between anchors.
#include "etfe/kernels/nearest.h"

#include "check.h"

#include <cmath>
#include <random>
#include <vector>

namespace {

std::vector<double> BruteForce(const std::vector<double> &p, const std::vector<double> &a) {
  std::vector<double> d(p.size() / 3, INFINITY);
  for (size_t n = 0; n < d.size(); ++n)
    for (size_t k = 0; k < a.size() / 3; ++k)
      d[n] = std::min(d[n], std::hypot(p[3 * n] - a[3 * k], p[3 * n + 1] - a[3 * k + 1], p[3 * n + 2] - a[3 * k + 2]));
  return d;
}

void Add(std::vector<double> *v, double x, double y, double z) {
  v->push_back(x), v->push_back(y), v->push_back(z);
}

void Compare(const char *what, const std::vector<double> &p, const std::vector<double> &a) {
  const std::vector<double> fast = etfe::NearestAnchorDistances(p, a), slow = BruteForce(p, a);
  int differ = 0;
  for (size_t n = 0; n < slow.size(); ++n) differ += fast[n] != slow[n];
  CHECK(fast.size() == slow.size() && differ == 0, "%s: %d of %zu distances differ from the loop over all anchors",
        what, differ, slow.size());
}

} // namespace

int main() {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1000.0, 1000.0);
  {  // a disc of radius 500 in rings, against its rim
    std::vector<double> nodes, rim;
    const int rings = 40;
    Add(&nodes, 0.0, 0.0, 0.0);
    for (int r = 1; r <= rings; ++r)
      for (int k = 0; k < 6 * r; ++k) {
        const double t = 2 * M_PI * k / (6 * r), rad = 500.0 * r / rings;
        const double xyz[3] = {rad * std::cos(t), rad * std::sin(t), 1e-3 * rad * rad};
        nodes.insert(nodes.end(), xyz, xyz + 3);
        if (r == rings) rim.insert(rim.end(), xyz, xyz + 3);
      }
    Compare("disc against its rim", nodes, rim);
  }
  for (int m : {1, 2, 7, 100, 1000}) {
    std::vector<double> p, a;
    for (int k = 0; k < 3 * m; ++k) a.push_back(u(rng));
    for (int k = 0; k < 3 * 2000; ++k) p.push_back(u(rng));
    p.insert(p.end(), a.begin(), a.end());  // points on anchors: distance 0
    a.insert(a.end(), a.begin(), a.begin() + 3);  // a duplicate anchor
    Compare("random points and anchors", p, a);
  }
  {  // a flat set of anchors (z = 0) and a grid whose points tie between neighbouring anchors
    std::vector<double> p, a;
    for (int i = 0; i <= 20; ++i)
      for (int j = 0; j <= 20; ++j) Add(&a, 10.0 * i, 10.0 * j, 0.0);
    for (int i = 0; i <= 40; ++i)
      for (int j = 0; j <= 40; ++j) Add(&p, 5.0 * i, 5.0 * j, (double)(i % 3));
    Compare("grid with ties", p, a);
  }
  {
    const std::vector<double> d = etfe::NearestAnchorDistances({3, 4, 0}, {0, 0, 0});
    CHECK(d.size() == 1 && d[0] == 5.0, "one point, one anchor: %g", d.empty() ? -1.0 : d[0]);
  }
  TEST_MAIN_END();
}
