// Error handlers and the error exit (error_handlers.h).
#include "error_handlers.h"

#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <sstream>
#include <string>

#include "etfe/output.h"

namespace etfe {

namespace {

// The first error of the run, for the results file's status, with the system's error number at
// that moment (HDF5's messages do not say that the disk is full; errno does).
struct FirstError {
  std::string message;
  int sys_errno = 0;
  bool set = false;
};

struct ErrorReporting {
  bool traceback = false;
  std::vector<OptionsFileRequirement> requirements;
  FirstError first;
} g_errors;

void RecordError(const char *mess) {
  FirstError &e = g_errors.first;
  if (e.set) return;
  e.sys_errno = errno;
  e.set = true;
  e.message = mess ? mess : "error";
  for (char &c : e.message)
    if (c == '\n') c = ' ';
}

// PETSc's conversion errors ("Input string abc has no integer value") do not say which option
// held the string: find it in the database.
void PrintOptionOfBadValue(const char *fun, const char *mess) {
  const char *lead = "Input string ";
  if (!mess || !fun || std::strncmp(fun, "PetscOptionsStringTo", 20) != 0 ||
      std::strncmp(mess, lead, 13) != 0)
    return;
  std::string bad(mess + 13);
  bad = bad.substr(0, bad.find(' '));
  char *all = nullptr;
  if (PetscOptionsGetAll(nullptr, &all) || !all) return;
  std::string names, prev;
  std::istringstream in(all);
  for (std::string tok; in >> tok; prev = tok)
    if (tok == bad && prev.size() > 1 && prev[0] == '-') names += " " + prev;
  PetscFree(all);
  if (!names.empty())
    (*PetscErrorPrintf)("  (the value of%s: give a number of the option's type, see -help)\n",
                        names.c_str());
}

// A message that names a file an options file requires, and the file is missing: the case
// starts from a surface another case makes.
void PrintRequirementHint(const char *mess) {
  if (!mess) return;
  std::error_code ec;
  for (const OptionsFileRequirement &r : g_errors.requirements) {
    if (!std::strstr(mess, r.file.c_str()) || std::filesystem::exists(r.file, ec)) continue;
    (*PetscErrorPrintf)(
        "  (%s requires it: make it with etfe -options_file %s, or run the case with "
        "scripts/run, which makes it first)\n",
        r.options_file.c_str(), r.maker.c_str());
    return;
  }
}

PetscErrorCode TracebackErrorHandler(MPI_Comm comm, int line, const char *fun, const char *file,
                                     PetscErrorCode n, PetscErrorType p, const char *mess,
                                     void *ctx) {
  if (p == PETSC_ERROR_INITIAL) RecordError(mess); // first: errno as the error left it
  const PetscErrorCode ierr = PetscTraceBackErrorHandler(comm, line, fun, file, n, p, mess, ctx);
  if (p == PETSC_ERROR_INITIAL) PrintRequirementHint(mess);
  return ierr;
}

// PETSc's default report repeats the whole option table and configure line, and where in the
// source the error was raised; a user needs the message and the way out.
PetscErrorCode ConciseErrorHandler(MPI_Comm, int, const char *fun, const char *, PetscErrorCode n,
                                   PetscErrorType p, const char *mess, void *) {
  if (p != PETSC_ERROR_INITIAL) return n;
  RecordError(mess);
  (*PetscErrorPrintf)("%s\n", mess ? mess : "(no message)");
  PrintOptionOfBadValue(fun, mess);
  PrintRequirementHint(mess);
  (*PetscErrorPrintf)(
      "  (-etfe_traceback: where it was raised in the code, and PETSc's full report)\n");
  return n;
}

PetscErrorCode ErrorHandler(MPI_Comm comm, int line, const char *fun, const char *file,
                            PetscErrorCode n, PetscErrorType p, const char *mess, void *ctx) {
  auto *reporting = static_cast<ErrorReporting *>(ctx);
  return (reporting->traceback ? TracebackErrorHandler : ConciseErrorHandler)(comm, line, fun, file,
                                                                              n, p, mess, nullptr);
}

} // namespace

PetscErrorCode ErrorHandlersPush(const std::vector<OptionsFileRequirement> &requirements) {
  PetscFunctionBeginUser;
  g_errors.requirements = requirements;
  PetscCall(PetscPushErrorHandler(ErrorHandler, &g_errors));
  PetscFunctionReturn(0);
}

void ErrorHandlersUseTraceback(bool traceback) {
  g_errors.traceback = traceback;
}

// Ranks waiting for a partner that failed alone never arrive; then the failed rank gives up
// after a while and the run is aborted. The communicator is never one a stuck collective call
// could be using.
bool AllRanksFailed(MPI_Comm agree) {
  int size = 1, done = 0;
  MPI_Request req;
  MPI_Comm_size(agree, &size);
  if (size == 1) return true;
  MPI_Ibarrier(agree, &req);
  for (const double t0 = MPI_Wtime(); !done && MPI_Wtime() - t0 < 10.0;) {
    MPI_Test(&req, &done, MPI_STATUS_IGNORE);
    if (!done) usleep(1000);
  }
  return done;
}

int ErrorExit(MPI_Comm agree, PetscErrorCode ierr) {
  PetscMPIInt size = 1;
  MPI_Comm_size(PETSC_COMM_WORLD, &size);
  // A reader must tell a dead run from a live one. Only when all ranks are here: a collective
  // write from one rank alone would hang.
  if (OutputIsOpen() && AllRanksFailed(agree)) {
    // The status is rank 0's message (ranks may word one failure differently).
    std::string why = g_errors.first.message;
    const int e = g_errors.first.sys_errno;
    if (e == ENOSPC || e == EDQUOT || e == EFBIG || e == EIO)
      why += std::string(" (") + std::strerror(e) + ")";
    unsigned long long n = why.size();
    MPI_Bcast(&n, 1, MPI_UNSIGNED_LONG_LONG, 0, agree);
    why.resize(n);
    MPI_Bcast(why.data(), (int)n, MPI_CHAR, 0, agree);
    PetscPushErrorHandler(PetscReturnErrorHandler, nullptr);
    if (OutputAbandon(why))
      (*PetscErrorPrintf)("etfe: the failure could not be recorded in the results status\n");
    PetscPopErrorHandler();
  } else if (OutputIsOpen()) {
    // The others wait in a collective call that will never complete: this rank records the
    // failure beside the results (readers take it for the file's "running"), then all end.
    PetscMPIInt rank = 0;
    MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
    const std::string note = OutputNoteFailure(g_errors.first.message + " (rank " + std::to_string(rank) + ")");
    (*PetscErrorPrintf)("etfe: the other ranks did not stop with this error (they wait elsewhere): %s; every rank "
                        "is ended now\n",
                        note.empty() ? "the failure of another rank is recorded"
                                     : ("the failure is recorded in " + note).c_str());
  }
  if (size > 1) MPI_Abort(PETSC_COMM_WORLD, (int)ierr);
  PetscFinalize();
  return (int)ierr;
}

} // namespace etfe
