// See nearest.h.
#include "etfe/kernels/nearest.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace etfe {

namespace {

// A k-d tree stored in place: the anchors' indices reordered so that each range [lo, hi) has its
// median at mid = (lo + hi) / 2, the left half below it along axis[mid], the right half above.
struct KdTree {
  const std::vector<double> &x;
  std::vector<int> idx;
  std::vector<signed char> axis;
  std::vector<double> box;  // per range, at its mid: the anchors' bounding box (min xyz, max xyz)

  explicit KdTree(const std::vector<double> &anchors)
      : x(anchors), idx(anchors.size() / 3), axis(idx.size()), box(6 * idx.size()) {
    std::iota(idx.begin(), idx.end(), 0);
    Build(0, (int)idx.size());
  }
  void Build(int lo, int hi) {
    if (hi <= lo) return;
    double mn[3] = {INFINITY, INFINITY, INFINITY}, mx[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (int k = lo; k < hi; ++k)
      for (int i = 0; i < 3; ++i) mn[i] = std::min(mn[i], x[3 * idx[k] + i]), mx[i] = std::max(mx[i], x[3 * idx[k] + i]);
    const int mid = (lo + hi) / 2;
    if (hi - lo == 1) {
      for (int i = 0; i < 3; ++i) box[6 * mid + i] = mn[i], box[6 * mid + 3 + i] = mx[i];
      return;
    }
    int a = 0;
    for (int i = 1; i < 3; ++i)
      if (mx[i] - mn[i] > mx[a] - mn[a]) a = i;
    std::nth_element(idx.begin() + lo, idx.begin() + mid, idx.begin() + hi,
                     [&](int p, int q) { return x[3 * p + a] < x[3 * q + a]; });
    axis[mid] = (signed char)a;
    for (int i = 0; i < 3; ++i) box[6 * mid + i] = mn[i], box[6 * mid + 3 + i] = mx[i];
    Build(lo, mid);
    Build(mid + 1, hi);
  }
  // The smallest distance from p to an anchor of [lo, hi): the search runs on squared distances
  // (best2) and measures with hypot, the expression a loop over all anchors uses, every anchor
  // within a relative 1e-12 of the best squared distance so far (round-off between the two
  // expressions is ~1e-16), so the result is that loop's, bit for bit. A subtree is skipped only
  // when its anchors' bounding box is farther than the best.
  void Search(const double p[3], int lo, int hi, double *best2, double *best) const {
    if (hi <= lo) return;
    const int mid = (lo + hi) / 2;
    double out2 = 0.0;  // squared distance from p to the range's box
    for (int i = 0; i < 3; ++i) {
      const double below = box[6 * mid + i] - p[i], above = p[i] - box[6 * mid + 3 + i];
      if (below > 0) out2 += below * below;
      else if (above > 0) out2 += above * above;
    }
    if (out2 > *best2 * (1.0 + 1e-12)) return;
    const double *q = &x[3 * idx[mid]];
    const double dx = p[0] - q[0], dy = p[1] - q[1], dz = p[2] - q[2], d2 = dx * dx + dy * dy + dz * dz;
    if (d2 <= *best2 * (1.0 + 1e-12)) {
      *best = std::min(*best, std::hypot(dx, dy, dz));
      *best2 = std::min(*best2, d2);
    }
    if (hi - lo == 1) return;
    const bool left_first = p[axis[mid]] < q[axis[mid]];
    Search(p, left_first ? lo : mid + 1, left_first ? mid : hi, best2, best);
    Search(p, left_first ? mid + 1 : lo, left_first ? hi : mid, best2, best);
  }
};

} // namespace

std::vector<double> NearestAnchorDistances(const std::vector<double> &points, const std::vector<double> &anchors) {
  const KdTree tree(anchors);
  std::vector<double> d(points.size() / 3, INFINITY);
  for (size_t n = 0; n < d.size(); ++n) {
    double best2 = INFINITY;
    tree.Search(&points[3 * n], 0, (int)tree.idx.size(), &best2, &d[n]);
  }
  return d;
}

} // namespace etfe
