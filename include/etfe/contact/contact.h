// Node-to-rigid friction contact as a component of the problem (options -contact_*). Exists
// only when the scene has supports: without contact no pairs, state or output are allocated.
// Each pair lives on the rank that owns its film node; its frame is fixed at t0 (the thesis's
// Assumption 1, -contact_normal frozen).
#pragma once
#include <algorithm>
#include <cmath>

#include <petscsys.h>

#include <string>
#include <vector>

#include "etfe/kernels/contact_law.h"
#include "etfe/assembly/physics_term.h"
#include "etfe/description/scene.h"

namespace etfe {

struct Problem;

enum class FrictionLaw { Lagged, Implicit, None, Fixed };
// The laws' names in -contact_friction and in the printed lines, in FrictionLaw's order.
inline constexpr int kFrictionLawCount = 4;
inline constexpr const char *kFrictionLawNames[kFrictionLawCount] = {"lagged", "implicit", "none", "fixed"};

// The largest round-off floor of the penalty forces (1e2 eps k |u| sqrt(pairs)) the force-balance
// test may accept, as a fraction of the forces it balances: above it a penalty is refused.
constexpr double kPenaltyFloorMax = 0.05;
// That round-off floor [N] for penalties k [N/mm], displacements of size u [mm] and `pairs` pairs.
inline double PenaltyRoundoffFloor(double k, double u, PetscInt pairs) {
  return 1e2 * PETSC_MACHINE_EPSILON * k * u * std::sqrt((double)pairs);
}

struct ContactPair {
  PetscInt local_node;    // owned local node of the film
  PetscInt natural_node;  // scene node id
  PetscInt id;            // global pair id (pairs sorted by scene node id)
  int support;
  double M[3];            // master point on the support (global)
  double R[9];            // rows x0, y0, z0 (z0 = outward normal)
  double g0[3];           // gap at t0 (local), the origin of the reported slide
  double X[3];            // reference position of the film node
  double d0;              // distance to the support surface at t0 (round-off: taken as touching)
  // Its penalties are params.kn, kt times this: 1, or with -contact_penalty_length L0 its
  // tributary length along the contact line over L0 (a stiffness per unit length).
  double k_scale = 1.0;
  // Frozen frame: g and f local (contact_law.h). Following frame: g holds the node's
  // displacement and f the force, both global, so they survive the frame's motion.
  ContactState committed;
  ContactState trial;     // at the last evaluation: g, f, status
  // -contact_lagged_repeat: the committed state the increment began from, the one its last
  // converged solve used, and how often the pair's status changed within the increment.
  ContactState step_start, solved;
  int step_changes = 0;
};

// What a pair reports: force in its current frame, slide since t0 in the tangent plane (local
// x0, y0 and global X, Y).
struct ContactPairReport {
  double force[3], slide_local[2], slide_global[2];
  int status;
};

struct ContactSet : PhysicsTerm {
  ContactParameters params{};
  // -contact_<support>_mu: the friction coefficient of each support's pairs, in the order of
  // `supports` (empty: params.mu on every support, the single-coefficient run unchanged).
  std::vector<double> support_mu;
  // -contact_<support>_friction: a support's own law per stage (one entry: every stage), in the
  // order of `supports`; an empty entry, or none at all: the set's law (`law`, `stage_laws`).
  std::vector<std::vector<FrictionLaw>> support_laws;
  // The largest coefficient of any support (whether the slip tangent makes J non-symmetric).
  double MaxMu() const {
    double mu = params.mu;
    for (double m : support_mu) mu = std::max(mu, m);
    return mu;
  }
  FrictionLaw law = FrictionLaw::Implicit;  // the law of the first stage
  // -contact_friction a,b,c: the law of each stage (the last one holds for the stages after it);
  // empty when one law serves the whole run. A stage with "none" is frictionless (mu = 0).
  std::vector<FrictionLaw> stage_laws;
  // -contact_normal follow: the master point is the current closest point of the support and
  // the frame follows it (large slide); frozen: the thesis's frame fixed at t0.
  bool follow = false;
  std::vector<SupportSpec> supports;
  std::vector<ContactPair> pairs;  // this rank's pairs, by id
  PetscInt num_global = 0, pair_start = 0;
  // Up to this load time the pairs are frictionless: a film laid slack on a support has no
  // normal force, so its friction cone has no size; tensioning it first without friction (as
  // hanging weights do in the capstan rig) gives every pair its normal force. 0: friction from
  // the start.
  PetscReal frictionless_until = 0.0;
  std::vector<PetscInt> probe_nodes;  // scene node ids whose pair history goes to CSV
  // -contact_penalty_length L0 [mm]: kn, kt hold for a pair whose tributary length along its
  // contact line is L0 and scale with it (0: the same penalties for every pair, the thesis's).
  PetscReal penalty_length = 0.0;
  // The smallest and largest pair's k_scale, over all ranks (round-off floors take the stiffest).
  PetscReal k_scale_min = 1.0, k_scale_max = 1.0;
  // Lagged law: an increment whose commit would change a pair's status is solved again with the
  // new statuses, at most this many times (0: the thesis's algorithm, statuses from time t only).
  PetscInt lagged_repeat = 0;
  // The last commit's counts over all ranks: open, stick, slip, and pairs that lifted off; the
  // lift-offs since the last printed progress line.
  PetscInt counts[4] = {0, 0, 0, 0};
  PetscInt lifted_since_print = 0;

  // As a physics term (contact_term.cpp): pair forces in the local array, their stiffness, the
  // commit, the lagged law's repeats, the checkpoint's contact_state, the penalties' round-off
  // floor, the physics fingerprint's parameters, the rows of Layout::Pairs.
  const char *Name() const override { return "contact"; }
  PetscErrorCode AddLocalForces(Problem &, const PetscScalar *u, PetscScalar *f, int *status, double *external2) override;
  PetscErrorCode AddTangent(Problem &, Vec U, const PetscScalar *u, Mat A) override;
  PetscErrorCode Commit(Problem &, double t) override;
  // The block State writes (TermCheckpointDatasets).
  static const TermDatasetInfo kCheckpoint;
  PetscErrorCode State(const Problem &, std::vector<TermData> *blocks) const override;
  PetscErrorCode Restore(Problem &, const std::vector<TermData> &blocks) override;
  PetscInt RepeatLimit() const override { return lagged_repeat; }
  PetscErrorCode BeginRepeats(Problem &) override;
  PetscErrorCode Revise(Problem &, PetscInt *changed) override;
  PetscErrorCode UndoRevise(Problem &) override;
  PetscErrorCode ForceFloor(Problem &, Vec X, double fnorm, double tol, double *floor) override;
  void Fingerprint(Fnv64 &) const override;
  bool PairRows(PetscInt *num_global, PetscInt *first, std::vector<PetscInt> *ids) const override;
  TermSolverNeeds SolverNeeds() const override;
  // The penalties' line of the set-up report (with -contact_penalty_length), the probes' CSV,
  // the pair counts of the progress line, the stiff penalties' hint, and the supports that may hold rigid motions.
  PetscErrorCode SetupLines(const Problem &, std::vector<std::string> *lines) const override;
  PetscErrorCode IncrementOutput(Problem &, const std::string &stem, PetscInt step, double t) override;
  std::string Progress(bool printed) override;
  std::string LineSearchHint(const Problem &) const override;
  const char *RigidMotionHolder() const override { return "the rigid contact supports"; }
};

// The -contact_* options, read and range-checked once (collective). default_kn: the penalty when
// none is given (the thesis's 1e3 E h); default_search_tol: the scene's pair search distance.
struct ContactOptions {
  ContactParameters params;
  FrictionLaw law = FrictionLaw::Implicit;
  std::vector<FrictionLaw> stage_laws;  // as given (a law per stage when they differ)
  bool follow = false;
  PetscReal frictionless_until = 0.0, search_tol = 1e-6, penalty_length = 0.0;
  PetscInt lagged_repeat = 0;
  std::vector<PetscInt> probe_nodes;
  // -contact_mu as given (params.mu is 0 where the law is "none" throughout): a support with a
  // law of its own takes it.
  PetscReal mu_given = 0.3;
};
PetscErrorCode ContactOptionsFromCommandLine(MPI_Comm comm, double default_kn, double default_search_tol,
                                             ContactOptions *options);
// With the scene's supports: reads the -contact_* options, creates the pairs and adds the term
// (collective; nothing without supports).
PetscErrorCode AddContactTerm(Problem *problem);
// Force (global) and tangent of one pair at the film node's displacement u. The gap is
// g0 + R u rather than R (x - M): penalty gaps are tiny (f/kn) next to the coordinates, and
// the difference of positions would leave them with few significant digits.
int ContactEvaluate(const ContactSet &c, ContactPair &pair, const double u[3], double time,
                    double fglobal[3], double Kglobal[9]);
// After a converged increment: status update and cone correction (lagged), new committed state.
// Counts over all ranks: open, stick, slip, and pairs that lifted off in this increment.
PetscErrorCode ContactCommit(Problem *problem, PetscInt counts[4]);
// Lagged law solved to a status fixed point (-contact_lagged_repeat), between a converged solve
// of an increment and its commit. BeginStep: the increment's start state is the committed one.
// Revise: each closed pair whose commit would find the other of stick and slip gets the
// increment's state for that status (ContactLaggedRestartState); a pair on its second change is
// set to slip and kept there (a status that flips back and forth has its force on the cone
// either way, and slip puts it there without an overshoot to project). changed: pairs revised
// over all ranks (0: settled, or the lagged law is not in force at this time). UndoRevise: the
// states the last converged solve used (a solve with the revised statuses failed).
PetscErrorCode ContactLaggedBeginStep(Problem *problem);
PetscErrorCode ContactLaggedRevise(Problem *problem, PetscInt *changed);
PetscErrorCode ContactLaggedUndoRevise(Problem *problem);
// The law in force at load time t (stage s covers t in (s, s+1]): the set's, or on a support with
// a law of its own (-contact_<support>_friction) that one.
FrictionLaw ContactLawAt(const ContactSet &c, double time);
FrictionLaw ContactLawAt(const ContactSet &c, int support, double time);
ContactPairReport ContactReport(const ContactSet &c, const ContactPair &pair);
// Appends one line per probe pair to <stem>_contact_node<id>.csv, stem = the results file without
// its extension (written by the owning rank): step, time, status, slide x0/y0 (local), slide X/Y
// (global), force x0/y0/z0. Rows after a restart's step are dropped first (csv_history.h).
PetscErrorCode ContactWriteProbes(Problem *problem, const std::string &stem, PetscInt step, double time);

} // namespace etfe
