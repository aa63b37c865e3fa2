// Signals and the load stepper's safe points (see etfe/solver/interrupt.h). The handler notes the signal
// in a sig_atomic_t and nothing else; the ranks agree on it where they meet anyway: after each
// converged increment (SafePoint, one MPI_Allreduce of two ints that also carries rank 0's
// wall-clock checkpoint rule) and, once a signal is noted, in Newton's convergence test
// (InterruptGraceSpent), so every rank stops at the same increment and writes the same
// checkpoint.
#include <csignal>
#include <ctime>

#include "etfe/solver/interrupt.h"
#include "load_stepper_internal.h"

namespace etfe {

namespace {

constexpr int kCaught[4] = {SIGTERM, SIGINT, SIGUSR1, SIGXCPU};

struct Catching {
  bool on = false;
  struct sigaction before[4];
  double first_seen = -1.0;  // when this rank first saw the noted signal (monotonic s)
  bool gave_up = false;      // InterruptGraceSpent said so
} g_catching;

volatile sig_atomic_t g_noted = 0;

// The first signal is noted; a second one (of any of these) gets its default action at once:
// the user or the scheduler insists. No other work here (async-signal safety).
extern "C" void NoteSignal(int sig) {
  if (g_noted) {
    signal(sig, SIG_DFL);
    raise(sig);
    return;
  }
  g_noted = sig;
}

double MonotonicSeconds() {
  timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

} // namespace

PetscErrorCode InterruptCatch(bool on) {
  PetscFunctionBeginUser;
  if (on == g_catching.on) PetscFunctionReturn(0);
  for (int k = 0; k < 4; ++k) {
    if (on) {
      struct sigaction sa = {};
      sa.sa_handler = NoteSignal;
      sigemptyset(&sa.sa_mask);
      sa.sa_flags = SA_RESTART;  // a write or a wait under way goes on; the flag is read later
      PetscCheck(sigaction(kCaught[k], &sa, &g_catching.before[k]) == 0, PETSC_COMM_SELF, PETSC_ERR_SYS,
                 "cannot install the handler of %s", InterruptSignalName(kCaught[k]));
    } else
      sigaction(kCaught[k], &g_catching.before[k], nullptr);
  }
  g_catching.on = on;
  g_noted = 0;
  g_catching.first_seen = -1.0;
  g_catching.gave_up = false;
  PetscFunctionReturn(0);
}

PetscErrorCode InterruptHoldUntilExit() {
  PetscFunctionBeginUser;
  PetscCall(PetscPopSignalHandler());
  for (int sig : kCaught) signal(sig, SIG_IGN);
  PetscFunctionReturn(0);
}

int InterruptNoted() { return g_noted; }

const char *InterruptSignalName(int sig) {
  switch (sig) {
  case SIGTERM: return "SIGTERM";
  case SIGINT: return "SIGINT";
  case SIGUSR1: return "SIGUSR1";
  case SIGXCPU: return "SIGXCPU";
  default: return "a signal";
  }
}

PetscErrorCode InterruptGraceSpent(MPI_Comm comm, double grace, bool *spent) {
  PetscMPIInt size;
  int mine = 0, any;
  PetscFunctionBeginUser;
  *spent = false;
  if (!g_catching.on) PetscFunctionReturn(0);
  if (g_noted) {
    const double now = MonotonicSeconds();
    if (g_catching.first_seen < 0) g_catching.first_seen = now;
    mine = now - g_catching.first_seen > grace;
  }
  PetscCallMPI(MPI_Comm_size(comm, &size));
  if (size == 1) any = mine;
  else PetscCallMPI(MPI_Allreduce(&mine, &any, 1, MPI_INT, MPI_MAX, comm));
  *spent = any != 0;
  g_catching.gave_up = g_catching.gave_up || *spent;
  PetscFunctionReturn(0);
}

bool InterruptGaveUp() { return g_catching.gave_up; }

namespace load_stepping {

PetscErrorCode SafePoint(LoadStepper *s, bool *checkpoint, bool *stop) {
  PetscMPIInt size;
  PetscLogDouble now;
  PetscFunctionBeginUser;
  PetscCheck(!(s->P->rank == s->o.fail_alone[0] && s->step == s->o.fail_alone[1]), PETSC_COMM_SELF, PETSC_ERR_USER,
             "-etfe_test_fail_alone %" PetscInt_FMT ",%" PetscInt_FMT ": rank %d fails alone after increment %" PetscInt_FMT
             " (a test of one rank failing while the others wait)",
             s->o.fail_alone[0], s->o.fail_alone[1], s->P->rank, s->step);
  PetscCall(PetscTime(&now));
  // Rank 0's clock decides the wall-clock checkpoints: every rank must write the same one.
  int local[2] = {InterruptNoted(), s->P->rank == 0 && s->ck.every_s > 0 && now - s->checkpoint_time >= s->ck.every_s},
      agreed[2];
  PetscCallMPI(MPI_Comm_size(s->P->comm, &size));
  if (!g_catching.on && s->ck.every_s <= 0) agreed[0] = agreed[1] = 0;  // nothing to agree on
  else if (size == 1) agreed[0] = local[0], agreed[1] = local[1];
  else PetscCallMPI(MPI_Allreduce(local, agreed, 2, MPI_INT, MPI_MAX, s->P->comm));
  // By default a checkpoint at every stage end (the results file must exist to continue). After
  // the last increment there is nothing left to continue: no checkpoint, and a signal lets the
  // run complete.
  if (s->Finished()) PetscFunctionReturn(0);
  const bool stage_end = s->ck.stage_end && s->out && s->AtStageEnd();
  *checkpoint = s->checkpoint_step != s->step && (agreed[0] || agreed[1] || stage_end);
  if (agreed[0]) {
    s->res->interrupted = agreed[0];
    s->res->stopped = PETSC_TRUE;
    *stop = true;
  }
  PetscFunctionReturn(0);
}

PetscErrorCode StopWithinIncrement(LoadStepper *s, const Increment &inc, bool *stop) {
  int noted = InterruptNoted(), agreed;
  PetscFunctionBeginUser;
  *stop = !inc.Converged() && g_catching.gave_up;  // the same on every rank
  if (!*stop) PetscFunctionReturn(0);
  PetscCallMPI(MPI_Allreduce(&noted, &agreed, 1, MPI_INT, MPI_MAX, s->P->comm));
  s->res->interrupted = agreed;
  s->res->stopped = PETSC_TRUE;
  PetscFunctionReturn(0);
}

} // namespace load_stepping
} // namespace etfe
