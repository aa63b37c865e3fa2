// Whether the viscous stabilization left an equilibrium (see load_stepper_internal.h and
// docs/stabilization.md). A stabilized increment converges to a state where the film, the loads,
// the contact and the stabilizing force f = k (u - u_n) balance: f is the out-of-balance force of
// the unstabilized equations there. Where f only holds a slack region still while it moves (the
// fixed-arch saddles), its resultant and moment are a few per cent of the forces in play at most;
// where the film cannot carry the load (a free edge, a missing support), f carries it, and its
// resultant is a visible part of the loads. The first is accepted, the second is an attempt that
// failed: it is cut back like a diverged one (a slack region's stabilizing force shrinks with the
// increment, a carried load's does not), and the run stops, "not in equilibrium", once the
// cut-backs are spent. Over the run, the stabilizing force's work against the film's tells how
// far the load path was damped.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

#include "load_stepper_internal.h"

namespace etfe {
namespace load_stepping {

namespace {

double Norm3(const double v[3]) {
  return std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
}

// Scene node id and position of the largest nodal stabilizing force, for the messages.
std::string Where(const StabilizingForce &f) {
  char buf[160];
  std::snprintf(buf, sizeof buf, "%.3g N at node %lld, (%.0f, %.0f, %.0f) mm", f.largest,
                (long long)f.node, f.position[0], f.position[1], f.position[2]);
  return buf;
}

} // namespace

double ForceShare(const StabilizingForce &f) {
  const double R = Norm3(f.resultant), M = Norm3(f.moment);
  // Nothing from outside (a film with no load and no support): any force is all of it.
  const double inf = std::numeric_limits<double>::infinity();
  const double force = f.applied > 0 ? R / f.applied : (R > 0 ? inf : 0.0);
  const double moment = f.applied_moment > 0 ? M / f.applied_moment : (M > 0 ? inf : 0.0);
  return std::max(force, moment);
}

void CheckStabilizedIncrement(const LoadStepper &s, Increment *inc) {
  inc->unbalanced = inc->stabilized && inc->Converged() && s.o.stabilize_force_max > 0 &&
                    !(ForceShare(inc->stab) <= s.o.stabilize_force_max);
}

PetscErrorCode ReportUnbalancedIncrement(LoadStepper *s, const Increment &inc, bool exhausted) {
  const StabilizingForce &f = inc.stab;
  char what[700], buf[1400];
  PetscFunctionBeginUser;
  std::snprintf(what, sizeof what,
                "the viscous stabilization carrying %.3g of the forces in play (its resultant %.3g "
                "N and moment %.3g N mm against %.3g N of loads, contact forces and reactions "
                "summed over the nodes; "
                "-load_stabilize_force_max %g); its largest nodal force %s",
                ForceShare(f), Norm3(f.resultant), Norm3(f.moment), f.applied,
                (double)s->o.stabilize_force_max, Where(f).c_str());
  if (s->o.monitor)
    PetscCall(PetscPrintf(
        s->P->comm, "step %5lld  t %8.5f -> %.5f not in equilibrium: converged only with %s; %s\n",
        (long long)(s->step + 1), inc.t, inc.t_new, what,
        exhausted ? "the cut-backs are spent"
                  : ("cutting back to dt " + std::to_string(s->dt)).c_str()));
  if (!exhausted) PetscFunctionReturn(0);
  std::snprintf(buf, sizeof buf,
                "not in equilibrium: increment %lld (load time %.6g -> %.6g, after %lld cut-backs) "
                "converged only with %s. The film has a mechanism that the load moves there: a "
                "free edge, a missing support, a slack region that nothing holds, or a "
                "snap-through (no static path on). Ways out: hold it (-bc_<group>_fix, a rigid "
                "support), more increments (-load_increments, -load_max_cutbacks: the stabilizing "
                "force shrinks with the increment where an equilibrium is near), or accept the "
                "imbalance knowingly with a larger "
                "-load_stabilize_force_max",
                (long long)(s->step + 1), inc.t, inc.t_new, (long long)s->o.max_cutbacks, what);
  s->res->failure = buf;
  PetscFunctionReturn(0);
}

void AccountStabilizedIncrement(LoadStepper *s, const Increment &inc) {
  if (!inc.stabilized) return;
  ++s->res->stabilized;
  s->stab_work_total += inc.stab.work;
  s->stab_force_max = std::max(s->stab_force_max, inc.stab.largest);
  const double share = ForceShare(inc.stab);
  if (s->worst_stabilized.step < 0 || share > s->worst_stabilized.share) {
    s->worst_stabilized.step = s->step;
    s->worst_stabilized.share = share;
    s->worst_stabilized.force = inc.stab;
  }
}

PetscErrorCode StabilizationSummary(LoadStepper *s) {
  Problem *P = s->P;
  LoadStepperResult *res = s->res;
  const LoadStepperOptions &o = s->o;
  PetscReal reaction_max;
  PetscFunctionBeginUser;
  if (!res->stabilized) PetscFunctionReturn(0);
  // The work measure the run is judged by: against the increments' work magnitudes, so that a
  // load cycle (loading, then unloading) does not make the film's work vanish.
  const double work_share =
      s->work_magnitude > 0
          ? s->stab_work_total / s->work_magnitude
          : (s->stab_work_total > 0 ? std::numeric_limits<double>::infinity() : 0.0);
  PetscCall(VecMaxNodalNorm(P->reaction, &reaction_max));
  PetscCall(PetscPrintf(
      P->comm,
      "etfe: %" PetscInt_FMT
      " increments stabilized (-load_stabilize %g, -load_stabilize_when %s): the stabilizing force "
      "did %.3e N mm of work (%.2e of the work done on the film), largest "
      "nodal stabilizing force %.3e N (%.2e of the largest reaction)%s\n",
      res->stabilized, (double)o.stabilize, kStabilizeWhen[o.stabilize_when], s->stab_work_total,
      s->work_total != 0 ? s->stab_work_total / std::fabs(s->work_total) : 0.0, s->stab_force_max,
      reaction_max > 0 ? s->stab_force_max / reaction_max : 0.0,
      s->ck.restart[0] ? " since the restart" : ""));
  PetscCall(PetscPrintf(P->comm,
                        "etfe: equilibrium: the stabilizing force did %.2e of the work "
                        "(-load_stabilize_work_max %g) and carried at most %.2e of the forces in "
                        "play (increment %" PetscInt_FMT ", -load_stabilize_force_max %g)%s\n",
                        work_share, (double)o.stabilize_work_max, s->worst_stabilized.share,
                        s->worst_stabilized.step, (double)o.stabilize_force_max,
                        s->ck.restart[0] ? " since the restart" : ""));
  if (!res->failure.empty() || !s->Finished() || o.stabilize_work_max <= 0 ||
      work_share <= o.stabilize_work_max)
    PetscFunctionReturn(0);
  char buf[1024];
  std::snprintf(
      buf, sizeof buf,
      "not in equilibrium: over the run the viscous stabilization did %.3g of the work done on the "
      "film (%.3e of %.3e N mm, the increments' work magnitudes summed; -load_stabilize_work_max "
      "%g) in %lld stabilized increments%s; the largest share of the forces in play, %.3g, was in "
      "increment %lld, its largest nodal force %s. The load path was damped, not followed: the "
      "film has a mechanism (a free edge, a missing support, a slack region) that the "
      "stabilization held. Ways out: hold it (-bc_<group>_fix, a rigid support), more increments "
      "(-load_increments), or accept it knowingly "
      "with a larger -load_stabilize_work_max",
      work_share, s->stab_work_total, s->work_magnitude, (double)o.stabilize_work_max,
      (long long)res->stabilized, s->ck.restart[0] ? " since the restart" : "",
      s->worst_stabilized.share, (long long)s->worst_stabilized.step,
      Where(s->worst_stabilized.force).c_str());
  res->failure = buf;
  PetscFunctionReturn(0);
}

} // namespace load_stepping
} // namespace etfe
