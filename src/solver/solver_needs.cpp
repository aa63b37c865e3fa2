// What the problem's physics asks of the linear solver (etfe/solver_needs.h).
#include "etfe/solver_needs.h"

#include "etfe/chamber.h"
#include "etfe/contact.h"

namespace etfe {

TermSolverNeeds ProblemSolverNeeds(const Problem &P) {
  TermSolverNeeds needs;
  // Sealed gas chambers with their rank-one stiffness (-chamber_rank_one): Newton's matrix is the
  // sparse tangent plus U diag(c) U^T (chamber.h), which only a Krylov method around the sparse
  // tangent's preconditioner solves.
  needs.krylov_outer = P.chambers && P.chambers->may_seal;
  // A contact penalty stiffer than 1e5 E h delays pivots (MUMPS's workspace, ICNTL(14)).
  needs.penalty = P.contact && P.contact->params.kn > 1e5 * P.AxialStiffness();
  return needs;
}

} // namespace etfe
