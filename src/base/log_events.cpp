// The project's log events (log_events.h).
#include "etfe/base/log_events.h"

namespace etfe {

namespace {

PetscErrorCode RegisterLogEvents(LogEventIds *e) {
  PetscClassId id;
  PetscFunctionBeginUser;
  PetscCall(PetscClassIdRegister("ETFE", &id));
  PetscCall(PetscLogEventRegister("EtfeResidual", id, &e->residual));
  PetscCall(PetscLogEventRegister("EtfeJacobian", id, &e->jacobian));
  PetscCall(PetscLogEventRegister("EtfeContact", id, &e->contact));
  PetscCall(PetscLogEventRegister("EtfePredictor", id, &e->predictor));
  PetscCall(PetscLogEventRegister("EtfeIncrement", id, &e->increment));
  PetscCall(PetscLogEventRegister("EtfeOutput", id, &e->output));
  PetscCall(PetscLogEventRegister("EtfeCheckpoint", id, &e->checkpoint));
  PetscCall(PetscLogEventRegister("EtfePmatShift", id, &e->pmat));
  PetscFunctionReturn(0);
}

} // namespace

const LogEventIds &LogEvents() {
  // Registration fails only when PETSc cannot allocate its event table, and then the next PETSc
  // call fails too: the error code is not lost, only reported one call later.
  static LogEventIds ids = [] {
    LogEventIds e{};
    (void)RegisterLogEvents(&e);
    return e;
  }();
  return ids;
}

} // namespace etfe
