// The scene's loads as physics terms (assembly layer, src/assembly/pressure_term.cpp): follower
// pressures on groups of elements (a gas chamber's boundary takes the chamber's pressure) and
// dead forces at nodes. Each exists only when the scene has such loads.
#pragma once
#include <vector>

#include "etfe/assembly/physics_term.h"
#include "etfe/description/scene.h"

namespace etfe {

// One follower pressure load: its local elements and value.
struct FollowerPressure {
  std::vector<PetscInt> elements;
  ScheduledValue value;
  int chamber = -1; // the boundary of a gas chamber: its pressure (chamber.h) times sign
  double sign = 1.0;
};

struct PressureTerm : PhysicsTerm {
  std::vector<FollowerPressure> loads;
  const char *Name() const override { return "pressure"; }
  PetscErrorCode AddLocalForces(Problem &, const PetscScalar *u, PetscScalar *f, int *status,
                                double *external2) override;
  PetscErrorCode AddElementPressure(Problem &, std::vector<double> *pressure) override;
};

struct NodalForceTerm : PhysicsTerm {
  std::vector<PetscInt> owned_dof; // owned local DOFs
  std::vector<ScheduledValue> value;
  const char *Name() const override { return "nodal_forces"; }
  PetscErrorCode AddLocalForces(Problem &, const PetscScalar *u, PetscScalar *f, int *status,
                                double *external2) override;
};

// The pressure loads of the problem (empty without them).
const std::vector<FollowerPressure> &PressureLoads(const Problem &problem);

// Each with the loads of the scene on this rank: per pressure load its local elements
// (elements[k] moved from), the nodal forces on owned nodes; nothing when the scene has none.
PetscErrorCode AddPressureTerm(Problem *problem, std::vector<std::vector<PetscInt>> *elements);
PetscErrorCode AddNodalForceTerm(Problem *problem, const std::vector<NodalForce> &forces);

} // namespace etfe
