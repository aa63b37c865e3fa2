// Form finding by updated-reference iterations (see formfind.h for the method).
#include <cmath>
#include <filesystem>

#include "etfe/assembly/assembly.h"
#include "etfe/assembly/cable_term.h"
#include "etfe/analyses/cutpattern.h"
#include "etfe/analyses/formfind.h"
#include "etfe/kernels/status.h"
#include "etfe/mesh/gmsh_reader.h"

namespace etfe {

PetscErrorCode FormFindOptionsFromCommandLine(MPI_Comm comm, FormFindOptions *o) {
  PetscFunctionBeginUser;
  PetscOptionsBegin(comm, nullptr, "Form finding (-analysis formfind)", "FormFind");
  PetscCall(PetscOptionsReal("-formfind_stress", "Prescribed TD membrane stress [MPa]", "", o->stress, &o->stress, nullptr));
  PetscCall(PetscOptionsReal("-formfind_ratio", "Stress ratio MD:TD (1 = isotropic, minimal surface)", "", o->ratio,
                             &o->ratio, nullptr));
  PetscCall(PetscOptionsInt("-formfind_max_iterations", "Updated-reference iterations before giving up", "",
                            o->max_iterations, &o->max_iterations, nullptr));
  PetscCall(PetscOptionsReal("-formfind_tol", "Converged when the largest nodal move < tol * model size", "", o->tol,
                             &o->tol, nullptr));
  PetscCall(PetscOptionsString("-formfind_mesh_out", "Gmsh file of the found surface (default beside the results)",
                               "", o->mesh_out, o->mesh_out, sizeof o->mesh_out, nullptr));
  PetscCall(PetscOptionsBool("-formfind_mesh_control",
                             "Move interior nodes along their normals only (no in-plane drift)", "",
                             o->mesh_control, &o->mesh_control, nullptr));
  PetscCall(PetscOptionsInt("-formfind_monitor", "Print every n-th iteration (0: quiet)", "", o->monitor,
                            &o->monitor, nullptr));
  PetscOptionsEnd();
  PetscCall(CutPatternOptionsFromCommandLine(comm, &o->cutpattern));
  PetscCheck(o->stress > 0 && o->ratio > 0, comm, PETSC_ERR_ARG_OUTOFRANGE,
             "-formfind_stress %g / -formfind_ratio %g: a form-finding stress must be tensile (> 0)", o->stress,
             o->ratio);
  PetscCheck(o->max_iterations >= 1 && o->tol > 0, comm, PETSC_ERR_ARG_OUTOFRANGE,
             "-formfind_max_iterations must be >= 1 and -formfind_tol > 0");
  PetscFunctionReturn(0);
}

namespace {

// Area-weighted nodal normals of the reference, unnormalised, in P->F_work (owned part valid).
PetscErrorCode NodalNormals(Problem *P) {
  const LocalMesh &lm = P->mesh;
  Vec acc = P->F_work, accl;
  PetscScalar *a;
  PetscFunctionBeginUser;
  PetscCall(VecGhostGetLocalForm(acc, &accl));
  PetscCall(VecZeroEntries(accl));
  PetscCall(VecGetArray(accl, &a));
  for (PetscInt e = 0; e < lm.num_elements; ++e) {
    const double A = lm.ref[e].area, *n = &lm.ref[e].frame[6];
    for (int k = 0; k < 3; ++k)
      for (int i = 0; i < 3; ++i) a[3 * lm.tri[3 * e + k] + i] += A * n[i];
  }
  PetscCall(VecRestoreArray(accl, &a));
  PetscCall(VecGhostRestoreLocalForm(acc, &accl));
  PetscCall(VecGhostUpdateBegin(acc, ADD_VALUES, SCATTER_REVERSE));
  PetscCall(VecGhostUpdateEnd(acc, ADD_VALUES, SCATTER_REVERSE));
  PetscFunctionReturn(0);
}

PetscErrorCode MaxNormalMove(Problem *P, Vec U, PetscReal *m) {
  const LocalMesh &lm = P->mesh;
  Vec acc = P->F_work;
  PetscScalar *a;
  const PetscScalar *u;
  PetscReal local = 0.0;
  PetscFunctionBeginUser;
  PetscCall(NodalNormals(P));
  PetscCall(VecGetArray(acc, &a));
  PetscCall(VecGetArrayRead(U, &u));
  for (PetscInt l = 0; l < lm.num_owned; ++l) {
    const double *n = &a[3 * l];
    const double nn = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    if (nn > 0)
      local = PetscMax(local, std::fabs(u[3 * l] * n[0] + u[3 * l + 1] * n[1] + u[3 * l + 2] * n[2]) / nn);
  }
  PetscCall(VecRestoreArrayRead(U, &u));
  PetscCall(VecRestoreArray(acc, &a));
  PetscCallMPI(MPI_Allreduce(&local, m, 1, MPIU_REAL, MPIU_MAX, P->comm));
  PetscFunctionReturn(0);
}

// Mesh control: interior nodes move along their normal only. The shape is decided by the
// normal balance; tangential updates only redistribute nodes, and with an anisotropic stress
// (which cannot be in exact tangential balance on a curved surface) they would drift for ever.
// Constrained components keep their solved (prescribed) values.
PetscErrorCode ProjectOnNormals(Problem *P, Vec U) {
  const LocalMesh &lm = P->mesh;
  PetscScalar *a, *u;
  PetscFunctionBeginUser;
  PetscCall(NodalNormals(P));
  PetscCall(VecGetArray(P->F_work, &a));
  PetscCall(VecGetArray(U, &u));
  for (PetscInt l = 0; l < lm.num_owned; ++l) {
    const char *con = &P->dof_constrained[3 * l];
    if (con[0] && con[1] && con[2]) continue;
    const double *n = &a[3 * l];
    const double nn = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    if (nn == 0) continue;
    const double un = (u[3 * l] * n[0] + u[3 * l + 1] * n[1] + u[3 * l + 2] * n[2]) / (nn * nn);
    for (int i = 0; i < 3; ++i)
      if (!con[i]) u[3 * l + i] = un * n[i];
  }
  PetscCall(VecRestoreArray(U, &u));
  PetscCall(VecRestoreArray(P->F_work, &a));
  PetscFunctionReturn(0);
}

// The diagonal of the mesh's bounding box (collective).
PetscErrorCode ModelSize(Problem *P, double *size) {
  double ext[6] = {1e300, 1e300, 1e300, 1e300, 1e300, 1e300}, all[6];  // min X, -max X
  PetscFunctionBeginUser;
  for (PetscInt l = 0; l < P->mesh.num_owned; ++l)
    for (int i = 0; i < 3; ++i) {
      ext[i] = std::min(ext[i], P->mesh.X[3 * l + i]);
      ext[3 + i] = std::min(ext[3 + i], -P->mesh.X[3 * l + i]);
    }
  PetscCallMPI(MPI_Allreduce(ext, all, 6, MPI_DOUBLE, MPI_MIN, P->comm));
  *size = std::sqrt((-all[3] - all[0]) * (-all[3] - all[0]) + (-all[4] - all[1]) * (-all[4] - all[1]) +
                    (-all[5] - all[2]) * (-all[5] - all[2]));
  PetscFunctionReturn(0);
}

// The fixed-point iteration: solve at the prescribed stress, move the reference onto the
// solution, until the largest normal move is below tol * size. The moves add up in U_total; res
// gets the iterations, the last move, and converged or what went wrong.
PetscErrorCode IterateShape(Problem *P, SNES snes, const FormFindOptions &o, double size, double t_end, Vec U_total,
                            FormFindResult *res) {
  PetscFunctionBeginUser;
  for (PetscInt it = 1; it <= o.max_iterations; ++it) {
    PetscCall(VecZeroEntries(P->U));
    PetscCall(ProblemSetLoadTime(P, t_end, P->U));
    PetscCall(SNESSolve(snes, nullptr, P->U));
    SNESConvergedReason reason;
    PetscCall(SNESGetConvergedReason(snes, &reason));
    if (reason <= 0) {
      char why[400];
      std::snprintf(why, sizeof why,
                    "form finding iteration %lld: %s%s%s. No equilibrium surface with this stress "
                    "fits these boundaries (or the mesh folded): check the boundary positions, "
                    "the stress ratio, or refine the mesh",
                    (long long)it, SNESConvergedReasons[reason],
                    P->diagnostics.bad_status ? " at element " : "",
                    P->diagnostics.bad_status ? (std::to_string((long long)P->diagnostics.bad_element) + " (" +
                                                 KernelStatusName(P->diagnostics.bad_status) + ")").c_str()
                                              : "");
      res->failure = why;
      break;
    }
    PetscReal move, all;
    if (o.mesh_control) PetscCall(ProjectOnNormals(P, P->U));
    PetscCall(MaxNormalMove(P, P->U, &move));
    PetscCall(VecMaxNodalNorm(P->U, &all));
    // Cables: the edges they hold move in the film's tangent plane, so their nodes' moves across
    // the cable count too (the tangential drift of the interior, and of the cable nodes along
    // the cable, does not shape the surface).
    if (!P->scene.cables.empty()) {
      PetscReal cable_move;
      PetscCall(CableLargestMove(P, P->U, &cable_move));
      move = PetscMax(move, cable_move);
    }
    PetscCall(VecAXPY(U_total, 1.0, P->U));
    PetscCall(UpdateReference(P, P->U));
    if (P->diagnostics.bad_status != KERNEL_OK) {
      res->failure = "form finding iteration " + std::to_string((long long)it) + ": element " +
                     std::to_string((long long)P->diagnostics.bad_element) +
                     " collapsed (the surface pinches off: no equilibrium shape spans these "
                     "boundaries, e.g. catenoid rings beyond the Goldschmidt limit)";
      break;
    }
    res->iterations = it;
    res->last_move = move;
    if (o.monitor > 0 && (it % o.monitor == 0 || move < o.tol * size))
      PetscCall(PetscPrintf(P->comm, "formfind: iteration %4" PetscInt_FMT "  largest normal move %.3e mm (any direction %.3e mm)\n",
                            it, move, all));
    if (move < o.tol * size) {
      res->converged = PETSC_TRUE;
      break;
    }
  }
  if (res->failure.empty() && !res->converged)
    res->failure = "form finding did not converge in " + std::to_string((long long)o.max_iterations) +
                   " iterations (last move " + std::to_string(res->last_move) +
                   " mm): raise -formfind_max_iterations or -formfind_tol, or the shape keeps "
                   "shrinking because none exists for these boundaries";
  PetscFunctionReturn(0);
}

// The found surface as written: without the surface group "all" of every element (the general
// scene and the mesh generators add it to name the whole film, and add it again when they read the
// file) where other surface groups name the strips: written, it would overlap them, and
// -analysis cutpattern refuses overlapping strips.
MeshData WrittenSurface(const MeshData &shape) {
  const auto all = shape.element_sets.find("all");
  if (all == shape.element_sets.end() || shape.element_sets.size() < 2 ||
      (int)all->second.size() != shape.NumElements())
    return shape;
  MeshData m = shape;
  m.element_sets.erase("all");
  return m;
}

// Writes the found surface as Gmsh (rank 0) to -formfind_mesh_out or beside the results.
PetscErrorCode WriteFoundSurface(Problem *P, const OutputFile *out, const FormFindOptions &o, const MeshData &shape,
                                 std::string *path) {
  PetscFunctionBeginUser;
  *path = o.mesh_out;
  if (path->empty())
    *path = (out ? OutputDirectory(out) : std::string("results/") + P->scene.name) + "/" + P->scene.name +
            "_formfound.msh";
  if (P->rank == 0) {
    std::error_code ec;
    auto dir = std::filesystem::path(*path).parent_path();
    if (!dir.empty()) std::filesystem::create_directories(dir, ec);
    std::string err;
    PetscCheck(WriteGmshFile(*path, WrittenSurface(shape), &err), PETSC_COMM_SELF, PETSC_ERR_FILE_WRITE, "%s",
               err.c_str());
  }
  PetscFunctionReturn(0);
}

// Cuts the found surface (written to path) into flat patterns beside it.
PetscErrorCode CutFoundSurface(Problem *P, const FormFindOptions &o, const MeshData &shape, const std::string &path) {
  PetscFunctionBeginUser;
  const std::filesystem::path p(path);
  // Stress compensation without -cutpattern_prestress: the form-finding stress, (ratio S, S)
  // in each element's MD/TD frame (the Cauchy stress at the fixed point, taken as the PK2
  // the drawn film must reach).
  CutPatternOptions cpo = o.cutpattern;
  cpo.element_stress = true;
  for (int i = 0; i < 3; ++i) cpo.md_axis[i] = P->scene.md_axis[i];
  if (P->rank == 0 && cpo.compensation == Compensation::Stress && !cpo.prestress_given) {
    const auto &ratio = P->scene.element_stress_ratio;
    cpo.element_prestress.resize(3 * (size_t)shape.NumElements());
    for (int e = 0; e < shape.NumElements(); ++e) {
      cpo.element_prestress[3 * e] = (ratio.empty() ? o.ratio : ratio[e]) * o.stress;
      cpo.element_prestress[3 * e + 1] = o.stress;
      cpo.element_prestress[3 * e + 2] = 0.0;
    }
  }
  PetscCall(CutPatternRun(P->comm, shape, cpo, p.parent_path().empty() ? "." : p.parent_path().string(),
                          p.stem().string()));
  PetscFunctionReturn(0);
}

} // namespace

PetscErrorCode FormFindRun(Problem *P, SNES snes, OutputFile *out, const FormFindOptions &o,
                           FormFindResult *res) {
  Vec U_total;
  PetscFunctionBeginUser;
  PetscCall(VecDuplicate(P->U, &U_total));
  PetscCall(VecZeroEntries(U_total));
  double size = 0.0;
  PetscCall(ModelSize(P, &size));
  const double t_end = P->scene.NumStages();  // boundaries at their final (prescribed) positions
  res->converged = PETSC_FALSE;
  // A scene may give each element its own stress ratio (the saddle: middle 1:1, corners 3:1).
  // The prescribed-stress material keeps (S_MD, S_TD) as its element history.
  const auto &ratio = P->element_stress_ratio;
  if (!ratio.empty())
    for (PetscInt e = 0; e < P->mesh.num_elements; ++e) P->history[2 * e] = ratio[e] * P->history[2 * e + 1];
  PetscCall(IterateShape(P, snes, o, size, t_end, U_total, res));
  // The found surface: displacement from the scene's mesh, stresses at the last iterate.
  PetscCall(VecZeroEntries(P->U));
  PetscCall(ProblemSetLoadTime(P, t_end, P->U));
  PetscCall(ProblemUpdateReactions(P, P->U));
  if (out) PetscCall(OutputWriteStep(out, P, U_total, 1, t_end, P->U));
  if (res->converged) {
    MeshData shape;
    std::string path;
    PetscCall(OutputGatherShape(P, P->U, &shape));
    PetscCall(WriteFoundSurface(P, out, o, shape, &path));
    PetscCall(PetscPrintf(P->comm, "formfind: converged after %" PetscInt_FMT " iterations; surface written to %s\n",
                          res->iterations, path.c_str()));
    for (const auto &term : P->terms) {  // the terms' lines (cables: force, length, cut length)
      std::vector<std::string> lines;
      PetscCall(term->Report(*P, &lines));
      for (const std::string &l : lines) PetscCall(PetscPrintf(P->comm, "formfind: %s\n", l.c_str()));
    }
    if (o.cutpattern.enabled) PetscCall(CutFoundSurface(P, o, shape, path));
  }
  // P->U now holds the total displacement so that scene reports see the found shape.
  PetscCall(VecZeroEntries(P->U));
  PetscCall(VecDestroy(&U_total));
  PetscFunctionReturn(0);
}

} // namespace etfe
