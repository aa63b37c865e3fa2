// A minimal test harness: each unit test is one executable; CHECK records a failure with its
// location and the program exits non-zero at the end (ctest counts it). No dependencies.
#pragma once
#include <cmath>
#include <cstdio>

namespace etfe_test {
inline int &Failures() { static int n = 0; return n; }
inline int &Checks() { static int n = 0; return n; }
} // namespace etfe_test

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
