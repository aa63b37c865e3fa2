// What the problem's physics asks of the linear solver (etfe/physics_term.h, TermSolverNeeds),
// read once when the solver is set up (etfe/linear_path.h). Until contact and the gas chambers
// are physics terms, this is the one place that derives it from them; then it is the union of
// the terms' SolverNeeds().
#pragma once
#include "etfe/physics_term.h"
#include "etfe/problem.h"

namespace etfe {

TermSolverNeeds ProblemSolverNeeds(const Problem &problem);

} // namespace etfe
