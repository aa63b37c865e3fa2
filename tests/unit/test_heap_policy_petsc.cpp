// Freed memory goes back to the system (src/app/heap_policy.h). Linked with PETSc, so the library
// constructors of a real run have run (Debian's libsuperlu_dist turns mmap off in one):
//  * as loaded, whether a freed 64 MB block stays resident is printed (the library's setting);
//  * after HeapReleaseLargeBlocks, what the heap kept is returned at the next free, and a 64 MB block is mapped on its own (mallinfo2's hblkhd grows by
//    it) and the resident memory falls back by it when it is freed;
//  * a block below the threshold stays in the heap (reused without new page faults).
#include <malloc.h>
#include <petscsys.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "../../src/app/heap_policy.h"
#include "check.h"

static double ResidentMB() {
  long pages = 0, resident = 0;
  FILE *f = std::fopen("/proc/self/statm", "r");
  if (!f) return -1.0;
  if (std::fscanf(f, "%ld %ld", &pages, &resident) != 2) resident = -1;
  std::fclose(f);
  return resident * (double)sysconf(_SC_PAGESIZE) / (1 << 20);
}

static double MappedMB() { return mallinfo2().hblkhd / double(1 << 20); }

struct Cycle {
  double mapped_while_held, resident_gain, resident_kept;  // MB
};

// Allocate and touch n bytes, then free them; what was mapped and resident on the way.
static Cycle AllocTouchFree(size_t n) {
  Cycle c;
  const double r0 = ResidentMB(), m0 = MappedMB();
  char *p = static_cast<char *>(std::malloc(n));
  if (!p) return {0, 0, 0};
  std::memset(p, 1, n);
  asm volatile("" : : "r"(p) : "memory");  // keep the compiler from eliding the block
  c.mapped_while_held = MappedMB() - m0;
  c.resident_gain = ResidentMB() - r0;
  std::free(p);
  c.resident_kept = ResidentMB() - r0;
  return c;
}

int main(int argc, char **argv) {
  // PETSc (and the libraries it loads, whose constructors a real run has had) initialised as in
  // a run.
  if (PetscInitialize(&argc, &argv, nullptr, nullptr)) return 1;
  const size_t big = 64u << 20, small = 8u << 20;
  const Cycle before = AllocTouchFree(big);
  std::printf("as loaded: a freed 64 MB block leaves %.1f MB resident (mapped on its own: %.1f MB)%s\n",
              before.resident_kept, before.mapped_while_held,
              before.mapped_while_held < 1 ? " -- a library turned mmap off" : "");

  CHECK(etfe::HeapReleaseLargeBlocks(), "mallopt refused the policy");
  // The block freed above is still at the heap's top: it is reused, and freed again it is trimmed.
  const double r0 = ResidentMB();
  const Cycle reuse = AllocTouchFree(big);
  std::printf("with the policy, the heap's free top: resident +%.1f MB while held, %.1f MB from the start after free\n",
              reuse.resident_gain, ResidentMB() - r0);
  CHECK(ResidentMB() - r0 <= -60.0, "the kept 64 MB are returned (%.1f MB)", ResidentMB() - r0);
  const Cycle after = AllocTouchFree(big);
  std::printf("with the policy, a new block: mapped %.1f MB, resident +%.1f MB while held, %.1f MB left after free\n",
              after.mapped_while_held, after.resident_gain, after.resident_kept);
  CHECK(after.mapped_while_held >= 63.9, "a 64 MB block is mapped on its own (%.1f MB mapped)", after.mapped_while_held);
  CHECK(after.resident_gain >= 60.0, "touching it makes it resident (+%.1f MB)", after.resident_gain);
  CHECK(after.resident_kept <= 4.0, "freeing it returns it (%.1f MB left)", after.resident_kept);

  const Cycle below = AllocTouchFree(small);
  CHECK(below.mapped_while_held < 1.0, "an 8 MB block stays in the heap (%.1f MB mapped)", below.mapped_while_held);
  if (PetscFinalize()) return 1;
  TEST_MAIN_END();
}
