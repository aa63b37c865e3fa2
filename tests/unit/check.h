// A minimal test harness: each unit test is one executable; CHECK records a failure with its
// location and the program exits non-zero at the end (ctest counts it). No dependencies.
#pragma once
#include <cmath>
#include <cstdint>
#include <cstdio>

namespace etfe_test {
inline int &Failures() { static int n = 0; return n; }
inline int &Checks() { static int n = 0; return n; }
} // namespace etfe_test

// A deterministic generator for random test states, so a failure reproduces (splitmix64 -> [-1, 1)).
struct Rng {
  std::uint64_t s;
  double Next() {
    std::uint64_t z = (s += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    z ^= z >> 31;
    return 2.0 * static_cast<double>(z >> 11) * 0x1.0p-53 - 1.0;
  }
};

// The largest |v[i]| and the largest |a[i] - b[i]| over n entries (0 for n = 0): the scale and the
// error of a tangent checked against differences.
inline double MaxAbs(const double *v, int n) {
  double m = 0.0;
  for (int i = 0; i < n; ++i) m = std::fmax(m, std::fabs(v[i]));
  return m;
}

inline double MaxDiff(const double *a, const double *b, int n) {
  double m = 0.0;
  for (int i = 0; i < n; ++i) m = std::fmax(m, std::fabs(a[i] - b[i]));
  return m;
}

#define CHECK(cond, ...)                                                                           \
  do {                                                                                             \
    ++etfe_test::Checks();                                                                         \
    if (!(cond)) {                                                                                 \
      ++etfe_test::Failures();                                                                     \
      std::fprintf(stderr, "%s:%d: CHECK(%s) failed: ", __FILE__, __LINE__, #cond);                \
      std::fprintf(stderr, __VA_ARGS__);                                                           \
      std::fprintf(stderr, "\n");                                                                  \
    }                                                                                              \
  } while (0)

#define CHECK_CLOSE(a, b, rtol, atol)                                                              \
  CHECK(std::fabs((a) - (b)) <= (atol) + (rtol)*std::fabs(b), "%s = %.17g, %s = %.17g", #a,        \
        (double)(a), #b, (double)(b))

#define TEST_MAIN_END()                                                                            \
  do {                                                                                             \
    std::printf("%d checks, %d failed\n", etfe_test::Checks(), etfe_test::Failures());             \
    return etfe_test::Failures() ? 1 : 0;                                                          \
  } while (0)
