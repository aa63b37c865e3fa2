// A case: what every run of an options file needs, the distributed problem with its material,
// membrane options, scene observer and contact set, the solver and the load-stepping options.
// Built by the app's one run and by each run of the drawing planner (plan_driver.h).
#pragma once
#include <petscsnes.h>

#include "etfe/analyses/formfind.h"
#include "etfe/solver/load_stepper.h"
#include "etfe/assembly/problem.h"
#include "etfe/description/scene.h"

namespace etfe {

struct Case {
  Problem *P = nullptr; // null while no scene is named
  SNES snes = nullptr;
  LoadStepperOptions lso;
  FormFindOptions ffo; // -analysis formfind only
  bool formfind = false;
};

// The analysis's material (stretch: from -material_*; formfind: the prescribed stress of
// -formfind_*), the membrane options, then the problem, the solver and the load-stepping options.
PetscErrorCode CreateCase(MPI_Comm comm, bool formfind, SceneSpec &&scene,
                          const SceneObserver &observer, Case *c);
// What CreateCase made (nothing when no scene was named).
PetscErrorCode CaseDestroy(Case *c);

} // namespace etfe
