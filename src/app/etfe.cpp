// etfe: the ETFE membrane solver. Everything at run time comes from PETSc options
// (-options_file, command line); -help lists them all.
static const char help[] =
    "ETFE membrane solver: total-Lagrangian membranes on PETSc (SNES + MUMPS), load stepping,\n"
    "HDF5/XDMF results. Usage: etfe -options_file options/<scene>.opts [-option value ...]\n"
    "  -scene_list lists the scenes; -help lists every option with its prefix.\n\n";

#include <petscsnes.h>

#include <sys/resource.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "heap_policy.h"
#include "options_check.h"
#include "options_files.h"
#include "etfe/assembly.h"
#include "etfe/checkpoint.h"
#include "etfe/contact.h"
#include "etfe/cutpattern.h"
#include "etfe/formfind.h"
#include "etfe/linesearch.h"
#include "etfe/load_stepper.h"
#include "etfe/material.h"
#include "etfe/output.h"
#include "etfe/plan.h"
#include "etfe/problem.h"
#include "etfe/scene_registry.h"
#include "etfe/tangent_shift.h"

using namespace etfe;

namespace {

PetscErrorCode ReadMembraneOptions(MPI_Comm comm, Problem *P) {
  PetscFunctionBeginUser;
  PetscOptionsBegin(comm, nullptr, "Membrane element", "Membrane");
  PetscCall(PetscOptionsReal("-membrane_thickness", "Film thickness h0 [mm]", "", P->thickness,
                             &P->thickness, nullptr));
  PetscCall(PetscOptionsReal("-membrane_min_area_ratio",
                             "Smallest current/reference area before an element counts as collapsed",
                             "", P->min_area_ratio, &P->min_area_ratio, nullptr));
  PetscCall(PetscOptionsReal("-membrane_tangent_shift",
                             "Tangent-only diagonal shift, relative to E h (slack starts; the answer is unchanged)",
                             "", P->tangent_shift, &P->tangent_shift, nullptr));
  PetscCall(PetscOptionsBool("-membrane_tangent_shift_adaptive",
                             "Scale the tangent shift by |F_k|/|F_0| of the Newton solve, so it vanishes at convergence",
                             "", P->tangent_shift_adaptive, &P->tangent_shift_adaptive, nullptr));
  PetscCall(PetscOptionsBool("-membrane_tangent_tension_only",
                             "Geometric stiffness from the tensile part of the stress only (wrinkling films; "
                             "the answer is unchanged)", "", P->tangent_tension_only, &P->tangent_tension_only,
                             nullptr));
  PetscCall(PetscOptionsBool("-membrane_near_null_space",
                             "Attach the 6 rigid-body modes of the nodal coordinates to the tangent as its near-null "
                             "space (for -pc_type gamg; LU ignores it)", "", P->near_null_space, &P->near_null_space,
                             nullptr));
  const char *wrinkling_models[] = {"none", "tension_field"};
  PetscInt wrinkling = P->wrinkling ? 1 : 0;
  PetscCall(PetscOptionsEList("-membrane_wrinkling",
                              "none: the film carries compression (thesis); tension_field: no compression, "
                              "each element taut, wrinkled (uniaxial tension) or slack (issue 15)",
                              "", wrinkling_models, 2, wrinkling_models[wrinkling], &wrinkling, nullptr));
  P->wrinkling = wrinkling == 1 ? PETSC_TRUE : PETSC_FALSE;
  PetscOptionsEnd();
  PetscCheck(P->tangent_shift >= 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "-membrane_tangent_shift must be >= 0");
  PetscCheck(P->thickness > 0, comm, PETSC_ERR_ARG_OUTOFRANGE,
             "-membrane_thickness %g: the film thickness must be positive (mm)", P->thickness);
  PetscFunctionReturn(0);
}

PetscErrorCode LUNativeMaxDofFromOptions(MPI_Comm comm, PetscInt *max_dof) {
  PetscFunctionBeginUser;
  *max_dof = 0;
  PetscOptionsBegin(comm, nullptr, "Linear solver", "PC");
  PetscCall(PetscOptionsInt("-etfe_lu_native_max_dof",
                            "On one rank, systems up to this many DOF are factored with PETSc's own LU (AMD ordering) "
                            "unless -pc_factor_mat_solver_type names a package; 0: always MUMPS",
                            "", *max_dof, max_dof, nullptr));
  PetscOptionsEnd();
  PetscFunctionReturn(0);
}

// The LU package when the options name none: on one rank and up to -etfe_lu_native_max_dof DOF,
// PETSc's own LU with an AMD ordering; MUMPS otherwise. Measured (-log_view, MatLUFactorNum per
// factorization): PD15a, 2 340 DOF: 1.25 ms against MUMPS's ~4.5 ms (its analysis and
// distribution overheads dominate a small system); Hencky, 5 403 DOF: 15 vs 10 ms; DD1511 on
// 10^4 triangles, 30 k DOF: 35 vs 23 ms. Whenever MUMPS factors, its workspace margin ICNTL(14)
// defaults to 200 % unless the options set it: the stiff contact penalties delay pivots and need
// more than MUMPS's own 20 %.
PetscErrorCode ChooseLUPackage(Problem *P, PC pc) {
  char pkg[64] = "", pctype[64] = "";
  PetscBool pkg_set = PETSC_FALSE, pc_set = PETSC_FALSE, icntl14 = PETSC_FALSE;
  PetscInt max_dof;
  PetscFunctionBeginUser;
  PetscCall(LUNativeMaxDofFromOptions(P->comm, &max_dof));
  PetscCall(PetscOptionsGetString(nullptr, nullptr, "-pc_factor_mat_solver_type", pkg, sizeof pkg, &pkg_set));
  PetscCall(PetscOptionsGetString(nullptr, nullptr, "-pc_type", pctype, sizeof pctype, &pc_set));
  const bool native = P->size == 1 && 3 * P->mesh.num_nodes_global <= max_dof;
  if (!pkg_set) {
    PetscCall(PCFactorSetMatSolverType(pc, native ? MATSOLVERPETSC : MATSOLVERMUMPS));
    if (native) PetscCall(PCFactorSetMatOrderingType(pc, MATORDERINGAMD));
  }
  const bool factor = !pc_set || !std::strcmp(pctype, PCLU) || !std::strcmp(pctype, PCCHOLESKY);
  const bool mumps = factor && (pkg_set ? !std::strcmp(pkg, MATSOLVERMUMPS) : !native);
  PetscCall(PetscOptionsHasName(nullptr, nullptr, "-mat_mumps_icntl_14", &icntl14));
  if (mumps && !icntl14) PetscCall(PetscOptionsSetValue(nullptr, "-mat_mumps_icntl_14", "200"));
  PetscFunctionReturn(0);
}

// Solver defaults (Newton + the etfe line search + LU, ChooseLUPackage); options files override them.
PetscErrorCode CreateSolver(Problem *P, SNES *snes) {
  KSP ksp;
  PC pc;
  SNESLineSearch ls;
  Vec F;
  PetscFunctionBeginUser;
  PetscCall(SNESCreate(P->comm, snes));
  PetscCall(VecDuplicate(P->U, &F));
  PetscCall(SNESSetFunction(*snes, F, FormResidual, P));
  PetscCall(VecDestroy(&F));
  PetscCall(SNESSetJacobian(*snes, P->J, P->J, FormShiftedJacobian, P));
  PetscCall(SNESSetType(*snes, SNESNEWTONLS));
  PetscCall(SNESSetTolerances(*snes, 1e-9, 1e-10, 1e-14, 30, 10000));
  PetscCall(SNESGetKSP(*snes, &ksp));
  PetscCall(KSPSetType(ksp, KSPPREONLY));
  PetscCall(KSPGetPC(ksp, &pc));
  PetscCall(PCSetType(pc, PCLU));
  PetscCall(ChooseLUPackage(P, pc));
  PetscCall(SNESGetLineSearch(*snes, &ls));
  PetscCall(SNESLineSearchSetType(ls, SNESLINESEARCHETFE));
  PetscCall(SNESSetFromOptions(*snes));
  PetscCall(SNESGetLineSearch(*snes, &ls));
  PetscCall(SNESLineSearchEtfeSetProblem(ls, P));
  PetscFunctionReturn(0);
}

// The analysis's material (stretch: from -material_*; formfind: the prescribed stress) and the
// membrane options, then the distributed problem with the scene's observer and contact set, the
// solver and the load-stepping options: what every run of a case needs (the app's one run, and
// each of the drawing planner's).
PetscErrorCode CreateCase(MPI_Comm comm, bool formfind, SceneSpec &&scene, const SceneObserver &observer,
                          FormFindOptions *ffo, Problem **problem, SNES *snes, LoadStepperOptions *lso) {
  std::unique_ptr<Material> material;
  PetscFunctionBeginUser;
  if (formfind) {
    PetscCall(FormFindOptionsFromCommandLine(comm, ffo));
    material = MaterialCreatePrescribedStress(ffo->ratio * ffo->stress, ffo->stress);
  } else {
    PetscCall(MaterialCreateFromOptions(comm, &material));
  }
  auto *P = new Problem();
  *problem = P;
  P->thickness = scene.thickness;
  PetscCall(ReadMembraneOptions(comm, P));
  PetscCheck(!(formfind && P->wrinkling), comm, PETSC_ERR_ARG_INCOMP,
             "-membrane_wrinkling tension_field needs a material law (-analysis stretch); form finding "
             "prescribes the stress: drop the option for -analysis formfind");
  if (P->wrinkling) material = MaterialWrapTensionField(std::move(material));
  PetscCall(CheckpointFingerprintScene(comm, scene, P));
  // A load history keeps only each rank's part (form finding keeps the global description on
  // rank 0, which writes the found shape with the scene's topology).
  PetscCall(ProblemCreate(comm, std::move(scene), std::move(material), formfind, P));
  P->observer = observer;
  if (P->scene.contact.active) {
    ContactSet *contact;
    PetscCall(ContactCreate(P, &contact));
    PetscCall(ProblemSetContact(P, contact));
  }
  if (P->observer.setup) PetscCall(P->observer.setup(P, P->observer.ctx));
  PetscCall(CreateSolver(P, snes));
  PetscCall(LoadStepperOptionsFromCommandLine(comm, lso));
  PetscCall(LoadStepperSetConvergenceTest(P, *snes, *lso));
  PetscFunctionReturn(0);
}

// A stretch case built from the options database: the drawing planner checks it once, then runs
// it once per evaluation. P stays null when no scene is named.
struct StretchCase {
  Problem *P = nullptr;
  SNES snes = nullptr;
  LoadStepperOptions lso;
};

PetscErrorCode StretchCaseCreate(MPI_Comm comm, StretchCase *c) {
  SceneSpec scene;
  SceneObserver observer;
  FormFindOptions ffo;
  PetscFunctionBeginUser;
  PetscCall(SceneCreateFromOptions(comm, &scene, &observer));
  if (scene.name.empty()) PetscFunctionReturn(0);
  PetscCall(CreateCase(comm, false, std::move(scene), observer, &ffo, &c->P, &c->snes, &c->lso));
  PetscFunctionReturn(0);
}

// What CreateCase made, destroyed (P may be null: no scene was named).
PetscErrorCode CaseDestroy(SNES *snes, Problem **P) {
  PetscFunctionBeginUser;
  PetscCall(SNESDestroy(snes));
  if (*P) PetscCall(ProblemDestroy(*P));
  delete *P;
  *P = nullptr;
  PetscFunctionReturn(0);
}

PetscErrorCode StretchCaseDestroy(StretchCase *c) { return CaseDestroy(&c->snes, &c->P); }

// One stretch run of the case under the current options, for the drawing planner: no results
// file, no monitor, the per-element criteria fields gathered on every rank.
PetscErrorCode PlanStretchOnce(MPI_Comm comm, void *, PlanRunFields *fields) {
  StretchCase c;
  LoadStepperResult res;
  PetscFunctionBeginUser;
  PetscCall(StretchCaseCreate(comm, &c));
  c.lso.monitor = 0;
  PetscCall(LoadStepperRun(c.P, c.snes, nullptr, c.lso, CheckpointOptions(), &res));
  fields->completed = res.completed && !res.stopped;
  fields->failure = res.stopped ? "stopped by -load_stop_after" : res.failure;
  fields->newton = res.newton_iterations;
  fields->wall = res.wall;
  if (fields->completed) PetscCall(PlanGatherFields(c.P, fields));
  PetscCall(StretchCaseDestroy(&c));
  PetscFunctionReturn(0);
}

// Peak resident memory of each rank so far (the kernel's high-water mark, set-up included), as
// max / min over the ranks in MB: what a user sizing a dense run needs, printed after set-up and
// at the end; with now, also what each rank holds at this moment (after set-up: without the
// global description rank 0 read and a load history has released, ProblemReleaseScene).
PetscErrorCode PrintPeakMemory(MPI_Comm comm, const char *when, bool now = false) {
  struct rusage ru;
  double mb[4], max_mb[4];
  PetscFunctionBeginUser;
  getrusage(RUSAGE_SELF, &ru);
  mb[0] = ru.ru_maxrss / 1024.0;  // kB on Linux
  mb[2] = 0.0;
  if (FILE *f = std::fopen("/proc/self/statm", "r")) {
    unsigned long size = 0, resident = 0;
    if (std::fscanf(f, "%lu %lu", &size, &resident) == 2) mb[2] = resident * (double)sysconf(_SC_PAGESIZE) / 1048576.0;
    std::fclose(f);
  }
  mb[1] = -mb[0], mb[3] = -mb[2];
  PetscCallMPI(MPI_Allreduce(mb, max_mb, 4, MPI_DOUBLE, MPI_MAX, comm));
  char resident[64] = "";
  if (now && max_mb[2] > 0) std::snprintf(resident, sizeof resident, "; resident now %.0f / %.0f MB", max_mb[2], -max_mb[3]);
  PetscCall(PetscPrintf(comm, "  peak memory per rank %s: %.0f MB (max), %.0f MB (min)%s\n", when, max_mb[0], -max_mb[1],
                        resident));
  PetscFunctionReturn(0);
}

PetscErrorCode PrintHeader(Problem *P, SNES snes) {
  KSP ksp;
  PC pc;
  KSPType ktype;
  PCType ptype;
  MatSolverType stype = nullptr;
  SNESLineSearch ls;
  SNESLineSearchType lstype;
  PetscInt emin, emax, nmin, nmax;
  PetscFunctionBeginUser;
  PetscCall(SNESGetKSP(snes, &ksp));
  PetscCall(KSPGetType(ksp, &ktype));
  PetscCall(KSPGetPC(ksp, &pc));
  PetscCall(PCGetType(pc, &ptype));
  PetscCall(PCFactorGetMatSolverType(pc, &stype));
  PetscCall(SNESGetLineSearch(snes, &ls));
  PetscCall(SNESLineSearchGetType(ls, &lstype));
  PetscCallMPI(MPI_Allreduce(&P->mesh.num_elements, &emin, 1, MPIU_INT, MPI_MIN, P->comm));
  PetscCallMPI(MPI_Allreduce(&P->mesh.num_elements, &emax, 1, MPIU_INT, MPI_MAX, P->comm));
  PetscCallMPI(MPI_Allreduce(&P->mesh.num_owned, &nmin, 1, MPIU_INT, MPI_MIN, P->comm));
  PetscCallMPI(MPI_Allreduce(&P->mesh.num_owned, &nmax, 1, MPIU_INT, MPI_MAX, P->comm));
  PetscCall(PetscPrintf(P->comm, "etfe: scene %s\n", P->scene.name.c_str()));
  PetscCall(PetscPrintf(P->comm, "  mesh: %s, %" PetscInt_FMT " nodes, %" PetscInt_FMT
                        " triangles, %" PetscInt_FMT " DOF\n",
                        P->mesh.source.c_str(), P->mesh.num_nodes_global,
                        P->mesh.num_elements_global, 3 * P->mesh.num_nodes_global));
  PetscCall(PetscPrintf(P->comm, "  ranks: %d (METIS), elements per rank %" PetscInt_FMT "-%" PetscInt_FMT
                        ", owned nodes per rank %" PetscInt_FMT "-%" PetscInt_FMT " (imbalance %.3f)\n",
                        P->size, emin, emax, nmin, nmax,
                        emax * (double)P->size / std::max<PetscInt>(1, P->mesh.num_elements_global)));
  PetscInt ncon = (PetscInt)P->con_owned_dof.size(), ncon_all;
  PetscCallMPI(MPI_Allreduce(&ncon, &ncon_all, 1, MPIU_INT, MPI_SUM, P->comm));
  PetscCall(PetscPrintf(P->comm, "  physics: membrane (TL, h0 = %g mm), %s material%s, %" PetscInt_FMT " constrained DOF\n",
                        P->thickness, P->material->Name(), P->has_pressure ? ", follower pressure" : "", ncon_all));
  PetscCall(P->material->View(P->comm));
  PetscCall(PetscPrintf(P->comm, "  solver: SNES newtonls, line search %s, KSP %s, PC %s%s%s\n", lstype,
                        ktype, ptype, stype ? " " : "", stype ? stype : ""));
  {
    // The streamed set-up: rank 0 alone held the global mesh and description and sent each rank
    // its share (src/mesh/distribute.cpp).
    double kb[2] = {P->mesh.share_bytes / 1024.0, -(P->mesh.share_bytes / 1024.0)}, all[2];
    PetscCallMPI(MPI_Allreduce(kb, all, 2, MPI_DOUBLE, MPI_MAX, P->comm));
    PetscCall(PetscPrintf(P->comm, "  set-up: rank 0 built the scene and sent each rank its share: %.0f kB (max), %.0f kB (min)\n",
                          all[0], -all[1]));
  }
  if (P->contact && P->contact->penalty_length > 0)
    PetscCall(PetscPrintf(P->comm,
                          "  contact: %" PetscInt_FMT " pairs, penalties per unit length (kn %g, kt %g N/mm at a tributary "
                          "length of %g mm; pair factors %.3g-%.3g)\n",
                          P->contact->num_global, P->contact->params.kn, P->contact->params.kt,
                          P->contact->penalty_length, P->contact->k_scale_min, P->contact->k_scale_max));
  if (!P->scene.initial_guess_note.empty())
    PetscCall(PetscPrintf(P->comm, "  initial guess: %s\n", P->scene.initial_guess_note.c_str()));
  PetscCall(PrintPeakMemory(P->comm, "after set-up", true));
  PetscFunctionReturn(0);
}

// The first error of the run, for the results file's status, with the system's error number at
// that moment (HDF5's messages do not say that the disk is full; errno does).
struct FirstError {
  std::string message;
  int sys_errno = 0;
  bool set = false;
} g_first_error;

void RecordError(const char *mess) {
  if (g_first_error.set) return;
  g_first_error.sys_errno = errno;
  g_first_error.set = true;
  g_first_error.message = mess ? mess : "error";
  for (char &c : g_first_error.message)
    if (c == '\n') c = ' ';
}

// Whether every rank is on its error path: they meet on a communicator of their own (never one a
// stuck collective call could be using). Ranks waiting for a partner that failed alone never
// arrive; then the failed rank gives up after a while and the run is aborted as before.
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

PetscErrorCode TracebackErrorHandler(MPI_Comm comm, int line, const char *fun, const char *file, PetscErrorCode n,
                                     PetscErrorType p, const char *mess, void *ctx) {
  if (p == PETSC_ERROR_INITIAL) RecordError(mess);
  return PetscTraceBackErrorHandler(comm, line, fun, file, n, p, mess, ctx);
}

// PETSc's default report repeats the whole option table and configure line; a user needs the
// message and where it came from. -etfe_traceback restores PETSc's full report.
PetscErrorCode ConciseErrorHandler(MPI_Comm comm, int line, const char *fun, const char *file,
                                   PetscErrorCode n, PetscErrorType p, const char *mess, void *) {
  if (p == PETSC_ERROR_INITIAL) {
    RecordError(mess);
    (*PetscErrorPrintf)("%s\n", mess ? mess : "(no message)");
    // PETSc's conversion errors ("Input string abc has no integer value") do not say which option
    // held the string: find it in the database.
    const char *lead = "Input string ";
    if (mess && fun && std::strncmp(fun, "PetscOptionsStringTo", 20) == 0 && std::strncmp(mess, lead, 13) == 0) {
      std::string bad(mess + 13);
      bad = bad.substr(0, bad.find(' '));
      char *all = nullptr;
      if (!PetscOptionsGetAll(nullptr, &all) && all) {
        std::string names, prev;
        std::istringstream in(all);
        for (std::string tok; in >> tok; prev = tok)
          if (tok == bad && prev.size() > 1 && prev[0] == '-') names += " " + prev;
        PetscFree(all);
        if (!names.empty())
          (*PetscErrorPrintf)("  (the value of%s: give a number of the option's type, see -help)\n", names.c_str());
      }
    }
    (*PetscErrorPrintf)("  (raised in %s() at %s:%d; -etfe_traceback gives PETSc's full report)\n",
                        fun, file, line);
  }
  return n;
}

// -analysis: stretch (load stepping, the default), formfind, cutpattern (the strips of a surface
// mesh, no scene) or plan (the drawing planner over stretch runs of the case).
enum class Analysis { stretch = 0, formfind = 1, cutpattern = 2, plan = 3 };

PetscErrorCode AnalysisFromOptions(MPI_Comm comm, Analysis *analysis) {
  static const char *const kinds[] = {"stretch", "formfind", "cutpattern", "plan"};
  PetscInt kind = 0;
  PetscFunctionBeginUser;
  PetscOptionsBegin(comm, nullptr, "Analysis", "Analysis");
  PetscCall(PetscOptionsEList("-analysis",
                              "stretch (load stepping), formfind (prescribed-stress shape), cutpattern (flatten "
                              "the physical surfaces of -mesh_file, no scene) or plan (search the drawing schedule "
                              "of a stretch case, -plan_*)",
                              "", kinds, 4, kinds[0], &kind, nullptr));
  PetscOptionsEnd();
  *analysis = (Analysis)kind;
  PetscFunctionReturn(0);
}

// -analysis plan: the case is built once to check it and its options (and to print what it is),
// then the planner runs it as often as its search needs.
PetscErrorCode RunPlan(MPI_Comm comm, PetscBool help_only) {
  StretchCase c;
  OutputOptions oo;
  PlanOptions po;
  PetscFunctionBeginUser;
  PetscCall(StretchCaseCreate(comm, &c));
  PetscCheck(c.P || help_only, comm, PETSC_ERR_USER_INPUT,
             "-analysis plan needs a stretch case: -options_file options/saddle/dd1511.opts -analysis plan");
  if (!c.P) PetscFunctionReturn(0);
  PetscCall(OutputOptionsFromCommandLine(comm, c.P->scene.name.c_str(), &oo));
  PetscCall(PlanOptionsFromCommandLine(comm, std::filesystem::path(oo.path).replace_extension("").string(), &po));
  po.case_arrays = c.P->scene.stage_options;
  if (!help_only) {
    PetscCall(CheckUnusedOptions(comm, PETSC_TRUE));
    PetscCall(PrintHeader(c.P, c.snes));
  }
  PetscCall(StretchCaseDestroy(&c));
  if (help_only) PetscFunctionReturn(0);
  PetscCall(PlanRun(comm, po, PlanStretchOnce, nullptr));
  PetscCall(CheckUnusedOptions(comm, PETSC_FALSE));
  PetscFunctionReturn(0);
}

// This program's own switches (read here so that -help lists them).
PetscErrorCode ProgramOptions(MPI_Comm comm) {
  PetscBool traceback = PETSC_FALSE, allow = PETSC_FALSE, heap_release = PETSC_TRUE;
  PetscFunctionBeginUser;
  PetscOptionsBegin(comm, nullptr, "etfe", "etfe");
  PetscCall(PetscOptionsBool("-etfe_traceback", "Errors with PETSc's full report instead of one line", "", traceback,
                             &traceback, nullptr));
  PetscCall(PetscOptionsBool("-options_allow_unused", "Accept option names this project does not know (typos)", "",
                             allow, &allow, nullptr));
  PetscCall(PetscOptionsBool("-etfe_heap_release",
                             "Return freed blocks of 32 MB and more to the system (undoes SuperLU_DIST's "
                             "mallopt; off: a 10^6-triangle rank's memory grows ~1 GB with MUMPS refactoring)",
                             "", heap_release, &heap_release, nullptr));
  PetscOptionsEnd();
  PetscCheck(!heap_release || HeapReleaseLargeBlocks(), comm, PETSC_ERR_SYS,
             "-etfe_heap_release: the C library refused mallopt (run with -etfe_heap_release 0)");
  PetscFunctionReturn(0);
}

PetscErrorCode Run() {
  MPI_Comm comm = PETSC_COMM_WORLD;
  PetscFunctionBeginUser;
  PetscCall(ProgramOptions(comm));
  PetscBool help_only = PETSC_FALSE, list = PETSC_FALSE;
  PetscCall(PetscOptionsHasName(nullptr, nullptr, "-help", &help_only));
  PetscCall(PetscOptionsHasName(nullptr, nullptr, "-scene_list", &list));

  // 1. Registries: scenes, materials, the etfe line search.
  PetscCall(SceneRegisterAll());
  PetscCall(MaterialRegisterAll());
  PetscCall(SNESLineSearchRegisterEtfe());

  // 2. The scene: mesh, supports, loads, schedule.
  // The analysis first: a scene that offers both builds the one asked for.
  Analysis analysis;
  PetscCall(AnalysisFromOptions(comm, &analysis));
  if (analysis == Analysis::plan && !list) {
    PetscCall(RunPlan(comm, help_only));
    PetscFunctionReturn(0);
  }
  if (analysis == Analysis::cutpattern && !list) {
    // Cutting patterns of a surface mesh: no scene, problem or solver.
    CutPatternSurfaceOptions cso;
    PetscCall(CutPatternSurfaceOptionsFromCommandLine(comm, &cso));
    if (help_only) PetscFunctionReturn(0);
    PetscCall(CheckUnusedOptions(comm, PETSC_TRUE));
    PetscCall(CutPatternSurfaceRun(comm, cso));
    PetscCall(CheckUnusedOptions(comm, PETSC_FALSE));
    PetscFunctionReturn(0);
  }
  const bool formfind = analysis == Analysis::formfind;
  SceneSpec scene;
  scene.form_finding = formfind;
  SceneObserver observer;
  PetscCall(SceneCreateFromOptions(comm, &scene, &observer));
  if (list) {
    PetscFunctionReturn(0);
  }
  if (help_only && scene.name.empty()) {
    // -help without a scene: list the options of every component, then stop.
    std::unique_ptr<Material> m;
    Problem throwaway;
    SNES snes;
    SNESLineSearch ls;
    PetscCall(PetscOptionsSetValue(nullptr, "-material_type", "plastic"));
    FormFindOptions ffo_help;
    PetscCall(FormFindOptionsFromCommandLine(comm, &ffo_help));
    PetscCall(MaterialCreateFromOptions(comm, &m));
    PetscCall(ReadMembraneOptions(comm, &throwaway));
    LoadStepperOptions lso;
    PetscCall(LoadStepperOptionsFromCommandLine(comm, &lso));
    OutputOptions oo;
    PetscCall(OutputOptionsFromCommandLine(comm, "scene", &oo));
    CheckpointOptions cko;
    PetscCall(CheckpointOptionsFromCommandLine(comm, "results/scene/scene", &cko));
    {
      double young, nu;
      m->ElasticConstants(&young, &nu);
      ContactOptions co;
      PetscCall(ContactOptionsFromCommandLine(comm, 1e3 * young * throwaway.thickness, 1e-6, &co));
    }
    PetscInt lu_max_dof;
    PetscCall(LUNativeMaxDofFromOptions(comm, &lu_max_dof));
    PetscCall(SNESCreate(comm, &snes));
    PetscCall(SNESGetLineSearch(snes, &ls));
    PetscCall(SNESLineSearchSetType(ls, SNESLINESEARCHETFE));
    PetscCall(SNESSetFromOptions(snes));
    PetscCall(SNESDestroy(&snes));
    PetscFunctionReturn(0);
  }

  // 3-4. Material, membrane, problem, contact, solver and load-stepping options.
  FormFindOptions ffo;
  Problem *P;
  SNES snes;
  LoadStepperOptions lso;
  PetscCall(CreateCase(comm, formfind, std::move(scene), observer, &ffo, &P, &snes, &lso));
  OutputOptions oo;
  PetscCall(OutputOptionsFromCommandLine(comm, P->scene.name.c_str(), &oo));
  CheckpointOptions cko;
  PetscCall(CheckpointOptionsFromCommandLine(comm, std::filesystem::path(oo.path).replace_extension("").string(), &cko));
  PetscCheck(!(formfind && (cko.restart[0] || cko.every > 0)), comm, PETSC_ERR_SUP,
             "checkpoint/restart is for load histories (-analysis stretch); form finding restarts from its "
             "Gmsh output instead");
  if (help_only) {
    PetscCall(CaseDestroy(&snes, &P));
    PetscFunctionReturn(0);
  }
  PetscCall(CheckUnusedOptions(comm, PETSC_TRUE));
  PetscCall(PrintHeader(P, snes));

  // 5. Run the schedule, writing results as it goes.
  OutputFile *out = nullptr;
  PetscInt restart_step = -1;
  // A refused restart must leave every file as it was: check the checkpoint completely before
  // the results file is opened (and truncated to the checkpoint's step).
  std::string run_id;
  if (cko.restart[0]) PetscCall(CheckpointValidate(P, cko.restart, &restart_step, &run_id));
  if (oo.enabled) PetscCall(OutputOpen(P, oo, &out, restart_step, run_id));
  if (out) P->observer.results_stem = OutputStem(out);
  LoadStepperResult res;
  if (formfind) {
    FormFindResult ffr;
    PetscLogDouble t0, t1;
    PetscCall(PetscTime(&t0));
    PetscCall(FormFindRun(P, snes, out, ffo, &ffr));
    PetscCall(PetscTime(&t1));
    res.completed = ffr.converged;
    res.failure = ffr.failure;
    res.steps = ffr.iterations;
    res.time = P->time;
    res.wall = t1 - t0;
    PetscCall(SNESGetLinearSolveIterations(snes, &res.newton_iterations));
  } else {
    PetscCall(LoadStepperRun(P, snes, out, lso, cko, &res));
  }
  PetscCall(PetscPrintf(comm, "etfe: %s after %" PetscInt_FMT " increments (load time %.6g), %" PetscInt_FMT
                        " Newton iterations, %" PetscInt_FMT " cut-backs, %.3f s\n",
                        res.stopped ? "stopped as asked" : res.completed ? "completed" : "STOPPED", res.steps, res.time,
                        res.newton_iterations, res.cutbacks, res.wall));
  PetscCall(PrintPeakMemory(comm, "over the run"));

  // 6. The scene's own quantities of interest, then close the results.
  if (P->observer.report && res.completed && !res.stopped) PetscCall(P->observer.report(P, P->observer.ctx));
  if (res.stopped)
    PetscCall(PetscPrintf(comm, "etfe: checkpoint %s; continue with -restart %s\n", cko.file, cko.file));
  if (out) {
    const std::string status = res.stopped ? "stopped at increment " + std::to_string((long long)res.steps) +
                                                 " (checkpoint " + cko.file + ")"
                               : res.completed ? std::string("complete")
                                               : "failed: " + res.failure;
    PetscCall(OutputClose(&out, status));
    PetscCall(PetscPrintf(comm, "etfe: results in %s (+ .xmf for ParaView)\n", oo.path));
  }
  PetscCall(CaseDestroy(&snes, &P));
  PetscCheck(res.completed, comm, PETSC_ERR_NOT_CONVERGED, "%s. %s", res.failure.c_str(),
             formfind ? "The last iterate is in the results (status \"failed\")."
                      : "The last converged increment is in the results. Ways out: more "
                        "increments (-load_increments), more cut-backs (-load_max_cutbacks), or "
                        "check the supports and loads of the scene");
  PetscCall(CheckUnusedOptions(comm, PETSC_FALSE));
  PetscFunctionReturn(0);
}

} // namespace

int main(int argc, char **argv) {
  PetscBool traceback = PETSC_FALSE;
  PetscMPIInt size;
  // Open MPI's "sm" shared-file-pointer component guards every MPI_File_open with a named
  // semaphore keyed by the file's base name (/dev/shm/sem.OMPIO_<name>): a run killed while
  // writing leaves it taken, and the next run that opens a file of that name (its restart's
  // checkpoint) waits forever. HDF5 never uses shared file pointers, so leave the component out
  // unless the user chose otherwise.
  setenv("OMPI_MCA_sharedfp", "^sm", 0);
  // Options files are expanded here, before PETSc reads the command line (options_files.h).
  std::vector<std::string> args(argv + 1, argv + argc), expanded;
  std::string error;
  if (!ExpandOptionsFiles(args, &expanded, &error)) {
    const char *rank = std::getenv("OMPI_COMM_WORLD_RANK");
    if (!rank || std::strcmp(rank, "0") == 0) std::fprintf(stderr, "etfe: %s\n", error.c_str());
    return 2;
  }
  // Before MPI starts (heap_policy.h): huge pages for the large blocks -etfe_heap_release maps.
  if (HeapReleaseWanted(expanded)) HeapRestartWithHugePages(argv);
  std::vector<char *> new_argv{argv[0]};
  for (std::string &a : expanded) new_argv.push_back(a.data());
  new_argv.push_back(nullptr);
  argc = (int)expanded.size() + 1;
  argv = new_argv.data();
  PetscCall(PetscInitialize(&argc, &argv, nullptr, help));
  PetscCall(PetscOptionsGetBool(nullptr, nullptr, "-etfe_traceback", &traceback, nullptr));
  PetscCall(PetscPushErrorHandler(traceback ? TracebackErrorHandler : ConciseErrorHandler, nullptr));
  MPI_Comm agree;
  PetscCallMPI(MPI_Comm_dup(PETSC_COMM_WORLD, &agree));
  PetscErrorCode ierr = Run();
  if (ierr) {
    PetscCallMPI(MPI_Comm_size(PETSC_COMM_WORLD, &size));
    // Every error exit after the results file exists marks it failed (a reader must tell a dead
    // run from a live one). Only when all ranks are here: a collective write from one rank alone
    // would hang.
    if (OutputIsOpen() && AllRanksFailed(agree)) {
      // The status is rank 0's message (ranks may word one failure differently).
      std::string why = g_first_error.message;
      const int e = g_first_error.sys_errno;
      if (e == ENOSPC || e == EDQUOT || e == EFBIG || e == EIO) why += std::string(" (") + std::strerror(e) + ")";
      unsigned long long n = why.size();
      MPI_Bcast(&n, 1, MPI_UNSIGNED_LONG_LONG, 0, agree);
      why.resize(n);
      MPI_Bcast(why.data(), (int)n, MPI_CHAR, 0, agree);
      PetscPushErrorHandler(PetscReturnErrorHandler, nullptr);
      if (OutputAbandon(why)) (*PetscErrorPrintf)("etfe: the failure could not be recorded in the results status\n");
      PetscPopErrorHandler();
    } else if (OutputIsOpen()) {
      (*PetscErrorPrintf)("etfe: the other ranks did not stop with this error; the results status is not updated\n");
    }
    // An error raised on one rank only would leave the others waiting in PetscFinalize.
    if (size > 1) MPI_Abort(PETSC_COMM_WORLD, (int)ierr);
    PetscFinalize();
    return (int)ierr;
  }
  PetscCall(PetscFinalize());
  return 0;
}
