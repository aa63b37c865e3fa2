// The linear solver path of a run, decided once: a sparse direct factorization (MUMPS or PETSc's
// own LU), a Krylov method with algebraic multigrid, another Krylov method, or the unassembled
// tangent with domain decomposition (BDDC). The memory check, the matrix format, the LU package
// and the outer Krylov solve all read this one decision instead of the options' strings, and the
// settings the path adds to the options database are written here alone.
//
// Two steps, because the matrix format and the memory check come before the problem exists and
// the physics is known only once it does: DecideLinearPath (options, system size, rank count)
// before the problem is built; LinearPathTakeNeeds (what the physics terms ask of the solver)
// when the solver is set up.
#pragma once
#include <petscsys.h>

#include <string>

#include "etfe/assembly/physics_term.h"

namespace etfe {

struct LinearPath {
  enum class Kind { direct_lu, krylov_amg, krylov_other, unassembled };
  Kind kind = Kind::direct_lu;
  // The Newton solve is a Krylov method (not KSP preonly): named by the options, or asked for by
  // the physics (a low-rank tangent part around the assembled matrix's preconditioner).
  bool outer_krylov = false;
  bool krylov_named = false;  // the options name a Krylov method (-ksp_type other than preonly)
  bool scalable = false;      // the scalable path's settings (FGMRES + GAMG) were put into the options
  bool automatic = false;     // ... by the automatic choice (-etfe_solver auto over a threshold)
  // The top-level preconditioner is a factorization (LU or Cholesky) and which package factors:
  // PETSc's own LU with AMD (small systems on one rank) or MUMPS, unless the options name one.
  bool factor = false;
  bool lu_native = false;
  bool lu_package_named = false;  // -pc_factor_mat_solver_type given: the options' package
  bool mumps = false;
  bool mat_type_named = false;  // the options name the matrix type (-mat_type)
  TermSolverNeeds needs;        // what the physics asked (LinearPathTakeNeeds)
  PetscInt dof = 0;
  PetscMPIInt ranks = 1;
  std::string why;  // one line: the path and why it was chosen
  // The path's peak memory per DOF as measured with this code (docs/solvers.md), what the memory
  // check estimates with, and how many times the whole system is held (PC redundant: once per
  // rank group).
  const char *memory_name = "a sparse direct factorization";
  double kb_per_dof = 2.5;
  double copies = 1.0;
};

const char *LinearPathKindName(LinearPath::Kind kind);

// -etfe_lu_native_max_dof: up to this many DOF on one rank, PETSc's own LU (0: always MUMPS).
PetscErrorCode LUNativeMaxDofFromOptions(MPI_Comm comm, PetscInt *max_dof);

// Reads -etfe_solver auto|direct|scalable, its thresholds and -etfe_lu_native_max_dof; where the
// scalable path is chosen, puts its settings into the options database and prints why; sets
// MUMPS's workspace margin where MUMPS factors; then classifies the path as PETSc builds it from
// the options (a KSP configured as the solver's). Collective; before the problem reads its
// options (the path names the matrix type and the near-null space).
PetscErrorCode DecideLinearPath(MPI_Comm comm, PetscInt dof, LinearPath *path);

// The physics' needs: a term that asks for an outer Krylov solve gets one (GMRES around the
// factorization when the options say preonly).
void LinearPathTakeNeeds(LinearPath *path, const TermSolverNeeds &needs);

} // namespace etfe
