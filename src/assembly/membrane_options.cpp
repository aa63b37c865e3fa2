// The membrane element's options (-membrane_*), read into the Problem before ProblemCreate: the
// assembly layer owns them because the residual and the tangent are what they change.
#include <petscsys.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "etfe/assembly/problem.h"

namespace etfe {

PetscErrorCode MembraneOptionsFromCommandLine(MPI_Comm comm, Problem *P) {
  PetscFunctionBeginUser;
  PetscOptionsBegin(comm, nullptr, "Membrane element", "Membrane");
  PetscCall(PetscOptionsReal("-membrane_thickness", "Film thickness h0 [mm]", "", P->thickness,
                             &P->thickness, nullptr));
  PetscCall(
      PetscOptionsReal("-membrane_min_area_ratio",
                       "Smallest current/reference area before an element counts as collapsed", "",
                       P->min_area_ratio, &P->min_area_ratio, nullptr));
  PetscCall(PetscOptionsReal(
      "-membrane_tangent_shift",
      "Tangent-only diagonal shift, relative to E h (slack starts; the answer is unchanged)", "",
      P->tangent_shift, &P->tangent_shift, nullptr));
  PetscCall(PetscOptionsBool(
      "-membrane_tangent_shift_adaptive",
      "Scale the tangent shift by |F_k|/|F_0| of the Newton solve, so it vanishes at convergence",
      "", P->tangent_shift_adaptive, &P->tangent_shift_adaptive, nullptr));
  PetscCall(PetscOptionsBool(
      "-membrane_tangent_tension_only",
      "Geometric stiffness from the tensile part of the stress only (wrinkling films; "
      "the answer is unchanged)",
      "", P->tangent_tension_only, &P->tangent_tension_only, nullptr));
  PetscCall(PetscOptionsBool(
      "-membrane_near_null_space",
      "Attach the 6 rigid-body modes of the nodal coordinates to the tangent as its near-null "
      "space (for -pc_type gamg; LU ignores it)",
      "", P->near_null_space, &P->near_null_space, nullptr));
  const char *wrinkling_models[] = {"none", "tension_field"};
  PetscInt wrinkling = P->wrinkling ? 1 : 0;
  PetscCall(PetscOptionsEList(
      "-membrane_wrinkling",
      "none: the film carries compression (thesis); tension_field: no compression, "
      "each element taut, wrinkled (uniaxial tension) or slack",
      "", wrinkling_models, 2, wrinkling_models[wrinkling], &wrinkling, nullptr));
  P->wrinkling = wrinkling == 1 ? PETSC_TRUE : PETSC_FALSE;
  PetscOptionsEnd();
  // PETSc reads "inf" and "nan" as numbers: refused here by name, not met later as a NaN.
  auto num = [](double x) {  // as typed: PETSc's %g would print 0 as "0." and inf as "inf."
    char buf[32];
    std::snprintf(buf, sizeof buf, "%g", x);
    return std::string(buf);
  };
  PetscCheck(P->tangent_shift >= 0 && std::isfinite(P->tangent_shift), comm, PETSC_ERR_ARG_OUTOFRANGE,
             "-membrane_tangent_shift %s: the shift is relative to E h and must be a finite number >= 0",
             num(P->tangent_shift).c_str());
  PetscCheck(P->thickness > 0 && std::isfinite(P->thickness), comm, PETSC_ERR_ARG_OUTOFRANGE,
             "-membrane_thickness %s: the film thickness must be a positive, finite number (mm)",
             num(P->thickness).c_str());
  PetscCheck(std::isfinite(P->min_area_ratio), comm, PETSC_ERR_ARG_OUTOFRANGE,
             "-membrane_min_area_ratio %s: not a finite number; give a ratio such as 1e-3",
             num(P->min_area_ratio).c_str());
  PetscFunctionReturn(0);
}

} // namespace etfe
