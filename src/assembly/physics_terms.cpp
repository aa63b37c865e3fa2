// The registry of physics terms (physics_terms.h, physics_term.h): one line per term. Each term
// decides from the scene and its options whether the problem has it; its own file holds the rest.
//
// The order is the order in which the residual and the Jacobian sum the terms' parts, and a
// changed order changes the answers' last bits: the pressure loads (which read the chambers'
// pressures, evaluated in every term's Prepare before any term's forces), the chambers (made
// after the loads on their boundaries), the nodal forces, rigid contact; after the ghost sum the
// stabilization, then layer contact; the cables (new, last: their
// nodes' forces are added after all the others').
#include "physics_terms.h"

#include "etfe/assembly/assembly.h"
#include "etfe/assembly/cable_term.h"
#include "etfe/assembly/chamber.h"
#include "etfe/contact/contact.h"
#include "etfe/assembly/layer_contact.h"
#include "etfe/assembly/pressure_term.h"

namespace etfe {

PetscErrorCode MakePhysicsTerms(Problem *P, std::vector<std::vector<PetscInt>> *pressure_elements,
                                const std::vector<NodalForce> &forces) {
  PetscFunctionBeginUser;
  PetscCall(AddPressureTerm(P, pressure_elements));
  PetscCall(AddChamberTerm(P));
  PetscCall(AddNodalForceTerm(P, forces));
  PetscCall(AddContactTerm(P));
  PetscCall(AddStabilizationTerm(P));
  PetscCall(AddLayerContactTerm(P));
  PetscCall(CableTermAdd(P));
  PetscFunctionReturn(0);
}

TermSolverNeeds ProblemSolverNeeds(const Problem &P) {
  TermSolverNeeds all;
  for (const auto &term : P.terms) {
    const TermSolverNeeds n = term->SolverNeeds();
    all.krylov_outer |= n.krylov_outer;
    all.penalty |= n.penalty;
    if (!all.outer)
      all.outer = n.outer; // one term at most has its own outer matrix (the chambers')
  }
  return all;
}

// In the order the terms write them (MakePhysicsTerms).
const std::vector<TermDatasetInfo> &TermCheckpointDatasets() {
  static const std::vector<TermDatasetInfo> all = {ChamberSet::kCheckpoint, ContactSet::kCheckpoint,
                                                   LayerContactSet::kCheckpoint, kCableCheckpoint};
  return all;
}

bool TermsReportLastEvaluation(const Problem &P) {
  for (const auto &term : P.terms)
    if (term->ReportsLastEvaluation()) return true;
  return false;
}

} // namespace etfe
