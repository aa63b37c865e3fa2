// printf-style appending for the pattern writers (DXF, SVG, CSV).
#pragma once
#include <cstdarg>
#include <cstdio>
#include <string>
#include <vector>

namespace etfe {

inline void Append(std::string *s, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
inline void Append(std::string *s, const char *fmt, ...) {
  char buf[512];
  va_list ap;
  va_start(ap, fmt);
  const int n = std::vsnprintf(buf, sizeof buf, fmt, ap);
  va_end(ap);
  if (n < (int)sizeof buf) {
    s->append(buf, n > 0 ? (size_t)n : 0);
    return;
  }
  std::vector<char> big((size_t)n + 1);
  va_start(ap, fmt);
  std::vsnprintf(big.data(), big.size(), fmt, ap);
  va_end(ap);
  s->append(big.data(), (size_t)n);
}

} // namespace etfe
