// The project's phases as PETSc log events (class "ETFE"), so -log_view says where a run's time
// goes: residual and Jacobian assembly, the contact pairs inside them, the tangent predictor, the
// load increment (predictor + Newton), results output and checkpoints, and the preconditioning
// matrix of the regularized AMG path. scripts/bench-scaling reads them.
#pragma once

#include <petscsys.h>

namespace etfe {

struct LogEventIds {
  PetscLogEvent residual, jacobian, contact, predictor, increment, output, checkpoint, pmat;
};

// The event ids, registered on first use (after PetscInitialize; the same order on every rank).
const LogEventIds &LogEvents();

} // namespace etfe
