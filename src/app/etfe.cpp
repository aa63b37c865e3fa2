// etfe: the ETFE membrane solver. Everything at run time comes from PETSc options
// (-options_file, command line); -help lists them all. Run reads as the steps of a run; each
// step's pieces live in the files named for them (case_setup, solver_defaults, run_report,
// plan_driver, help_listing, error_handlers, options_files, options_check, heap_policy).
static const char help[] =
    "ETFE membrane solver: total-Lagrangian membranes on PETSc (SNES + MUMPS), load stepping,\n"
    "HDF5/XDMF results. Usage: etfe -options_file options/<scene>.opts [-option value ...]\n"
    "  -scene_list lists the scenes; -help lists every option with its prefix.\n\n";

#include <petscsnes.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "case_setup.h"
#include "error_handlers.h"
#include "etfe/io/checkpoint.h"
#include "etfe/analyses/cutpattern.h"
#include "etfe/solver/interrupt.h"
#include "etfe/solver/linesearch.h"
#include "etfe/material/material.h"
#include "etfe/io/output.h"
#include "etfe/scenes/scene_registry.h"
#include "etfe/io/writer_identity.h"
#include "heap_policy.h"
#include "help_listing.h"
#include "options_check.h"
#include "options_files.h"
#include "plan_driver.h"
#include "run_report.h"

using namespace etfe;

namespace {

// -analysis: stretch (load stepping, the default), formfind, cutpattern (the strips of a surface
// mesh, no scene) or plan (the drawing planner over stretch runs of the case).
enum class Analysis { stretch = 0, formfind = 1, cutpattern = 2, plan = 3 };

PetscErrorCode AnalysisFromOptions(MPI_Comm comm, Analysis *analysis) {
  static const char *const kinds[] = {"stretch", "formfind", "cutpattern", "plan"};
  PetscInt kind = 0;
  PetscFunctionBeginUser;
  PetscOptionsBegin(comm, nullptr, "Analysis", "Analysis");
  PetscCall(PetscOptionsEList(
      "-analysis",
      "stretch (load stepping), formfind (prescribed-stress shape), cutpattern (flatten "
      "the physical surfaces of -mesh_file, no scene) or plan (search the drawing schedule "
      "of a stretch case, -plan_*)",
      "", kinds, 4, kinds[0], &kind, nullptr));
  PetscOptionsEnd();
  *analysis = (Analysis)kind;
  PetscFunctionReturn(0);
}

// This program's own switches (read here, once, so that -help lists them).
PetscErrorCode ProgramOptions(MPI_Comm comm) {
  PetscBool traceback = PETSC_FALSE, allow = PETSC_FALSE, heap_release = PETSC_TRUE;
  PetscFunctionBeginUser;
  PetscOptionsBegin(comm, nullptr, "etfe", "etfe");
  PetscCall(PetscOptionsBool("-etfe_traceback",
                             "Errors with PETSc's full report instead of one line", "", traceback,
                             &traceback, nullptr));
  PetscCall(PetscOptionsBool("-options_allow_unused",
                             "Accept option names this project does not know (typos)", "", allow,
                             &allow, nullptr));
  PetscCall(PetscOptionsBool(
      "-etfe_heap_release",
      "Return freed blocks of 32 MB and more to the system (undoes SuperLU_DIST's "
      "mallopt; off: a 10^6-triangle rank's memory grows ~1 GB with MUMPS refactoring)",
      "", heap_release, &heap_release, nullptr));
  PetscOptionsEnd();
  ErrorHandlersUseTraceback(traceback);
  CheckUnusedOptionsAllow(allow);
  PetscCheck(!heap_release || HeapReleaseLargeBlocks(), comm, PETSC_ERR_SYS,
             "-etfe_heap_release: the C library refused mallopt (run with -etfe_heap_release 0)");
  PetscFunctionReturn(0);
}

// -results_status FILE: the status of a results file as a reader should believe it (a "running"
// whose writer is gone is "interrupted (writer gone ...)"; writer_identity.h). Exit status: 0
// complete, 10 running, 75 interrupted or stopped (continue with -restart), 1 otherwise.
PetscErrorCode PrintResultsStatus(MPI_Comm comm, const char *path, int *exit_status) {
  PetscFunctionBeginUser;
  const std::string st = ResultsStatusSeen(path);
  PetscCall(PetscPrintf(comm, "%s: %s\n", path, st.c_str()));
  *exit_status = st == "complete"                                              ? 0
                 : st.rfind("running", 0) == 0                                 ? 10
                 : st.rfind("interrupted", 0) == 0 || st.rfind("stopped", 0) == 0 ? kExitInterrupted
                                                                               : 1;
  PetscFunctionReturn(0);
}

// -analysis cutpattern: the strips of a surface mesh; no scene, problem or solver.
PetscErrorCode RunCutPattern(MPI_Comm comm, PetscBool help_only) {
  CutPatternSurfaceOptions cso;
  PetscFunctionBeginUser;
  PetscCall(CutPatternSurfaceOptionsFromCommandLine(comm, &cso));
  if (help_only) PetscFunctionReturn(0);
  PetscCall(CheckUnusedOptions(comm, PETSC_TRUE));
  PetscCall(CutPatternSurfaceRun(comm, cso));
  PetscCall(CheckUnusedOptions(comm, PETSC_FALSE));
  PetscFunctionReturn(0);
}

// Where the case's results and checkpoints go (-output_*, -checkpoint_*, -restart).
PetscErrorCode ResultsOptionsFromCommandLine(const Case &c, OutputOptions *oo,
                                             CheckpointOptions *cko) {
  MPI_Comm comm = c.P->comm;
  PetscFunctionBeginUser;
  PetscCall(OutputOptionsFromCommandLine(comm, c.P->scene.name.c_str(), oo));
  PetscCall(CheckpointOptionsFromCommandLine(
      comm, std::filesystem::path(oo->path).replace_extension("").string(), cko));
  char branch[PETSC_MAX_PATH_LEN] = "";
  PetscOptionsBegin(comm, nullptr, "Branch restart", "Checkpoint");
  PetscCall(PetscOptionsString("-restart_branch",
                               "Start this run's own loads from a base state: a checkpoint at a stage end of a run "
                               "whose model, supports and loads up to there this run shares (only the stages after "
                               "it may differ); results go to this run's own -output_file (docs/design-run.md)",
                               "", branch, branch, sizeof branch, nullptr));
  PetscCall(PetscOptionsBool("-checkpoint_final",
                             "Also write a checkpoint of the last state once the load history completes: the base "
                             "state that -restart_branch runs start from",
                             "", cko->final, &cko->final, nullptr));
  PetscOptionsEnd();
  if (branch[0]) {
    PetscCheck(!cko->restart[0], comm, PETSC_ERR_ARG_INCOMP,
               "-restart %s and -restart_branch %s: give one (-restart continues a history, -restart_branch starts "
               "another from a base state)", cko->restart, branch);
    std::snprintf(cko->restart, sizeof cko->restart, "%s", branch);
    cko->branch = PETSC_TRUE;
  }
  PetscCheck(!(c.formfind && (cko->restart[0] || cko->every > 0 || cko->every_s > 0)), comm, PETSC_ERR_SUP,
             "checkpoint/restart is for load histories (-analysis stretch); form finding restarts "
             "from its "
             "Gmsh output instead");
  PetscFunctionReturn(0);
}

// Opens the results file (null when -output 0). A refused restart must leave every file as it
// was: the checkpoint is checked completely before the results file is opened (and truncated to
// the checkpoint's step).
PetscErrorCode OpenResults(const Case &c, const OutputOptions &oo, const CheckpointOptions &cko,
                           OutputFile **out) {
  PetscInt restart_step = -1;
  std::string run_id;
  PetscFunctionBeginUser;
  *out = nullptr;
  // Checkpoints are written with results (stage ends, signals) or when asked for (also by
  // -load_stop_after): their directory is tried now, not after a stage's work (the results
  // file's is, by its creation below).
  if (!c.formfind && (oo.enabled || cko.every > 0 || cko.every_s > 0 || c.lso.stop_after >= 0))
    PetscCall(CheckpointCheckWritable(c.P->comm, cko));
  OutputOptions o = oo;
  if (cko.restart[0])
    PetscCall(CheckpointValidate(c.P, cko.restart, &restart_step, &run_id, &o.checkpoint_results, cko.branch));
  if (cko.branch) {  // a load history of its own: a new results file and run id
    restart_step = -1;
    run_id.clear();
    std::error_code ec1, ec2;
    const bool same = !o.checkpoint_results.empty() &&
                      std::filesystem::weakly_canonical(oo.path, ec1) ==
                          std::filesystem::weakly_canonical(o.checkpoint_results, ec2) && !ec1 && !ec2;
    PetscCheck(!oo.enabled || !same, c.P->comm, PETSC_ERR_ARG_WRONG,
               "-restart_branch %s: -output_file %s is the base run's results file; give the branch a file of its "
               "own (-output_file)", cko.restart, oo.path);
  }
  if (oo.enabled) PetscCall(OutputOpen(c.P, o, out, restart_step, run_id));
  if (*out) c.P->observer.results_stem = OutputStem(*out);
  PetscFunctionReturn(0);
}

// The schedule (load stepping) or the form finding, writing results as it goes; form finding's
// outcome in the load stepper's terms.
PetscErrorCode RunAnalysis(Case &c, OutputFile *out, const CheckpointOptions &cko,
                           LoadStepperResult *res) {
  FormFindResult ffr;
  PetscLogDouble t0, t1;
  PetscFunctionBeginUser;
  if (!c.formfind) {
    PetscCall(LoadStepperRun(c.P, c.snes, out, c.lso, cko, res));
    PetscFunctionReturn(0);
  }
  PetscCall(PetscTime(&t0));
  PetscCall(FormFindRun(c.P, c.snes, out, c.ffo, &ffr));
  PetscCall(PetscTime(&t1));
  res->completed = ffr.converged;
  res->failure = ffr.failure;
  res->steps = ffr.iterations;
  res->time = c.P->time;
  res->wall = t1 - t0;
  PetscCall(SNESGetLinearSolveIterations(c.snes, &res->newton_iterations));
  PetscFunctionReturn(0);
}

// This run's command line as given (options files not expanded), set in main.
std::vector<std::string> g_command;

// The command that continues this run from `checkpoint`: the same one with -restart (under
// mpirun with as many ranks, which a bit-for-bit continuation needs).
std::string RestartCommand(MPI_Comm comm, const char *checkpoint) {
  PetscMPIInt size = 1;
  MPI_Comm_size(comm, &size);
  std::string cmd = size > 1 ? "mpirun -n " + std::to_string(size) + " " : "";
  auto quoted = [](const std::string &a) {
    if (!a.empty() && a.find_first_of(" \t'\"$;&|<>()*?`\\") == std::string::npos) return a;
    std::string q = "'";
    for (char ch : a) q += ch == '\'' ? std::string("'\\''") : std::string(1, ch);
    return q + "'";
  };
  for (size_t k = 0; k < g_command.size(); ++k) {
    // The checkpoint given before is replaced (a branch's own checkpoint continues the branch).
    if (k > 0 && (g_command[k] == "-restart" || g_command[k] == "-restart_branch")) {
      ++k;
      continue;
    }
    cmd += (k ? " " : "") + quoted(g_command[k]);
  }
  return cmd + " -restart " + quoted(checkpoint);
}

// A run stopped by a signal: what it says on stdout and in the results status.
std::string InterruptedStatus(MPI_Comm comm, const CheckpointOptions &cko, const LoadStepperResult &res) {
  char head[128];
  std::snprintf(head, sizeof head, "interrupted by %s at increment %lld (load time %.6g); checkpoint ",
                InterruptSignalName(res.interrupted), (long long)res.steps, res.time);
  return head + std::string(cko.file) + "; continue with: " + RestartCommand(comm, cko.file);
}

// The scene's own quantities of interest (after a complete run), then the results file closed
// with its status.
PetscErrorCode ReportAndCloseResults(const Case &c, const OutputOptions &oo,
                                     const CheckpointOptions &cko, const LoadStepperResult &res,
                                     OutputFile **out) {
  MPI_Comm comm = c.P->comm;
  PetscFunctionBeginUser;
  if (c.P->observer.report && res.completed && !res.stopped)
    PetscCall(c.P->observer.report(c.P, c.P->observer.ctx));
  if (res.interrupted)
    PetscCall(PetscPrintf(comm, "etfe: %s\n", InterruptedStatus(comm, cko, res).c_str()));
  else if (res.stopped)
    PetscCall(
        PetscPrintf(comm, "etfe: checkpoint %s; continue with -restart %s\n", cko.file, cko.file));
  if (!*out) PetscFunctionReturn(0);
  const std::string status = res.interrupted ? InterruptedStatus(comm, cko, res)
                             : res.stopped
                                 ? "stopped at increment " + std::to_string((long long)res.steps) +
                                       " (checkpoint " + cko.file + ")"
                             : res.completed ? std::string("complete")
                                             : "failed: " + res.failure;
  PetscCall(OutputClose(out, status));
  PetscCall(PetscPrintf(comm, "etfe: results in %s (+ .xmf for ParaView)\n", oo.path));
  PetscFunctionReturn(0);
}

// A run that did not complete is an error exit, after its results are closed.
PetscErrorCode CheckCompleted(MPI_Comm comm, bool formfind, const LoadStepperResult &res) {
  PetscFunctionBeginUser;
  PetscCheck(
      res.completed, comm, PETSC_ERR_NOT_CONVERGED, "%s. %s", res.failure.c_str(),
      formfind
          ? "The last iterate is in the results (status \"failed\")."
          : "The last converged increment is in the results. Ways out: more increments "
            "(-load_increments), more cut-backs (-load_max_cutbacks), or check the supports and "
            "loads of the scene");
  PetscFunctionReturn(0);
}

// exit_status: 0, or kExitInterrupted when a signal stopped the run at a safe point.
PetscErrorCode Run(int *exit_status) {
  MPI_Comm comm = PETSC_COMM_WORLD;
  PetscBool help_only = PETSC_FALSE, list = PETSC_FALSE;
  Analysis analysis;
  SceneSpec scene;
  SceneObserver observer;
  Case c;
  OutputOptions oo;
  CheckpointOptions cko;
  OutputFile *out = nullptr;
  LoadStepperResult res;
  PetscFunctionBeginUser;
  // 1. The program's own switches; -help and -scene_list run the steps below only to list.
  PetscCall(ProgramOptions(comm));
  {
    char path[PETSC_MAX_PATH_LEN] = "";
    PetscBool given = PETSC_FALSE;
    PetscOptionsBegin(comm, nullptr, "Results status", "etfe");
    PetscCall(PetscOptionsString("-results_status",
                                 "Print the status of this results file as a reader should believe it (a \"running\" "
                                 "whose writer is gone says so) and exit: 0 complete, 10 running, 75 interrupted or "
                                 "stopped, 1 otherwise (failed, incomplete, unreadable); a run's own exit status: 0 "
                                 "complete, 75 interrupted, 1 did not complete, 2 input refused, 3 system, 4 internal",
                                 "", path, path, sizeof path, &given));
    PetscOptionsEnd();
    if (given) {
      PetscCall(PrintResultsStatus(comm, path, exit_status));
      PetscFunctionReturn(0);
    }
  }
  PetscCall(PetscOptionsHasName(nullptr, nullptr, "-help", &help_only));
  PetscCall(PetscOptionsHasName(nullptr, nullptr, "-scene_list", &list));

  // 2. Registries: scenes, materials, the etfe line search.
  PetscCall(SceneRegisterAll());
  PetscCall(MaterialRegisterAll());
  PetscCall(SNESLineSearchRegisterEtfe());

  // 3. The analysis first (a scene that offers both builds the one asked for); the drawing
  //    planner and the cutting patterns have drivers of their own.
  PetscCall(AnalysisFromOptions(comm, &analysis));
  if (!list && (analysis == Analysis::plan || analysis == Analysis::cutpattern)) {
    PetscCall(analysis == Analysis::plan ? RunPlan(comm, help_only)
                                         : RunCutPattern(comm, help_only));
    PetscFunctionReturn(0);
  }

  // 4. The scene: mesh, supports, loads, schedule. -help without one lists every component.
  scene.form_finding = analysis == Analysis::formfind;
  PetscCall(SceneCreateFromOptions(comm, &scene, &observer));
  if (list) PetscFunctionReturn(0);
  if (help_only && scene.name.empty()) {
    PetscCall(ListEveryOption(comm));
    PetscFunctionReturn(0);
  }

  // 5. The case (material, membrane, problem, contact, solver, load stepping) and its results.
  PetscCall(CreateCase(comm, analysis == Analysis::formfind, std::move(scene), observer, &c));
  PetscCall(ResultsOptionsFromCommandLine(c, &oo, &cko));
  if (help_only) {
    PetscCall(CaseDestroy(&c));
    PetscFunctionReturn(0);
  }
  PetscCall(CheckUnusedOptions(comm, PETSC_TRUE));
  PetscCall(PrintHeader(c.P, c.snes));

  // 6. Run the schedule (or find the form), writing results as it goes.
  // A signal from here on stops the load history at a safe point (etfe/solver/interrupt.h); one that
  // comes after its last increment is too late to matter: the run completes.
  if (!c.formfind && oo.enabled) PetscCall(InterruptCatch(true));
  PetscCall(OpenResults(c, oo, cko, &out));
  PetscCall(RunAnalysis(c, out, cko, &res));
  PetscCall(PrintRunSummary(comm, res));

  // 7. The scene's own quantities of interest, then close the results; a failure is an error.
  PetscCall(ReportAndCloseResults(c, oo, cko, res, &out));
  PetscCall(CaseDestroy(&c));
  PetscCall(CheckCompleted(comm, analysis == Analysis::formfind, res));
  PetscCall(CheckUnusedOptions(comm, PETSC_FALSE));
  *exit_status = res.interrupted ? kExitInterrupted : 0;
  PetscFunctionReturn(0);
}

} // namespace

int main(int argc, char **argv) {
  // Open MPI's "sm" shared-file-pointer component guards every MPI_File_open with a named
  // semaphore keyed by the file's base name (/dev/shm/sem.OMPIO_<name>): a run killed while
  // writing leaves it taken, and the next run that opens a file of that name (its restart's
  // checkpoint) waits forever. HDF5 never uses shared file pointers, so leave the component out
  // unless the user chose otherwise.
  setenv("OMPI_MCA_sharedfp", "^sm", 0);
  // Options files are expanded here, before PETSc reads the command line (options_files.h).
  std::vector<std::string> args(argv + 1, argv + argc), expanded;
  g_command.assign(argv, argv + argc);
  std::vector<OptionsFileRequirement> requirements;
  std::string error;
  if (!ExpandOptionsFiles(args, &expanded, &error, &requirements)) {
    const char *rank = std::getenv("OMPI_COMM_WORLD_RANK");
    if (!rank || std::string(rank) == "0") std::fprintf(stderr, "etfe: %s\n", error.c_str());
    return kExitInputRefused;
  }
  // Before MPI starts (heap_policy.h): huge pages for the large blocks -etfe_heap_release maps.
  if (HeapReleaseWanted(expanded)) HeapRestartWithHugePages(argv);
  std::vector<char *> new_argv{argv[0]};
  for (std::string &a : expanded)
    new_argv.push_back(a.data());
  new_argv.push_back(nullptr);
  argc = (int)expanded.size() + 1;
  argv = new_argv.data();
  // PETSc's error codes are not exit statuses (PETSC_ERR_ARG_INCOMP is 75, "resubmit"): every
  // error exits with ExitStatusOf's (error_handlers.h).
  if (const PetscErrorCode e = PetscInitialize(&argc, &argv, nullptr, help)) return ExitStatusOf(e, 0);
  if (const PetscErrorCode e = ErrorHandlersPush(requirements)) return ErrorExit(PETSC_COMM_WORLD, e);
  MPI_Comm agree; // where the ranks meet on an error exit (error_handlers.h)
  if (MPI_Comm_dup(PETSC_COMM_WORLD, &agree) != MPI_SUCCESS) return ErrorExit(PETSC_COMM_WORLD, PETSC_ERR_MPI);
  int exit_status = 0;
  const PetscErrorCode ierr = Run(&exit_status);
  if (ierr) return ErrorExit(agree, ierr);
  MPI_Comm_free(&agree);
  if (const PetscErrorCode e = InterruptHoldUntilExit()) return ExitStatusOf(e, 0);
  if (const PetscErrorCode e = PetscFinalize()) return ExitStatusOf(e, 0);
  return exit_status;
}
