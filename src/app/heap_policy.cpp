// See heap_policy.h.
#include "heap_policy.h"

#include <cctype>
#include <cstdlib>  // defines __GLIBC__ on glibc
#include <cstring>
#include <string>
#include <unistd.h>
#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace etfe {

bool HeapReleaseWanted(const std::vector<std::string> &args) {
  bool wanted = true;
  for (size_t i = 0; i + 1 < args.size(); ++i)
    if (args[i] == "-etfe_heap_release") {
      std::string v = args[i + 1];
      for (char &ch : v) ch = (char)std::tolower((unsigned char)ch);
      wanted = !(v == "0" || v == "false" || v == "no" || v == "off");
    }
  return wanted;
}

bool HeapReleaseLargeBlocks() {
#if defined(__GLIBC__)
  const int glibc_default_mmap_max = 65536, mmap_threshold = 32 << 20, trim_threshold = 64 << 20;
  return mallopt(M_MMAP_MAX, glibc_default_mmap_max) == 1 && mallopt(M_MMAP_THRESHOLD, mmap_threshold) == 1 &&
         mallopt(M_TRIM_THRESHOLD, trim_threshold) == 1;
#else
  return true;  // the mallopt this undoes is glibc's
#endif
}

void HeapRestartWithHugePages(char **argv) {
#if defined(__GLIBC__) && defined(__linux__)
  const char *guard = "ETFE_NO_REEXEC";
  if (std::getenv(guard)) return;
  const char *tunables = std::getenv("GLIBC_TUNABLES");
  if (tunables && std::strstr(tunables, "glibc.malloc.hugetlb")) return;
  const std::string old = tunables ? tunables : "";
  const std::string value = old.empty() ? "glibc.malloc.hugetlb=1" : old + ":glibc.malloc.hugetlb=1";
  if (setenv("GLIBC_TUNABLES", value.c_str(), 1) == 0 && setenv(guard, "1", 1) == 0) execv("/proc/self/exe", argv);
  // exec failed: go on without huge pages, the environment as it was
  unsetenv(guard);
  if (tunables) setenv("GLIBC_TUNABLES", old.c_str(), 1);
  else unsetenv("GLIBC_TUNABLES");
#else
  (void)argv;
#endif
}

} // namespace etfe
