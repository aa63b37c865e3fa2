// What a run prints about itself (run_report.h).
#include "run_report.h"

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>

#include "etfe/assembly/pressure_term.h"
#include "etfe/material/material.h"

namespace etfe {

// Sizing a dense run needs the peak. After set-up the resident memory now says what a load
// history keeps once rank 0 has released the global description (ProblemReleaseScene).
PetscErrorCode PrintPeakMemory(MPI_Comm comm, const char *when, bool now) {
  struct rusage ru;
  double mb[4], max_mb[4];
  PetscFunctionBeginUser;
  getrusage(RUSAGE_SELF, &ru);
  mb[0] = ru.ru_maxrss / 1024.0; // kB on Linux
  mb[2] = 0.0;
  if (FILE *f = std::fopen("/proc/self/statm", "r")) {
    unsigned long size = 0, resident = 0;
    if (std::fscanf(f, "%lu %lu", &size, &resident) == 2)
      mb[2] = resident * (double)sysconf(_SC_PAGESIZE) / 1048576.0;
    std::fclose(f);
  }
  mb[1] = -mb[0], mb[3] = -mb[2];
  PetscCallMPI(MPI_Allreduce(mb, max_mb, 4, MPI_DOUBLE, MPI_MAX, comm));
  char resident[64] = "";
  if (now && max_mb[2] > 0)
    std::snprintf(resident, sizeof resident, "; resident now %.0f / %.0f MB", max_mb[2],
                  -max_mb[3]);
  PetscCall(PetscPrintf(comm, "  peak memory per rank %s: %.0f MB (max), %.0f MB (min)%s\n", when,
                        max_mb[0], -max_mb[1], resident));
  PetscFunctionReturn(0);
}

namespace {

// The mesh and how METIS shared it over the ranks.
PetscErrorCode PrintMeshAndRanks(Problem *P) {
  PetscInt emin, emax, nmin, nmax;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Allreduce(&P->mesh.num_elements, &emin, 1, MPIU_INT, MPI_MIN, P->comm));
  PetscCallMPI(MPI_Allreduce(&P->mesh.num_elements, &emax, 1, MPIU_INT, MPI_MAX, P->comm));
  PetscCallMPI(MPI_Allreduce(&P->mesh.num_owned, &nmin, 1, MPIU_INT, MPI_MIN, P->comm));
  PetscCallMPI(MPI_Allreduce(&P->mesh.num_owned, &nmax, 1, MPIU_INT, MPI_MAX, P->comm));
  PetscCall(PetscPrintf(P->comm,
                        "  mesh: %s, %" PetscInt_FMT " nodes, %" PetscInt_FMT
                        " triangles, %" PetscInt_FMT " DOF\n",
                        P->mesh.source.c_str(), P->mesh.num_nodes_global,
                        P->mesh.num_elements_global, 3 * P->mesh.num_nodes_global));
  PetscCall(
      PetscPrintf(P->comm,
                  "  ranks: %d (METIS), elements per rank %" PetscInt_FMT "-%" PetscInt_FMT
                  ", owned nodes per rank %" PetscInt_FMT "-%" PetscInt_FMT " (imbalance %.3f)\n",
                  P->size, emin, emax, nmin, nmax,
                  emax * (double)P->size / std::max<PetscInt>(1, P->mesh.num_elements_global)));
  PetscFunctionReturn(0);
}

// The solver as the options left it (types, not the defaults of solver_defaults.h).
PetscErrorCode PrintSolver(MPI_Comm comm, SNES snes) {
  KSP ksp;
  PC pc;
  KSPType ktype;
  PCType ptype;
  MatSolverType stype = nullptr;
  SNESLineSearch ls;
  SNESLineSearchType lstype;
  PetscFunctionBeginUser;
  PetscCall(SNESGetKSP(snes, &ksp));
  PetscCall(KSPGetType(ksp, &ktype));
  PetscCall(KSPGetPC(ksp, &pc));
  PetscCall(PCGetType(pc, &ptype));
  PetscCall(PCFactorGetMatSolverType(pc, &stype));
  PetscCall(SNESGetLineSearch(snes, &ls));
  PetscCall(SNESLineSearchGetType(ls, &lstype));
  PetscCall(PetscPrintf(comm, "  solver: SNES newtonls, line search %s, KSP %s, PC %s%s%s\n",
                        lstype, ktype, ptype, stype ? " " : "", stype ? stype : ""));
  PetscFunctionReturn(0);
}

} // namespace

PetscErrorCode PrintHeader(Problem *P, SNES snes) {
  PetscInt ncon = (PetscInt)P->con_owned_dof.size(), ncon_all;
  PetscFunctionBeginUser;
  PetscCall(PetscPrintf(P->comm, "etfe: scene %s\n", P->scene.name.c_str()));
  PetscCall(PrintMeshAndRanks(P));
  PetscCallMPI(MPI_Allreduce(&ncon, &ncon_all, 1, MPIU_INT, MPI_SUM, P->comm));
  PetscCall(PetscPrintf(
      P->comm,
      "  physics: membrane (TL, h0 = %g mm), %s material%s, %" PetscInt_FMT " constrained DOF\n",
      P->thickness, P->material->Name(), FindTerm<PressureTerm>(*P) ? ", follower pressure" : "", ncon_all));
  PetscCall(P->material->View(P->comm));
  // The surface groups' own laws ("film_<group>_": -film_<group>_material_*).
  for (size_t k = 0; k < P->part_materials.size(); ++k) {
    const std::string &prefix = P->scene.material_prefixes[k];
    PetscCall(PetscPrintf(P->comm, "  surface group %s (-%smaterial_*):\n",
                          prefix.substr(5, prefix.size() - 6).c_str(), prefix.c_str()));
    PetscCall(P->part_materials[k]->View(P->comm));
  }
  PetscCall(PrintSolver(P->comm, snes));
  {
    // The streamed set-up: rank 0 alone held the global mesh and description and sent each rank
    // its share (src/mesh/distribute.cpp).
    double kb[2] = {P->mesh.share_bytes / 1024.0, -(P->mesh.share_bytes / 1024.0)}, all[2];
    PetscCallMPI(MPI_Allreduce(kb, all, 2, MPI_DOUBLE, MPI_MAX, P->comm));
    PetscCall(PetscPrintf(P->comm,
                          "  set-up: rank 0 built the scene and sent each rank its share: %.0f kB "
                          "(max), %.0f kB (min)\n",
                          all[0], -all[1]));
  }
  {
    std::vector<std::string> lines;
    for (const auto &term : P->terms) PetscCall(term->SetupLines(*P, &lines));
    for (const std::string &line : lines) PetscCall(PetscPrintf(P->comm, "  %s\n", line.c_str()));
  }
  if (!P->scene.initial_guess_note.empty())
    PetscCall(PetscPrintf(P->comm, "  initial guess: %s\n", P->scene.initial_guess_note.c_str()));
  PetscCall(PrintPeakMemory(P->comm, "after set-up", true));
  PetscFunctionReturn(0);
}

PetscErrorCode PrintRunSummary(MPI_Comm comm, const LoadStepperResult &res) {
  PetscFunctionBeginUser;
  PetscCall(PetscPrintf(comm,
                        "etfe: %s after %" PetscInt_FMT
                        " increments (load time %.6g), %" PetscInt_FMT
                        " Newton iterations, %" PetscInt_FMT " cut-backs, %.3f s\n",
                        res.interrupted ? "stopped by a signal"
                        : res.stopped   ? "stopped as asked"
                        : res.completed ? "completed"
                                        : "STOPPED",
                        res.steps, res.time, res.newton_iterations, res.cutbacks, res.wall));
  PetscCall(PrintPeakMemory(comm, "over the run"));
  PetscFunctionReturn(0);
}

} // namespace etfe
