// Distance from each of many points to the nearest of a set of anchors, exactly (the smallest
// std::hypot over the anchors, bit for bit what a loop over every anchor gives) in about
// O(n log m) instead of O(n m): a k-d tree over the anchors, searched with pruning. The general
// scene's initial bulge measures every film node's distance to the held nodes with it; a loop
// over all pairs took minutes at 10^7 triangles (m ~ sqrt(n) anchors on the boundary).
#pragma once
#include <vector>

namespace etfe {

// points: 3 per point; anchors: 3 per anchor (at least one). Returns one distance per point.
std::vector<double> NearestAnchorDistances(const std::vector<double> &points, const std::vector<double> &anchors);

} // namespace etfe
