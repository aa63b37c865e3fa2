// Contact between film layers as a physics term (layer_contact.h).
#include "etfe/assembly/layer_contact.h"
#include "etfe/assembly/problem.h"

namespace etfe {

// After the ghost sum: the pairs couple nodes of any rank through the scattered master layer.
PetscErrorCode LayerContactSet::AddGlobalForces(Problem &P, Vec U, Vec F) {
  return LayerContactResidual(&P, U, F);
}

PetscErrorCode LayerContactSet::AddTangent(Problem &P, Vec U, const PetscScalar *, Mat A) {
  return LayerContactJacobian(&P, U, A);
}

// The pairs for the next increment (after the chambers' commit, which reads the pairs the
// increment was solved with).
PetscErrorCode LayerContactSet::Commit(Problem &P, double) {
  return LayerContactPair(&P, P.U);
}

// As after the checkpoint's increment.
PetscErrorCode LayerContactSet::Restarted(Problem &P) {
  return LayerContactPair(&P, P.U);
}

// The triangle each node keeps (pairing has hysteresis).
const TermDatasetInfo LayerContactSet::kCheckpoint = {"layer_pairs", Layout::Nodes, false, 1};

PetscErrorCode LayerContactSet::State(const Problem &P, std::vector<TermData> *blocks) const {
  std::vector<double> values;
  LayerContactStateGet(&P, &values);
  blocks->push_back(kCheckpoint.Block(std::move(values)));
  return 0;
}

PetscErrorCode LayerContactSet::Restore(Problem &P, const std::vector<TermData> &blocks) {
  if (const std::vector<double> *values = kCheckpoint.Find(blocks)) LayerContactStateSet(&P, *values);
  return 0;
}

PetscErrorCode LayerContactSet::Destroy(Problem &) {
  PetscFunctionBeginUser;
  PetscCall(VecScatterDestroy(&scatter));
  PetscCall(VecDestroy(&master_u));
  PetscFunctionReturn(0);
}

} // namespace etfe
