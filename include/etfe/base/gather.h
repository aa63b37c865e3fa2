// Every rank's few values, concatenated in rank order on every rank: what a look-up needs
// everywhere (contact pair nodes, the edges between them, the members of a node set).
#pragma once
#include <petscsys.h>

#include <type_traits>
#include <vector>

namespace etfe {

// Collective. *first (if given): where this rank's values start in *all.
template <class T>
PetscErrorCode AllGatherConcat(MPI_Comm comm, const std::vector<T> &mine, std::vector<T> *all, PetscInt *first = nullptr) {
  static_assert(std::is_trivially_copyable<T>::value, "only plain values travel as bytes");
  PetscMPIInt size, rank;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_size(comm, &size));
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscMPIInt n = (PetscMPIInt)(mine.size() * sizeof(T));
  std::vector<PetscMPIInt> counts(size), displs(size, 0);
  PetscCallMPI(MPI_Allgather(&n, 1, MPI_INT, counts.data(), 1, MPI_INT, comm));
  for (int r = 1; r < size; ++r) displs[r] = displs[r - 1] + counts[r - 1];
  all->resize((displs[size - 1] + counts[size - 1]) / sizeof(T));
  PetscCallMPI(MPI_Allgatherv(mine.data(), n, MPI_BYTE, all->data(), counts.data(), displs.data(), MPI_BYTE, comm));
  if (first) *first = displs[rank] / (PetscInt)sizeof(T);
  PetscFunctionReturn(0);
}

} // namespace etfe
