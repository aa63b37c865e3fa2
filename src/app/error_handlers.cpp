// Error handlers and the error exit (error_handlers.h).
#include "error_handlers.h"

#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <sstream>
#include <string>

#include "etfe/io/output.h"

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

// HDF5's and MPI-IO's messages do not say that the disk is full; the system's error number does.
bool SystemCause(PetscErrorCode n, int e) {
  const bool io_code = n == PETSC_ERR_FILE_OPEN || n == PETSC_ERR_FILE_READ || n == PETSC_ERR_FILE_WRITE ||
                       n == PETSC_ERR_FILE_UNEXPECTED || n == PETSC_ERR_LIB || n == PETSC_ERR_PLIB ||
                       n == PETSC_ERR_SYS;
  return io_code && (e == ENOSPC || e == EDQUOT || e == EFBIG || e == EIO);
}

void PrintSystemCause(PetscErrorCode n) {
  const int e = g_errors.first.sys_errno;
  if (SystemCause(n, e)) (*PetscErrorPrintf)("  (the system: %s)\n", std::strerror(e));
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
  PrintSystemCause(n);
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

int ExitStatusOf(PetscErrorCode ierr, int sys_errno) {
  // A full disk or a failed device behind an error about a file or a library call (HDF5's
  // failures come as any of these); errno is not looked at for the other codes, where it may be
  // left over from an earlier call that did not matter.
  if (SystemCause(ierr, sys_errno)) return kExitSystem;
  switch (ierr) {
  case PETSC_ERR_NOT_CONVERGED:  // the run's own "did not complete" (CheckCompleted) and diverged solves
  case PETSC_ERR_CONV_FAILED:
  case PETSC_ERR_MAT_LU_ZRPVT:
  case PETSC_ERR_MAT_CH_ZRPVT:
  case PETSC_ERR_LIB:  // a library the run called failed: MUMPS's factorization
    return kExitRunFailed;
  case PETSC_ERR_ARG_SIZ:
  case PETSC_ERR_ARG_IDN:
  case PETSC_ERR_ARG_WRONG:
  case PETSC_ERR_ARG_OUTOFRANGE:
  case PETSC_ERR_ARG_INCOMP:
  case PETSC_ERR_ARG_NULL:
  case PETSC_ERR_ARG_UNKNOWN_TYPE:  // -pc_type nonesuch
  case PETSC_ERR_SUP:               // a combination this code does not offer
  case PETSC_ERR_FILE_OPEN:         // a mesh, options or checkpoint file missing
  case PETSC_ERR_FILE_READ:
  case PETSC_ERR_FILE_UNEXPECTED:  // a corrupt checkpoint, another run's results
  case PETSC_ERR_MISSING_FACTOR:   // a solver package this PETSc lacks
  case PETSC_ERR_OPT_OVERWRITE:
  case PETSC_ERR_WRONG_MPI_SIZE:
  case PETSC_ERR_USER_INPUT:
    return kExitInputRefused;
  case PETSC_ERR_MEM:  // also the memory check's refusal: the run would not fit the node
  case PETSC_ERR_FILE_WRITE:
  case PETSC_ERR_SYS:
  case PETSC_ERR_SUP_SYS:
  case PETSC_ERR_MPI:
  case PETSC_ERR_MPI_LIB_INCOMP:
    return kExitSystem;
  default:
    return kExitInternal;
  }
}

int ErrorExit(MPI_Comm agree, PetscErrorCode ierr) {
  const int status = ExitStatusOf(ierr, g_errors.first.sys_errno);
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
  // Several ranks end in MPI_Abort (no MPI_Finalize, nothing of HDF5's runs); a rank that failed
  // alone could not close a file collectively anyway. One rank closes HDF5 before MPI_Finalize,
  // or, when HDF5 cannot be closed (a file's close failed on a full disk), ends here: MPI_Finalize
  // would run HDF5's closing callback and die of a segmentation fault, after the message.
  if (size == 1 && !OutputLibraryClose()) {
    std::fflush(nullptr);
    _exit(status);
  }
  if (size > 1) MPI_Abort(PETSC_COMM_WORLD, status);
  PetscFinalize();
  return status;
}

} // namespace etfe
