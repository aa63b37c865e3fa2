// The crossover rule the automatic linear-path choice reads (etfe/solver/linear_crossover.h): taken
// only where the measurements show the Krylov path faster at every larger size measured on the
// same rank count, never extrapolated; and the rows measured here give none on one rank.
#include "check.h"
#include "etfe/solver/linear_crossover.h"

using etfe::Crossover;
using etfe::CrossoverOf;
using etfe::CrossoverRow;

int main() {
  const CrossoverRow rows[] = {
      {1, 1000, "k", 1.0, 2.0, ""},  {1, 10000, "k", 10.0, 9.0, ""}, {1, 100000, "k", 100.0, 50.0, ""},
      {2, 1000, "k", 1.0, 0.5, ""},  {2, 10000, "k", 5.0, 6.0, ""},  {1, 100000, "other", 1.0, 0.5, ""},
      {4, 1000, "k", 1.0, 0.0, ""},  // not measured with the Krylov path yet
  };
  const int n = sizeof rows / sizeof rows[0];
  Crossover c = CrossoverOf(rows, n, 1, "k");
  CHECK(c.dof == 10000 && c.measured_max == 100000 && c.rows == 3, "1 rank: faster from 1e4 on (%ld, %ld, %d)",
        (long)c.dof, (long)c.measured_max, c.rows);
  c = CrossoverOf(rows, n, 2, "k");
  CHECK(c.dof == 0 && c.measured_max == 10000, "2 ranks: slower at the largest size measured: none (%ld)", (long)c.dof);
  c = CrossoverOf(rows, n, 3, "k");
  CHECK(c.dof == 0 && c.rows == 0, "3 ranks: nothing measured");
  c = CrossoverOf(rows, n, 4, "k");
  CHECK(c.dof == 0 && c.rows == 0, "a row without the Krylov path's time does not count");
  c = CrossoverOf(rows, n, 1, "other");
  CHECK(c.dof == 100000, "per Krylov path (%ld)", (long)c.dof);
  // This machine's rows (one rank, the scalable path): the direct path was faster at every size.
  c = etfe::MeasuredCrossover(1, "gmres_gamg_shifted");
  CHECK(c.rows > 0 && c.dof == 0, "one rank here: no crossover up to %ld DOF (%ld)", (long)c.measured_max,
        (long)c.dof);
  TEST_MAIN_END();
}
