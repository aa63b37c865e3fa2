// The largest committed equivalent plastic strain of the film and where it is: the load stepper
// warns when it leaves the range of the small-strain yield law (the additive split of the
// Green-Lagrange strain holds for small plastic strains only).
#include <mpi.h>

#include "etfe/assembly/assembly.h"

namespace etfe {

PetscErrorCode LargestPlasticStrain(Problem *P, double *value, PetscInt *element, double centroid[3]) {
  const LocalMesh &m = P->mesh;
  const int nh = P->history_size;
  struct {
    double v;
    int rank;
  } mine = {-1.0, (int)P->rank}, best;
  PetscInt local = -1;
  PetscFunctionBeginUser;
  for (PetscInt e = 0; nh > 0 && e < m.num_elements; ++e) {
    double ep[3], ep_bar = 0.0;
    if (P->MaterialOf(e).PlasticStrain(&P->history[(size_t)nh * e], ep, &ep_bar) && ep_bar > mine.v)
      mine.v = ep_bar, local = e;
  }
  PetscCallMPI(MPI_Allreduce(&mine, &best, 1, MPI_DOUBLE_INT, MPI_MAXLOC, P->comm));
  double where[4] = {0, 0, 0, -1};  // centroid and natural id, from the rank that has it
  if (best.rank == P->rank && local >= 0) {
    for (int a = 0; a < 3; ++a)
      for (int i = 0; i < 3; ++i) where[i] += m.X[3 * m.tri[3 * local + a] + i] / 3.0;
    where[3] = (double)m.element_natural[local];
  }
  PetscCallMPI(MPI_Bcast(where, 4, MPI_DOUBLE, best.rank, P->comm));
  *value = best.v < 0 ? 0.0 : best.v;
  *element = (PetscInt)where[3];
  for (int i = 0; i < 3; ++i) centroid[i] = where[i];
  PetscFunctionReturn(0);
}

} // namespace etfe
