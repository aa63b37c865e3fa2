// Central differences for the unit tests' tangent checks: the one loop every kernel's consistent
// tangent is compared against, so each test states only what it differentiates and its tolerance.
#pragma once
#include <vector>

namespace etfe_test {

// J (m x n, row-major) ~ df/dx at x by central differences with step h:
//   J[row * n + col] = (f(x + h e_col)[row] - f(x - h e_col)[row]) / (2 h).
// f(const double *x, double *out) writes m values; it is called at x + h e_col, then at x - h e_col,
// for col = 0 .. n-1.
template <typename F>
void CentralDifferenceJacobian(const F &f, const double *x, int n, int m, double h, double *J) {
  std::vector<double> xp(x, x + n), xm(x, x + n), fp(m), fm(m);
  for (int col = 0; col < n; ++col) {
    xp[col] += h;
    xm[col] -= h;
    f(xp.data(), fp.data());
    f(xm.data(), fm.data());
    for (int row = 0; row < m; ++row) J[row * n + col] = (fp[row] - fm[row]) / (2.0 * h);
    xp[col] = xm[col] = x[col];
  }
}

} // namespace etfe_test
