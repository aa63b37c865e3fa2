// The measured crossover between the direct and the scalable path (etfe/solver/linear_crossover.h).
#include "etfe/solver/linear_crossover.h"

#include <algorithm>
#include <cstring>
#include <vector>

namespace etfe {

namespace {

// Hencky (options/hencky.opts, -mesh_rings n), CPU s of the whole run (user + system: the
// steadier figure on this shared machine, load average ~10 on 2 cores during these runs). First
// increment: scripts/bench-solvers --case hencky --sizes 60,130 --solvers
// mumps_lu,gmres_gamg_shifted --stop-after 1 (and mumps_lu,gmres_hypre_lean,mumps_lu,
// gmres_hypre_lean for the lean path): docs/solvers.md, "What the run picks". Five increments (2
// at 555 771 DOF): the table "Side by side on the clamped membrane" of docs/solvers.md. Rows of
// other rank counts go here as they are measured; a rank count without rows keeps the memory
// threshold.
const CrossoverRow kRows[] = {
    {1, 32943, "gmres_gamg_shifted", 1.8, 2.9, "hencky 60 rings, first increment"},
    {1, 153273, "gmres_gamg_shifted", 14.0, 20.3, "hencky 130 rings, first increment"},
    {1, 15501, "gmres_gamg_shifted", 1.4, 2.3, "hencky, 5 increments (docs/solvers.md)"},
    {1, 153273, "gmres_gamg_shifted", 29.0, 51.3, "hencky, 5 increments (docs/solvers.md)"},
    {1, 555771, "gmres_gamg_shifted", 107.0, 164.0, "hencky, first 2 increments (docs/solvers.md)"},
    {1, 32943, "gmres_hypre_lean", 2.1, 2.3, "hencky 60 rings, first increment (two runs each)"},
    {1, 153273, "gmres_hypre_lean", 12.05, 15.5, "hencky 130 rings, first increment (two runs each)"},
};

} // namespace

Crossover CrossoverOf(const CrossoverRow *all, int n, int ranks, const char *krylov) {
  Crossover c;
  std::vector<const CrossoverRow *> rows;
  for (int i = 0; i < n; ++i)
    if (all[i].ranks == ranks && !std::strcmp(all[i].krylov, krylov) && all[i].krylov_cpu > 0) rows.push_back(&all[i]);
  std::sort(rows.begin(), rows.end(), [](const CrossoverRow *a, const CrossoverRow *b) { return a->dof > b->dof; });
  c.rows = (int)rows.size();
  if (rows.empty()) return c;
  c.measured_max = rows.front()->dof;
  for (const CrossoverRow *r : rows) {
    if (!(r->krylov_cpu < r->direct_cpu)) break;
    c.dof = r->dof;
  }
  return c;
}

Crossover MeasuredCrossover(int ranks, const char *krylov) {
  return CrossoverOf(kRows, (int)(sizeof kRows / sizeof kRows[0]), ranks, krylov);
}

} // namespace etfe
