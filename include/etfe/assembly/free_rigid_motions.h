// The rigid motions of the film that its DOF constraints leave free (assembly layer,
// src/assembly/free_rigid_motions.cpp): the six rigid-body modes (three translations, three
// rotations) restricted to the constrained DOFs; a combination no constraint touches moves the
// whole film without a reaction. Nothing in the film resists it either (internal forces and
// follower pressures move along), so the equilibrium is not unique or does not exist: Newton
// meets a singular tangent, and the viscous stabilization would "carry" the load instead.
#pragma once
#include <string>
#include <vector>

#include "etfe/assembly/problem.h"

namespace etfe {

// One free rigid motion: a translation along `direction`, or a rotation about the axis along
// `direction` through `point` (mm).
struct RigidMotion {
  bool rotation = false;
  double direction[3] = {0, 0, 0};
  double point[3] = {0, 0, 0};
  std::string Describe() const; // "translation along x", "rotation about z through (0, 0, 30) mm"
};

// The free rigid motions at the film's position X + U (a basis of them, each as simple as the
// basis allows: an axis-aligned translation or a rotation about an axis-aligned axis where one
// is free). Collective.
PetscErrorCode FreeRigidMotions(Problem *problem, Vec U, std::vector<RigidMotion> *free);

// Before a load history: refuses (PetscCheck) a film whose DOF constraints leave a rigid motion
// free, naming the motions, the supported groups and the -bc_<group>_fix to add. Rigid contact
// supports may hold what the constraints do not: with them it only says what is free. refuse
// false (-load_check_supports false) prints the free motions instead of refusing. Collective.
PetscErrorCode CheckSupportsHoldRigidMotions(Problem *problem, Vec U, bool refuse);

} // namespace etfe
