// -structure_check capstan (docs/theory.md §5.6, thesis §5.2): a film strip over a fixed pipe, tension T1 on
// end A, end B pulled along its tangent through gross slip. T2 is the reaction at end B (node
// group right) along its pull direction; once every contact pair slips, Euler's belt formula
// predicts T2 = T1 exp(mu theta). Each increment (at the monitor's rate, and at the slip onset)
// prints T2 and the slipping pairs; the report prints T2 at the slip onset and
// mu_eff = ln(T2/T1)/theta against the friction coefficient.
#include <petscsys.h>

#include <cmath>
#include <string>
#include <vector>

#include "etfe/assembly/assembly.h"
#include "etfe/contact/contact.h"
#include "structure_inputs.h"

namespace etfe {

namespace {

// The check's state: T2 at the slip onset, its step, T2 at the last increment.
enum { kOnsetT2, kOnsetStep, kLastT2, kStateSize };

PetscErrorCode EndBTension(Problem *P, const CheckInput &ck, const std::vector<char> &is_b, double *t2) {
  const PetscScalar *r;
  double mine = 0.0;
  PetscFunctionBeginUser;
  PetscCall(VecGetArrayRead(P->reaction, &r));
  for (PetscInt l = 0; l < P->mesh.num_owned; ++l)
    if (is_b[l])
      for (int i = 0; i < 3; ++i) mine += r[3 * l + i] * ck.tB[i];
  PetscCall(VecRestoreArrayRead(P->reaction, &r));
  PetscCallMPI(MPI_Allreduce(&mine, t2, 1, MPI_DOUBLE, MPI_SUM, P->comm));
  PetscFunctionReturn(0);
}

} // namespace

std::vector<double> CapstanCheckStart() { return std::vector<double>{-1.0, -1.0, 0.0}; }

PetscErrorCode CapstanCheckStep(Problem *P, const CheckInput &ck, std::vector<double> *state, PetscInt step, double t,
                                PetscInt print_every) {
  double t2;
  PetscInt local[2] = {0, 0}, global[2];
  std::vector<char> is_b;
  std::vector<double> &s = *state;
  PetscFunctionBeginUser;
  const ContactSet *contact = FindTerm<ContactSet>(*P);
  PetscCheck(contact, P->comm, PETSC_ERR_ARG_WRONG,
             "-structure_check capstan needs the pipe: a rigid support (-structure_rigid) the strip slides on");
  PetscCall(ProblemNodeSetFlags(P, "right", &is_b));
  PetscCall(EndBTension(P, ck, is_b, &t2));
  for (const ContactPair &pr : contact->pairs) {
    if (is_b[pr.local_node]) continue;  // held by the grip: their slide is prescribed
    local[0] += pr.committed.status != CONTACT_OPEN;
    // Slipping, or sticking at the Coulomb limit: the lagged law commits a slipping pair whose
    // node stopped or turned back within the increment as sticking with its force still on the
    // cone (kernels/contact_law.cpp), so in gross slip pairs pass between the two; either way
    // their friction is fully mobilised. (The implicit law's sticking pairs lie inside the cone.)
    const ContactPairReport r = ContactReport(*contact, pr);
    const double limit = contact->params.mu * std::fabs(r.force[2]);
    local[1] += pr.committed.status == CONTACT_SLIP ||
                (pr.committed.status == CONTACT_STICK && std::hypot(r.force[0], r.force[1]) >= limit * (1.0 - 1e-9));
  }
  PetscCallMPI(MPI_Allreduce(local, global, 2, MPIU_INT, MPI_SUM, P->comm));
  s[kLastT2] = t2;
  const bool gross = global[0] > 0 && global[1] == global[0];
  if (gross && s[kOnsetStep] < 0 && t > 1.0) s[kOnsetStep] = (double)step, s[kOnsetT2] = t2;
  const bool onset = s[kOnsetStep] == (double)step;
  // Thinned like the progress line (-load_monitor n); the slip onset is always shown.
  if (print_every > 0 && (step % print_every == 0 || onset))
    PetscCall(PetscPrintf(P->comm,
                          "             capstan: T2 = %.6e N, T2/T1 = %.6f, slipping pairs %" PetscInt_FMT
                          "/%" PetscInt_FMT "%s%s\n",
                          t2, t2 / ck.t1, global[1], global[0], gross ? " (gross slip)" : "",
                          onset ? (" <- slip onset at step " + std::to_string(step)).c_str() : ""));
  PetscFunctionReturn(0);
}

PetscErrorCode CapstanCheckReport(Problem *P, const CheckInput &ck, std::vector<double> *state) {
  const std::vector<double> &s = *state;
  PetscFunctionBeginUser;
  PetscCheck(s[kOnsetStep] >= 0, P->comm, PETSC_ERR_NOT_CONVERGED,
             "capstan: no gross slip by the end of the pull (T2/T1 = %.4f); pull end B further", s[kLastT2] / ck.t1);
  const double mu_eff = std::log(s[kOnsetT2] / ck.t1) / ck.theta;
  const double mu = FindTerm<ContactSet>(*P)->params.mu;
  PetscCall(PetscPrintf(P->comm,
                        "capstan: theta = %.6f rad, T1 = %.6e N, T2 at slip onset = %.6e N (step %" PetscInt_FMT "), "
                        "T2 at the end = %.6e N, exp(mu theta) = %.6f\n",
                        ck.theta, ck.t1, s[kOnsetT2], (PetscInt)s[kOnsetStep], s[kLastT2], std::exp(mu * ck.theta)));
  PetscCall(PetscPrintf(P->comm, "mu_eff = %.8f\n", mu_eff));
  PetscCall(PetscPrintf(P->comm, "capstan: mu = %.6f, relative_error = %.3e\n", mu,
                        mu > 0 ? std::fabs(mu_eff - mu) / mu : std::fabs(mu_eff)));
  PetscFunctionReturn(0);
}

} // namespace etfe
