// See rank0.h.
#include "etfe/base/rank0.h"

namespace etfe {

PetscErrorCode Rank0Outcome(MPI_Comm comm, int ok, const std::string &err, PetscErrorCode code) {
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Bcast(&ok, 1, MPI_INT, 0, comm));
  if (ok) PetscFunctionReturn(0);
  std::string msg = err;
  int len = (int)msg.size();
  PetscCallMPI(MPI_Bcast(&len, 1, MPI_INT, 0, comm));
  msg.resize(len);
  PetscCallMPI(MPI_Bcast(msg.data(), len, MPI_CHAR, 0, comm));
  SETERRQ(comm, code, "%s", msg.c_str());
}

} // namespace etfe
