// Node-to-rigid penalty friction contact (docs/theory.md §5, thesis §4.2.2, eqs. 4.25-4.31).
// PETSc-free.
//
// A contact pair joins a film node S to a point M of a rigid support. Its local frame R (rows
// x0, y0, z0; z0 the outward normal of the support) maps global vectors to local ones. The gap
// g = R (u_S - u_M) (local); w = g[2] < 0 is penetration. The pair's force f (local) is the
// spring force: the slave node's internal-force residual gets R^T f and its tangent
// R^T (df/dg) R. In compression f[2] < 0.
#pragma once

namespace etfe {

enum ContactStatus : int { CONTACT_OPEN = 0, CONTACT_STICK = 1, CONTACT_SLIP = 2 };

struct ContactParameters {
  double kn;  // normal penalty [N/mm]
  double kt;  // tangential penalty [N/mm]
  double mu;  // Coulomb coefficient (>= 0)
};

// Committed state of a pair at the start of a load step.
struct ContactState {
  double g[3];   // gap at the start of the step (local)
  double f[3];   // force at the start of the step (local)
  int status;    // ContactStatus used for the step (lagged law) / found at the last commit
};

// Thesis law (eqs. 4.27, 4.29, 4.31): the status of the step is the committed one (decided from
// the forces at t). dg = g - committed.g.
//   stick: f = f_n + diag(kt, kt, kn) dg
//   slip : f_x = f_n,x - mu cos(a) kn dw, f_y = f_n,y - mu sin(a) kn dw, f_z = f_n,z + kn dw,
//          a = direction of (f_n,x, f_n,y) at t. The thesis prints "+ mu cos(a) kn dw" with the
//          pressure taken positive (Box 4.1); with f_z < 0 the minus makes |f_t| grow with |f_z|
//          and keeps a pair on the cone exactly on it. dfdg = [[0,0,-mu kn c],[0,0,-mu kn s],
//          [0,0,kn]] (eq. 4.31 with the normal axis flipped). A slip state with f_n,t = 0 and
//          mu > 0 has no direction: the step uses the stick springs tangentially.
//   open : f = 0, zero tangent; also when f_z would become >= 0 within the step (lift-off).
// f (3) and dfdg (3x3 row-major, df_i/dg_j at [3i+j], non-symmetric for slip; may be null).
void ContactLaggedForce(const ContactParameters &p, const ContactState &committed,
                        const double g[3], double f[3], double dfdg[9]);

// Whether a step from `committed` runs the slip law (4.29) with friction: a slip status with
// mu > 0 and a tangential force to give its direction. A slip status without one runs the stick
// springs tangentially, as a stick status does.
bool ContactLaggedRunsSlip(const ContactParameters &p, const ContactState &committed);

// Between load steps (thesis Fig. 4.4): the status and force of the next step, decided at the
// converged gap g from an elastic trial. committed is the state the step started from (next may
// alias it). For a step that ran the stick springs the trial is the converged force f; for a
// slip step it is f_n,t + kt (g_t - g_n,t). With the converged f_z: trial outside the cone
// (|f_t*| >= mu |f_z| (1 - 1e-12)) slips, its force put on the cone along the trial (the
// direction follows the motion); trial inside, or a slip step whose trial points against the
// committed force (the node turned back), sticks with the converged force f. Open if
// f_z >= 0; f_z >= 0 with a penetrating gap (w < 0) re-closes the pair: stick,
// f = (0, 0, kn w). Writes next (g = the converged gap). Start pairs from {g, f = 0, STICK}:
// committing f = 0 at w = 0 gives OPEN, which the lagged law keeps force-free for a whole step.
void ContactLaggedCommit(const ContactParameters &p, const ContactState &committed, const double g[3],
                         const double f[3], ContactState *next);

// The commit of the lagged law solved to a status fixed point: ContactLaggedCommit, except that a
// pair that slipped through the step and slips on keeps its direction (eq. 4.28's alpha) and the
// converged force, which the slip law (4.29) left on the cone. Why: in a slip step the pair has no
// tangential stiffness, so its sideways motion answers the sideways part of its own friction
// force; taking the next direction from that motion (the elastic trial) amplifies a sideways
// component by about f / (k_film slide) per increment, which grows as the increments shrink
// (measured on the capstan: 1e-14 to 2e-13 of the force in three increments). The direction is
// set where the pair starts to slip, from its stick force.
void ContactLaggedCommitSettled(const ContactParameters &p, const ContactState &committed, const double g[3],
                                const double f[3], ContactState *next);

// Lagged law solved to a status fixed point (-contact_lagged_repeat): the state a step is solved
// again from when its commit found the pair `status` (STICK or SLIP) instead of the status it
// was solved with. start: the committed state the step began from; dir: the tangential force
// the commit found (its direction only is used). Stick: the start itself. Slip: the start's g and
// f_z with the tangential force on the cone of the start's pressure, mu |f_z|, along dir, so the
// slip law (4.29) keeps it on the cone through the step; with no direction (dir = 0) or no
// pressure the start's tangential force is kept. The status is `status`.
void ContactLaggedRestartState(const ContactParameters &p, const ContactState &start, int status, const double dir[2],
                               ContactState *step);

// Implicit law: Coulomb return map on the friction cone at the current gap.
//   normal: f_z = kn min(w, 0)              (open, f = 0, when w >= 0: lift-off)
//   trial : f_t* = f_n,t + kt (g_t - g_n,t)
//   stick if |f_t*| <= mu |f_z|, else slip: f_t = mu |f_z| f_t*/|f_t*|
//   (committed OPEN: f_n,t = 0 and g_n,t = committed g_t, the point where the pair touched down)
// f, dfdg (consistent, non-symmetric in slip; may be null) and the status found. With mu = 0
// the tangential force is zero (frictionless, status SLIP); a fixed support is the
// lagged/implicit law with mu = infinity (use ContactFixedForce).
int ContactImplicitForce(const ContactParameters &p, const ContactState &committed,
                         const double g[3], double f[3], double dfdg[9]);

// No slide: f = diag(kt, kt, kn) g, always closed (the thesis's "fixed" arch case).
void ContactFixedForce(const ContactParameters &p, const double g[3], double f[3], double dfdg[9]);

} // namespace etfe
