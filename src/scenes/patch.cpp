// Patch scene: a flat rectangle (optionally an irregular mesh) stretched in its plane, uniaxial
// (free lateral edge) or biaxial, with a stage schedule of stretch multipliers so loading,
// unloading and reloading are one option (-patch_schedule 1,0,1.5). Every element must carry the
// same stress; with an elastic material the scene prints the closed form too.
#include <petscsys.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "etfe/assembly.h"
#include "etfe/mesh/generators.h"
#include "etfe/mesh/mesh_options.h"
#include "etfe/rank0.h"
#include "etfe/scene_registry.h"
#include "etfe/verification/patch_closed_form.h"
#include "real_array_option.h"

namespace etfe {

namespace {

enum class PatchMode { Uniaxial, Biaxial, PureShear, Shear };

struct PatchContext {
  double ex, ey;  // engineering strain at schedule value 1
  PatchMode mode;
  double final_factor;
};

// Stretch in Y that makes Eyy = -Exx (pure shear in the principal axes).
double PureShearStretchY(double lx) { return std::sqrt(std::max(0.0, 2.0 - lx * lx)); }

PetscErrorCode PatchReport(Problem *P, void *vctx) {
  auto *ctx = (PatchContext *)vctx;
  CellFields c;
  PetscFunctionBeginUser;
  PetscCall(ComputeCellFields(P, P->U, &c, false));
  double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300}, glo[3], ghi[3];
  for (PetscInt e = 0; e < P->mesh.num_elements; ++e)
    for (int i = 0; i < 3; ++i) {
      lo[i] = std::min(lo[i], c.stress[3 * e + i]);
      hi[i] = std::max(hi[i], c.stress[3 * e + i]);
    }
  PetscCallMPI(MPI_Allreduce(lo, glo, 3, MPI_DOUBLE, MPI_MIN, P->comm));
  PetscCallMPI(MPI_Allreduce(hi, ghi, 3, MPI_DOUBLE, MPI_MAX, P->comm));
  const double scale = std::max({std::fabs(ghi[0]), std::fabs(ghi[1]), std::fabs(glo[0]),
                                 std::fabs(glo[1]), 1e-30});
  const double spread = std::max({ghi[0] - glo[0], ghi[1] - glo[1], ghi[2] - glo[2]}) / scale;
  PetscCall(PetscPrintf(P->comm,
                        "patch: Sxx in [%.10e, %.10e], Syy in [%.10e, %.10e], Sxy in [%.3e, %.3e] MPa\n"
                        "patch: stress_spread = %.3e (max - min over elements, relative)\n",
                        glo[0], ghi[0], glo[1], ghi[1], glo[2], ghi[2], spread));
  if (std::string(P->material->Name()) == "elastic" && ctx->mode != PatchMode::Shear) {
    double young, nu, S[2];
    P->material->ElasticConstants(&young, &nu);
    const double lx = 1.0 + ctx->ex * ctx->final_factor;
    const double Exx = 0.5 * (lx * lx - 1.0);
    double Eyy = 0.0;
    if (ctx->mode != PatchMode::Uniaxial) {
      const double ly = ctx->mode == PatchMode::Biaxial ? 1.0 + ctx->ey * ctx->final_factor
                                                        : PureShearStretchY(lx);
      Eyy = 0.5 * (ly * ly - 1.0);
    }
    PatchClosedFormStress(young, nu, Exx, Eyy, ctx->mode == PatchMode::Uniaxial, S);
    const double err = std::max(std::fabs(ghi[0] - S[0]), std::fabs(glo[0] - S[0])) / std::fabs(S[0]);
    PetscCall(PetscPrintf(P->comm, "patch: closed_form Sxx = %.10e Syy = %.10e, relative_error = %.3e\n",
                          S[0], S[1], err));
  }
  PetscFunctionReturn(0);
}

// What the patch options give, defaults included.
struct PatchInputs {
  double lx = 1000.0, ly = 500.0;  // size of the generated rectangle [mm]; a mesh file's own size replaces it
  double ex = 0.02, ey = 0.0, shear = 0.0;
  std::vector<double> schedule = {1.0};  // stretch multiplier at the end of each stage
  PatchMode mode = PatchMode::Uniaxial;
  MeshOptions mesh;
};

PetscErrorCode ReadPatchOptions(MPI_Comm comm, PatchInputs *in) {
  char mode[32] = "uniaxial";
  PetscBool sched_named = PETSC_FALSE;
  PetscFunctionBeginUser;
  PetscOptionsBegin(comm, nullptr, "Patch scene: in-plane stretch of a rectangle", "Scene");
  PetscCall(PetscOptionsReal("-patch_lx", "Length in X [mm]", "", in->lx, &in->lx, nullptr));
  PetscCall(PetscOptionsReal("-patch_ly", "Width in Y [mm]", "", in->ly, &in->ly, nullptr));
  PetscCall(PetscOptionsReal("-patch_strain_x", "Engineering strain in X at schedule value 1", "", in->ex, &in->ex,
                             nullptr));
  PetscCall(PetscOptionsReal("-patch_strain_y", "Engineering strain in Y (biaxial only)", "", in->ey, &in->ey,
                             nullptr));
  PetscCall(PetscOptionsString("-patch_mode",
                               "uniaxial (top edge free), biaxial (-patch_strain_y on the top edge), "
                               "pureshear (Eyy = -Exx exactly at stage ends, interpolated in between), "
                               "shear (shear panel: every edge node on u = (ex X + g Y, ex Y), g = -patch_shear)",
                               "", mode, mode, sizeof mode, nullptr));
  PetscCall(PetscOptionsReal("-patch_shear", "Shear g = du_x/dY at schedule value 1 (-patch_mode shear)", "",
                             in->shear, &in->shear, nullptr));
  PetscCall(OptionsRealArray(PetscOptionsObject, "-patch_schedule",
                             "Stretch multipliers at the end of each stage, e.g. 1,0,1.5", &in->schedule,
                             &sched_named));
  PetscOptionsEnd();
  in->mesh.keys = kMeshFile | kMeshGrid | kMeshRefine | kMeshIrregular;
  in->mesh.nx = 8, in->mesh.ny = 4;
  PetscCall(MeshOptionsFromCommandLine(comm, "patch scene", &in->mesh));
  // PETSc reports an option given without values as not set: that is an empty schedule.
  PetscCheck(!sched_named || !in->schedule.empty(), comm, PETSC_ERR_ARG_SIZ,
             "-patch_schedule is empty: give at least one stage value (e.g. 1 or 1,0,1.5)");
  for (size_t k = 0; k < in->schedule.size(); ++k)
    PetscCheck(std::isfinite(in->schedule[k]), comm, PETSC_ERR_ARG_OUTOFRANGE,
               "-patch_schedule value %zu is %g: schedule values must be finite numbers", k + 1, in->schedule[k]);
  PetscCheck(std::isfinite(in->ex) && std::isfinite(in->ey) && in->ex > -1 && in->ey > -1, comm,
             PETSC_ERR_ARG_OUTOFRANGE, "-patch_strain_x %g / -patch_strain_y %g: strains must be finite and > -1",
             in->ex, in->ey);
  const MeshOptions &m = in->mesh;
  PetscCheck(in->lx > 0 && in->ly > 0 && m.nx >= 1 && m.ny >= 1 && m.refine >= 0 && m.refine < 12, comm,
             PETSC_ERR_ARG_OUTOFRANGE,
             "patch: need positive -patch_lx/-patch_ly, -mesh_nx/-mesh_ny >= 1, 0 <= -mesh_refine < 12");
  PetscCheck(m.perturb >= 0 && m.perturb < 0.5, comm, PETSC_ERR_ARG_OUTOFRANGE,
             "-mesh_perturb %g: must lie in [0, 0.5) or elements may invert", m.perturb);
  static const char *const modes[] = {"uniaxial", "biaxial", "pureshear", "shear"};
  int k = 0;
  while (k < 4 && std::string(mode) != modes[k]) ++k;
  PetscCheck(k < 4, comm, PETSC_ERR_ARG_UNKNOWN_TYPE, "-patch_mode %s: use uniaxial, biaxial, pureshear or shear",
             mode);
  in->mode = (PatchMode)k;
  PetscCheck(in->mode == PatchMode::Shear || in->shear == 0.0, comm, PETSC_ERR_ARG_INCOMP,
             "-patch_shear %g is for -patch_mode shear (the mode is %s)", in->shear, mode);
  const int per_cell = m.pattern == DiagonalPattern::Crossed ? 4 : 2;
  PetscCheck(GeneratedTriangles(m.nx, m.ny, per_cell, m.refine) <= kMaxGeneratedTriangles, comm,
             PETSC_ERR_ARG_OUTOFRANGE,
             "-mesh_nx %" PetscInt_FMT " -mesh_ny %" PetscInt_FMT " -mesh_refine %" PetscInt_FMT ": %.3g triangles, more "
             "than the %.3g a generated mesh may have", m.nx, m.ny, m.refine,
             GeneratedTriangles(m.nx, m.ny, per_cell, m.refine), kMaxGeneratedTriangles);
  PetscFunctionReturn(0);
}

// -mesh_file: the rectangle read (rank 0 checks its edge groups and flatness) and measured: the
// strains apply to its own size, which replaces -patch_lx/-patch_ly.
PetscErrorCode ReadPatchMesh(MPI_Comm comm, PatchInputs *in, SceneSpec *scene) {
  const char *mesh_file = in->mesh.file.c_str();
  std::string err;
  double ext[3] = {0, 0, 0};
  PetscFunctionBeginUser;
  PetscCall(SceneReadMesh(comm, mesh_file, &scene->mesh));
  if (SceneHoldsMesh(comm)) {
    for (const char *name : {"left", "right", "bottom", "top"})
      if (err.empty() && !scene->mesh.node_sets.count(name))
        err = std::string(mesh_file) + ": the patch scene needs a physical group named \"" + name +
              "\" (lines of that edge)";
    double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};
    for (int i = 0; i < scene->mesh.NumNodes(); ++i)
      for (int c = 0; c < 3; ++c) {
        lo[c] = std::min(lo[c], scene->mesh.coords[3 * i + c]);
        hi[c] = std::max(hi[c], scene->mesh.coords[3 * i + c]);
      }
    for (int c = 0; c < 3; ++c) ext[c] = hi[c] - lo[c];
    if (err.empty() && !(ext[0] > 0 && ext[1] > 0 && ext[2] <= 1e-9 * std::max(ext[0], ext[1]))) {
      char buf[PETSC_MAX_PATH_LEN + 160];
      std::snprintf(buf, sizeof buf, "%s: the patch scene needs a flat mesh in the XY plane; this one spans %g x %g x %g mm",
                    mesh_file, ext[0], ext[1], ext[2]);
      err = buf;
    }
  }
  PetscCall(Rank0Outcome(comm, err.empty() ? 1 : 0, err, PETSC_ERR_ARG_WRONG));
  PetscCallMPI(MPI_Bcast(ext, 3, MPI_DOUBLE, 0, comm));
  in->lx = ext[0];
  in->ly = ext[1];
  char size[64];  // PETSc's %g writes 10 as "10."
  std::snprintf(size, sizeof size, "%g x %g mm", in->lx, in->ly);
  PetscCall(PetscPrintf(comm, "patch: %s spans %s; the strains apply to that size (-patch_lx/-patch_ly size "
                              "the generated mesh only)\n", mesh_file, size));
  scene->mesh.node_sets["all"].resize(scene->mesh.NumNodes());
  for (int i = 0; i < scene->mesh.NumNodes(); ++i) scene->mesh.node_sets["all"][i] = i;
  PetscFunctionReturn(0);
}

// Shear panel (pretension ex in X and Y plus the shear g): the homogeneous deformation
// F = [[1 + ex, g], [0, 1 + ex]] on every edge node, so the whole panel takes it.
void AddShearPanelSupports(const PatchInputs &in, int is, SceneSpec *scene) {
  auto &sets = scene->mesh.node_sets;
  std::vector<char> edge(scene->mesh.NumNodes(), 0);
  for (const char *name : {"left", "right", "bottom", "top"})
    for (int n : sets[name]) edge[n] = 1;
  for (int n = 0; n < scene->mesh.NumNodes(); ++n) {
    if (!edge[n]) continue;
    const double X = scene->mesh.coords[3 * n], Y = scene->mesh.coords[3 * n + 1];
    scene->constraints.push_back({n, 0, {{in.ex * X + in.shear * Y, 0.0}, {is, -1}}});
    scene->constraints.push_back({n, 1, {{in.ex * Y, 0.0}, {is, -1}}});
  }
}

// Uniaxial, biaxial and pure shear: left and bottom edges on rollers, the right edge drawn in X,
// the top edge drawn in Y (biaxial; pure shear by a schedule of its own) or free (uniaxial).
void AddStretchSupports(const PatchInputs &in, int is, SceneSpec *scene) {
  auto &sets = scene->mesh.node_sets;
  for (int n : sets["left"]) scene->constraints.push_back({n, 0, {}});
  for (int n : sets["bottom"]) scene->constraints.push_back({n, 1, {}});
  for (int n : sets["right"]) scene->constraints.push_back({n, 0, {{in.ex * in.lx, 0.0}, {is, -1}}});
  if (in.mode == PatchMode::Biaxial)
    for (int n : sets["top"]) scene->constraints.push_back({n, 1, {{in.ey * in.ly, 0.0}, {is, -1}}});
  if (in.mode == PatchMode::PureShear) {
    // Eyy = -Exx is not linear in the schedule value, so each stage end gets its own value:
    // a second schedule carries the Y stretch of each stage end, interpolated in between.
    Schedule sy{"stretch_y", 0.0, {}};
    for (double f : in.schedule) sy.values.push_back(PureShearStretchY(1.0 + in.ex * f) - 1.0);
    const int iy = scene->AddSchedule(sy);
    for (int n : sets["top"]) scene->constraints.push_back({n, 1, {{in.ly, 0.0}, {iy, -1}}});
  }
}

} // namespace

PetscErrorCode SceneBuild_Patch(MPI_Comm comm, SceneSpec *scene, SceneObserver *observer) {
  PatchInputs in;
  PetscFunctionBeginUser;
  PetscCall(ReadPatchOptions(comm, &in));
  if (!in.mesh.file.empty()) {
    PetscCall(ReadPatchMesh(comm, &in, scene));
  } else if (SceneHoldsMesh(comm)) {
    const MeshOptions &m = in.mesh;
    scene->mesh = MakeRectangleMesh(0.0, 0.0, in.lx, in.ly, (int)(m.nx << m.refine), (int)(m.ny << m.refine),
                                    m.pattern, m.perturb, 12345u);
  }
  const int is = scene->AddSchedule(Schedule{"stretch", 0.0, in.schedule});
  for (int n : scene->mesh.node_sets["all"]) scene->constraints.push_back({n, 2, {}});  // empty but on rank 0
  if (in.mode == PatchMode::Shear)
    AddShearPanelSupports(in, is, scene);
  else
    AddStretchSupports(in, is, scene);
  auto *ctx = new PatchContext{in.ex, in.ey, in.mode, in.schedule.back()};
  observer->report = PatchReport;
  observer->ctx = ctx;
  observer->destroy = [](void *c) { delete (PatchContext *)c; };
  PetscFunctionReturn(0);
}

} // namespace etfe
