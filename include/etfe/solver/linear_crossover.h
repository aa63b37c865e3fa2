// Where the scalable path overtakes the direct one, as measured on this machine: the data the
// automatic linear-path choice (linear_path.h) reads. Each row is one size and rank count run
// with both paths in one sequence (scripts/bench-solvers, docs/solvers.md); a crossover is
// taken only where the measurements show it, never extrapolated past the largest size measured.
#pragma once
#include <petscsys.h>

namespace etfe {

struct CrossoverRow {
  int ranks;
  PetscInt dof;
  const char *krylov;          // options/solvers/<krylov>.opts, against MUMPS LU
  double direct_cpu, krylov_cpu;  // CPU seconds (user + system) of the same run
  const char *source;          // the case and where it is documented
};

struct Crossover {
  PetscInt dof = 0;           // the smallest measured DOF from which the Krylov path was faster at every
                              // larger measured size; 0: none measured
  PetscInt measured_max = 0;  // the largest DOF measured on that rank count (0: none)
  int rows = 0;
};

// The crossover of `krylov` on `ranks` ranks from the rows measured with exactly that many:
// from the largest size down, the sizes at which the Krylov path took less CPU time than the
// direct one; a size where it did not ends the run of them.
Crossover CrossoverOf(const CrossoverRow *rows, int n, int ranks, const char *krylov);
// The same over this machine's measurements (linear_crossover.cpp).
Crossover MeasuredCrossover(int ranks, const char *krylov);

} // namespace etfe
