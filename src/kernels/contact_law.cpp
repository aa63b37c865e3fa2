// Node-to-rigid penalty friction contact (docs/theory.md §5, thesis §4.2.2, eqs. 4.25-4.31).
//
// The pair's local gap is g = (u_g, v_g, w_g) = R (u_S - u_M); w < 0 is penetration. The force f
// is the spring force in the same frame, so f_z = kn w < 0 in compression and the normal
// pressure is |f_z| = -f_z. The Coulomb cone is |f_t| <= mu |f_z| with f_t = (f_x, f_y).
//
// Two laws share the committed state (g, f, status at the start of the step):
//
// * Lagged (the thesis's algorithm). The status of the whole step is the committed one (Assumption
//   3, eq. 4.26), so within a step the law is linear in the increment dg = g - g_n:
//     stick (4.27): f = f_n + diag(kt, kt, kn) dg. (The thesis prints kn on the x row and kt on
//                   the z row; that is a typo, eq. 4.31 and the text use kt tangential.)
//     slip  (4.29): f_z = f_n,z + kn dw,  f_t = f_n,t - mu kn dw (cos a, sin a),
//                   a = direction of f_n,t (4.28).
//   Sign of the slip increment: Box 4.1 writes f_gs = mu f_gz and then uses eq. (f),
//   |f_t| = mu |f_z|, as if f_z were the (positive) pressure. With our f_z < 0 in compression the
//   printed "+ mu cos(a) kn dw" would shrink |f_t| while |f_z| grows (dw < 0), which contradicts
//   (a)-(d). Written with magnitudes, |f_t|(t+dt) = mu (|f_n,z| - kn dw), i.e. the minus sign
//   above: a pair on the cone stays exactly on the cone for any dw. Eq. 4.31's matrix
//   T^T [[0,0,mu kn],[0,0,0],[0,0,kn]] T = [[0,0,mu kn c],[0,0,mu kn s],[0,0,kn]] is the same
//   statement in the variables (g_t, -w) -> (f_t, -f_z); in ours the tangential column flips:
//   df/dg = [[0,0,-mu kn c],[0,0,-mu kn s],[0,0,kn]].
//   Between steps ContactLaggedCommit applies the Fig. 4.4 correction and fixes the next step's
//   status (see there): an elastic trial decides stick or slip, slip puts it on the cone.
//
// * Implicit: the standard penalty return map at the current gap (no status lag), giving a
//   result independent of the step size for monotonic paths and the consistent tangent:
//     f_z = kn min(w, 0);  f_t* = f_n,t + kt (g_t - g_n,t);  t = f_t*/|f_t*|
//     slip: f_t = mu |f_z| t,  df_t/dg_t = (mu |f_z| kt / |f_t*|) (I - t t^T),  df_t/dw = -mu kn t
//   (the last from |f_z| = -kn w).
//
// Pure C++, no allocation; dfdg is 3x3 row-major, dfdg[3 i + j] = d f_i / d g_j.
#include "etfe/kernels/contact_law.h"

#include <cmath>

namespace etfe {

namespace {

// After the Fig. 4.4 projection |f_t| equals mu |f_z| only to rounding; without a tolerance the
// next commit could flip such a pair to stick at random and restart the tangential springs from
// the cone, so forces within this relative distance of the cone count as on it.
constexpr double kConeTol = 1e-12;

void ZeroForce(double f[3], double dfdg[9]) {
  for (int i = 0; i < 3; ++i) f[i] = 0.0;
  if (dfdg)
    for (int i = 0; i < 9; ++i) dfdg[i] = 0.0;
}

} // namespace

void ContactLaggedForce(const ContactParameters &p, const ContactState &committed,
                        const double g[3], double f[3], double dfdg[9]) {
  ZeroForce(f, dfdg);
  // An open pair stays force-free for the whole step; re-closing is decided at the commit.
  if (committed.status == CONTACT_OPEN) return;

  const double dg[3] = {g[0] - committed.g[0], g[1] - committed.g[1], g[2] - committed.g[2]};
  const double fz = committed.f[2] + p.kn * dg[2];
  // The thesis forbids opening (eq. 4.25); we let the pair lift off instead of pulling the film
  // back onto the support. fz = 0 stays closed (a film laid on the support starts with its
  // springs). Written as fz > 0 (not !(fz <= 0)) so a NaN gap propagates.
  if (fz > 0.0) return;
  f[2] = fz;
  if (dfdg) dfdg[8] = p.kn;

  const double ftn = std::hypot(committed.f[0], committed.f[1]);
  if (committed.status == CONTACT_SLIP && ftn > 0.0) {
    const double c = committed.f[0] / ftn, s = committed.f[1] / ftn;
    f[0] = committed.f[0] - p.mu * c * p.kn * dg[2];
    f[1] = committed.f[1] - p.mu * s * p.kn * dg[2];
    if (dfdg) {
      dfdg[2] = -p.mu * p.kn * c;
      dfdg[5] = -p.mu * p.kn * s;
    }
  } else if (committed.status == CONTACT_SLIP && p.mu == 0.0) {
    // Frictionless: slip with no tangential force, whatever the tangential motion.
    f[0] = committed.f[0];
    f[1] = committed.f[1];
  } else {
    // Stick, and also slip with a zero committed tangential force and mu > 0 (e.g. a pair that
    // starts at f = 0, where eq. 4.26 reads 0 < 0 and says slip): eq. 4.28 has no direction, so
    // the tangential springs carry the step and the commit puts the result back on the cone.
    f[0] = committed.f[0] + p.kt * dg[0];
    f[1] = committed.f[1] + p.kt * dg[1];
    if (dfdg) dfdg[0] = dfdg[4] = p.kt;
  }
}

bool ContactLaggedRunsSlip(const ContactParameters &p, const ContactState &committed) {
  return committed.status == CONTACT_SLIP && p.mu > 0.0 && std::hypot(committed.f[0], committed.f[1]) > 0.0;
}

// The Fig. 4.4 narrative (thesis L1342): a pair whose friction force exceeds mu |f_z| at t_i
// slides and its force is corrected onto the yield surface; "this correction will be stopped when
// the correction of friction force at t_j is smaller than the yield mu |f_z(t_j)|", and from t_j
// the pair sticks and its force follows the penalty springs (4.27).
// Followed: the status is fixed for a whole step (Assumption 3); a force past the cone is put back
// on it along its own direction and the pair slips; a slipping pair sticks again when its force
// at the commit is no longer pushed past the cone, and then follows the springs.
// Chosen, where the text is silent (with the consistent sign of 4.29 the slip law keeps the force
// exactly on the cone, so the converged force alone can never say "smaller than the yield"):
// * A slipping pair is tested with the elastic trial f_t* = f_n,t + kt (g_t - g_n,t), the force
//   the tangential springs would carry had it stuck through the step (the implicit law's and
//   plasticity's predictor). For a step that ran the stick springs it is the converged force.
// * Trial inside the cone (the node stopped, or the pressure grew past the pull): stick.
// * Trial against the committed direction (the node turned back): stick. Its motion in the step
//   was free (no tangential stiffness), so its direction says little about the film's pull; the
//   next step's springs measure that pull and send the pair into slip the other way if it is
//   large enough. Following such a trial straight away was tried and is unstable: the free
//   motion flips the friction, which flips the motion, and the capstan stopped earlier the more
//   increments it had (load time 1.75 at 40 increments, 1.03 at 2000).
// * Trial outside and forward: slip on, the force on the cone along the trial, so the direction
//   follows the motion and eq. 4.28 then reads it from the committed force.
// * A pair that sticks keeps the force it converged with (inside or on the cone), so the commit
//   adds no out-of-balance force; only the projection of an overshoot does, as in the thesis.
void ContactLaggedCommit(const ContactParameters &p, const ContactState &committed, const double g[3],
                         const double f[3], ContactState *next) {
  const bool ran_slip = ContactLaggedRunsSlip(p, committed);
  double trial[2] = {f[0], f[1]};
  bool reversed = false;
  if (ran_slip) {
    for (int i = 0; i < 2; ++i) trial[i] = committed.f[i] + p.kt * (g[i] - committed.g[i]);
    reversed = trial[0] * committed.f[0] + trial[1] * committed.f[1] <= 0.0;
  }
  for (int i = 0; i < 3; ++i) next->g[i] = g[i];

  if (f[2] >= 0.0) {
    // Open, unless the converged gap penetrates: then the pair re-closes at this gap, sticking,
    // with the normal spring force it would have had and no tangential memory.
    next->f[0] = next->f[1] = 0.0;
    if (g[2] < 0.0) {
      next->f[2] = p.kn * g[2];
      next->status = CONTACT_STICK;
    } else {
      next->f[2] = 0.0;
      next->status = CONTACT_OPEN;
    }
    return;
  }

  const double ft = std::hypot(trial[0], trial[1]);
  const double limit = p.mu * (-f[2]);
  next->f[0] = f[0];
  next->f[1] = f[1];
  next->f[2] = f[2];
  if (!reversed && ft >= limit * (1.0 - kConeTol)) {
    next->status = CONTACT_SLIP;
    // ft > limit >= 0 here, so the division is safe; mu = 0 projects to f_t = 0.
    if (ft > limit) {
      const double scale = limit / ft;
      next->f[0] = trial[0] * scale;
      next->f[1] = trial[1] * scale;
    }
  } else {
    next->status = CONTACT_STICK;
  }
}

void ContactLaggedCommitSettled(const ContactParameters &p, const ContactState &committed, const double g[3],
                                const double f[3], ContactState *next) {
  const bool ran_slip = ContactLaggedRunsSlip(p, committed);
  ContactLaggedCommit(p, committed, g, f, next);
  if (ran_slip && next->status == CONTACT_SLIP) next->f[0] = f[0], next->f[1] = f[1];
}

// Why the start's pressure: the step's force is f_n + K dg with K the slip tangent, so a force
// on the cone at the start stays on it at the end whatever dw the solve finds; the start's
// tangential force inside the cone (a sticking pair) is raised to the cone, the O(dt) error of
// deciding the status for the whole step.
void ContactLaggedRestartState(const ContactParameters &p, const ContactState &start, int status, const double dir[2],
                               ContactState *step) {
  *step = start;
  step->status = status;
  const double size = std::hypot(dir[0], dir[1]);
  if (status != CONTACT_SLIP || size <= 0.0 || start.f[2] >= 0.0) return;
  const double scale = p.mu * (-start.f[2]) / size;
  step->f[0] = scale * dir[0];
  step->f[1] = scale * dir[1];
}

int ContactImplicitForce(const ContactParameters &p, const ContactState &committed,
                         const double g[3], double f[3], double dfdg[9]) {
  ZeroForce(f, dfdg);
  const double w = g[2];
  if (w > 0.0) return CONTACT_OPEN;  // w = 0: closed with zero force, so a pair laid on
                                      // the support starts with its springs (no singular start)

  const double pressure = -p.kn * w;  // |f_z|
  f[2] = p.kn * w;
  if (dfdg) dfdg[8] = p.kn;
  if (p.mu == 0.0) return CONTACT_SLIP;

  // A pair that was open has no tangential history: it sticks where it touched down, which is
  // the committed gap (the pair is committed at the gap where it re-closes).
  const bool was_open = committed.status == CONTACT_OPEN;
  const double fnx = was_open ? 0.0 : committed.f[0];
  const double fny = was_open ? 0.0 : committed.f[1];
  const double trial[2] = {fnx + p.kt * (g[0] - committed.g[0]),
                           fny + p.kt * (g[1] - committed.g[1])};
  const double ft = std::hypot(trial[0], trial[1]);
  const double limit = p.mu * pressure;

  // A trial on the cone to round-off (a slipping pair at the first Newton iterate of the next
  // increment) sticks: its tangent is then the stick one, which gives a descent direction
  // whether the increment keeps slipping or reverses (as plasticity's elastic predictor does).
  if (ft <= limit * (1.0 + 1e-10)) {
    f[0] = trial[0];
    f[1] = trial[1];
    if (dfdg) dfdg[0] = dfdg[4] = p.kt;
    return CONTACT_STICK;
  }

  // ft > limit >= 0, so t is defined.
  const double tx = trial[0] / ft, ty = trial[1] / ft;
  f[0] = limit * tx;
  f[1] = limit * ty;
  if (dfdg) {
    const double r = p.kt * limit / ft;
    dfdg[0] = r * (1.0 - tx * tx);
    dfdg[1] = -r * tx * ty;
    dfdg[3] = -r * tx * ty;
    dfdg[4] = r * (1.0 - ty * ty);
    dfdg[2] = -p.mu * p.kn * tx;
    dfdg[5] = -p.mu * p.kn * ty;
  }
  return CONTACT_SLIP;
}

void ContactFixedForce(const ContactParameters &p, const double g[3], double f[3],
                       double dfdg[9]) {
  f[0] = p.kt * g[0];
  f[1] = p.kt * g[1];
  f[2] = p.kn * g[2];
  if (dfdg) {
    for (int i = 0; i < 9; ++i) dfdg[i] = 0.0;
    dfdg[0] = dfdg[4] = p.kt;
    dfdg[8] = p.kn;
  }
}

} // namespace etfe
