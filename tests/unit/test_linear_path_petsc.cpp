// The one linear-path decision (etfe/assembly/linear_path.h): from the options, the size and the rank
// count, the kind of path, the LU package and the memory estimate the other parts read; the
// options database gets the scalable path's settings and MUMPS's workspace margin, nothing else.
#include <petscsys.h>

#include <cstring>

#include "check.h"
#include "etfe/assembly/linear_path.h"

using etfe::LinearPath;

// One decision with `opts` (cleared afterwards), for dof DOF on PETSC_COMM_SELF.
static LinearPath Decide(const char *opts, PetscInt dof) {
  LinearPath path;
  if (PetscOptionsClear(nullptr) || PetscOptionsInsertString(nullptr, opts) ||
      etfe::DecideLinearPath(PETSC_COMM_SELF, dof, &path))
    CHECK(false, "DecideLinearPath with \"%s\" failed", opts);
  return path;
}

static bool OptionIs(const char *name, const char *value) {
  char v[64] = "";
  PetscBool set = PETSC_FALSE;
  PetscOptionsGetString(nullptr, nullptr, name, v, sizeof v, &set);
  return set && !std::strcmp(v, value);
}

int main(int argc, char **argv) {
  if (PetscInitialize(&argc, &argv, nullptr, nullptr)) return 1;
  using K = LinearPath::Kind;
  LinearPath p = Decide("", 5000);
  CHECK(p.kind == K::direct_lu && p.factor && !p.outer_krylov && p.mumps && !p.lu_native && !p.scalable,
        "default: MUMPS LU, preonly");
  CHECK(OptionIs("-mat_mumps_icntl_14", "200"), "MUMPS factors: its workspace margin 200 %%");
  CHECK(p.kb_per_dof == 2.5, "direct memory per DOF %g", p.kb_per_dof);

  p = Decide("-etfe_lu_native_max_dof 6000", 5000);
  CHECK(p.kind == K::direct_lu && p.lu_native && !p.mumps, "small on one rank: PETSc's LU");
  CHECK(!OptionIs("-mat_mumps_icntl_14", "200"), "PETSc's LU: no MUMPS margin written");

  p = Decide("-pc_factor_mat_solver_type mumps -etfe_lu_native_max_dof 6000", 5000);
  CHECK(p.mumps && !p.lu_native && p.lu_package_named, "a package named wins");

  p = Decide("", 3000000);
  CHECK(p.scalable && p.automatic && p.kind == K::krylov_amg && p.outer_krylov && !p.factor,
        "3e6 DOF: the scalable path, automatically");
  CHECK(OptionIs("-ksp_type", "fgmres") && OptionIs("-pc_type", "gamg") && OptionIs("-mat_type", "aij"),
        "the scalable path's method in the options");
  CHECK(p.kb_per_dof == 2.1 && p.mat_type_named, "GAMG memory per DOF %g", p.kb_per_dof);

  p = Decide("-ksp_type gmres -pc_type hypre", 3000000);
  CHECK(!p.scalable && p.kind == K::krylov_amg && p.krylov_named && p.kb_per_dof == 1.1,
        "a Krylov method named: kept at any size (BoomerAMG: AMG, lean memory)");

  p = Decide("-ksp_type gmres -pc_type bddc", 5000);
  CHECK(p.kind == K::unassembled && !p.mat_type_named, "BDDC: the unassembled path");

  p = Decide("-ksp_type gmres -pc_type bjacobi -sub_pc_type lu", 5000);
  CHECK(p.kind == K::krylov_other && p.kb_per_dof == 2.5 && !p.mumps,
        "block Jacobi with factored blocks: Krylov, a factorization's memory");

  p = Decide("-pc_type redundant", 5000);
  CHECK(p.kind == K::direct_lu && p.copies == 1.0 && !p.factor, "redundant LU on one rank: a direct solve, one copy");

  p = Decide("-etfe_solver direct", 3000000);
  CHECK(!p.scalable && p.kind == K::direct_lu, "-etfe_solver direct keeps LU at any size");

  p = Decide("", 5000);
  etfe::TermSolverNeeds needs;
  needs.krylov_outer = true;
  etfe::LinearPathTakeNeeds(&p, needs);
  CHECK(p.outer_krylov && p.kind == K::direct_lu, "the physics asks for an outer Krylov solve around LU");

  PetscOptionsClear(nullptr);
  PetscFinalize();
  TEST_MAIN_END();
}
