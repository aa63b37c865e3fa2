// A C++ context owned by a PETSc object (a callback's state that must live as long as the SNES or
// KSP that calls it): composed under a name, deleted when the object is destroyed.
#pragma once
#include <petscsys.h>

namespace etfe {

template <class T>
PetscErrorCode DeleteOwnedContext(void *ctx) {
  delete static_cast<T *>(ctx);
  return 0;
}

template <class T>
PetscErrorCode ComposeOwnedContext(PetscObject obj, const char *name, T *ctx) {
  PetscContainer holder;
  PetscFunctionBeginUser;
  PetscCall(PetscContainerCreate(PetscObjectComm(obj), &holder));
  PetscCall(PetscContainerSetPointer(holder, ctx));
  PetscCall(PetscContainerSetUserDestroy(holder, DeleteOwnedContext<T>));
  PetscCall(PetscObjectCompose(obj, name, (PetscObject)holder));
  PetscCall(PetscContainerDestroy(&holder));
  PetscFunctionReturn(0);
}

} // namespace etfe
