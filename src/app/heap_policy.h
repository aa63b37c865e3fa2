// Give freed memory back to the system. Debian's libsuperlu_dist (linked through PETSc, loaded
// whether or not SuperLU_DIST is used) calls mallopt(M_MMAP_MAX, 0) and mallopt(M_TRIM_THRESHOLD,
// -1) in a library constructor: every allocation then comes from the brk heap and nothing freed is
// ever returned. MUMPS allocates its multi-GB workspace anew at each factorization; at 10^6
// triangles on 2 ranks a freed workspace was split by smaller blocks, the next one was placed
// beyond it, and one rank's resident memory grew by ~1 GB (3.2 GB against the other rank's 2.2).
// Large blocks mapped on their own are returned at free instead.
#pragma once
#include <string>
#include <vector>

namespace etfe {

// Whether the run wants the heap released: -etfe_heap_release among the program's arguments
// (options files expanded) with 0, false, no or off turns it off, as PETSc reads a bool. Read
// here because the re-start below happens before PETSc is initialised.
bool HeapReleaseWanted(const std::vector<std::string> &args);

// Blocks of 32 MB and more (glibc's largest threshold; smaller ones stay in the heap and are
// reused) are mapped and unmapped on their own; the heap top is trimmed above 64 MB. Returns false
// when glibc refuses (other C libraries: true, nothing to undo).
bool HeapReleaseLargeBlocks();

// A freshly mapped block is faulted in page by page at each factorization; on a virtual machine a
// 4 KB fault cost ~20 us here and made MUMPS's numeric factorization 2.8x slower at 10^5
// triangles. glibc maps large blocks with transparent huge pages when its tunable
// glibc.malloc.hugetlb is 1, but reads tunables only at program start: so, before MPI starts,
// the program runs itself again once with the tunable added (unless the environment names it or
// ETFE_NO_REEXEC is set). Returns only when it did not re-run (nothing to do or exec failed).
void HeapRestartWithHugePages(char **argv);

} // namespace etfe
