// The circle through points that lie on a circular arc in space (an arch, a ring beam): its plane
// by least squares (the normal is the covariance's weakest direction), then the circle in that
// plane by algebraic least squares (Kasa). PETSc-free.
#pragma once

namespace etfe {

struct CircleFit {
  double centre[3], axis[3];  // axis: unit normal of the circle's plane
  double radius;
  double max_deviation;       // largest distance of a point from the fitted circle (in space)
};

// n points, 3 coordinates each. Returns false (fit untouched) when the points do not fix a circle:
// fewer than 3, or all on one line.
bool FitCircle(const double *pts, int n, CircleFit *fit);

// The direction in which n points spread most (unit; the covariance's largest eigenvector, its
// sign making the largest component positive): a strip's long axis. False for fewer than 2 points.
bool LongAxis(const double *pts, int n, double axis[3]);

} // namespace etfe
