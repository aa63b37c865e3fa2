// Form finding (docs/theory.md §8, thesis §2.2): the equilibrium shape of a film carrying a
// prescribed membrane stress (isotropic, or MD:TD = s) inside prescribed boundaries.
//
// Method: updated reference strategy (Bletzinger & Ramm) in its force-density limit. Each
// iteration takes the current shape as the reference and solves for the shape in which the
// prescribed PK2 stress S0 (MD/TD frame of the reference) is in equilibrium; with S0 fixed the
// residual f_a = h A0 F S0 gradN_a is linear in x, so every iteration is one linear solve with
// the geometric stiffness (K_ab = h A0 (gradN_a . S0 gradN_b) I3: positive definite for a tensile
// S0 with the boundary held, so no in-plane drift mode). At the fixed point the reference is
// the current shape, F is the in-plane identity and the Cauchy stress equals S0: the thesis's
// geometric-stiffness iteration (eqs. 2.14-2.20) linearised at the current shape is the same
// step, which is why it is not offered separately.
#pragma once
#include <petscsnes.h>

#include "etfe/analyses/cutpattern.h"
#include "etfe/io/output.h"
#include "etfe/assembly/problem.h"

namespace etfe {

struct FormFindOptions {
  PetscReal stress = 1.0;     // prescribed TD stress [MPa] (only the ratio shapes the surface)
  PetscReal ratio = 1.0;      // MD:TD
  PetscInt max_iterations = 200;
  PetscReal tol = 1e-8;       // converged when the largest normal nodal move < tol * model size
  char mesh_out[PETSC_MAX_PATH_LEN] = "";  // Gmsh file of the found surface ("" = beside results)
  PetscInt monitor = 1;
  PetscBool mesh_control = PETSC_TRUE;  // interior nodes move along their normals only
  CutPatternOptions cutpattern;         // -cutpattern: flatten the found surface's strips
};

struct FormFindResult {
  PetscInt iterations = 0;
  double last_move = 0.0;
  PetscBool converged = PETSC_FALSE;
  std::string failure;
};

PetscErrorCode FormFindOptionsFromCommandLine(MPI_Comm comm, FormFindOptions *o);
PetscErrorCode FormFindRun(Problem *problem, SNES snes, OutputFile *out, const FormFindOptions &o,
                           FormFindResult *result);

} // namespace etfe
