// -scene patch: a flat rectangle (optionally an irregular mesh, or a mesh file) stretched in its
// plane as a case of the general scene: uniaxial (free lateral edge), biaxial, pure shear, or a
// shear panel (every edge node on a homogeneous deformation, -bc_<group>_gradient), with a stage
// schedule of stretch multipliers so loading, unloading and reloading are one option
// (-patch_schedule 1,0,1.5). Every element must carry the same stress; with an elastic material
// the closed form is printed too (-structure_check patch). The same case as options only:
// options/structure/verify_patch.opts; this scene keeps its own option names (-patch_*).
#include <petscsys.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "etfe/mesh/generators.h"
#include "etfe/mesh/mesh_options.h"
#include "etfe/base/rank0.h"
#include "etfe/scenes/scene_registry.h"
#include "real_array_option.h"
#include "structure_inputs.h"

namespace etfe {

namespace {

enum class PatchMode { Uniaxial, Biaxial, PureShear, Shear };
const char *const kModes[] = {"uniaxial", "biaxial", "pureshear", "shear"};

// Stretch in Y that makes Eyy = -Exx (pure shear in the principal axes).
double PureShearStretchY(double lx) { return std::sqrt(std::max(0.0, 2.0 - lx * lx)); }

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
  int k = 0;
  while (k < 4 && std::string(mode) != kModes[k]) ++k;
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

// What the patch options give, as the general scene's inputs: the film held in its plane (all:
// z), then per mode the edges' supports, each a coefficient (ex lx, ...) times the stretch
// multipliers, as this scene always built them.
PetscErrorCode PatchPreset(MPI_Comm, StructureInputs *in, void *vctx) {
  const auto *p = (const PatchInputs *)vctx;
  PetscFunctionBeginUser;
  auto bc = [&](const char *group) -> BcInput & {
    in->bcs.push_back(BcInput());
    in->bcs.back().group = group;
    return in->bcs.back();
  };
  bc("all").fix = "z";
  if (p->mode == PatchMode::Shear) {
    // Shear panel (pretension ex in X and Y plus the shear g): F = [[1 + ex, g], [0, 1 + ex]] on
    // every edge node, so the whole panel takes it.
    for (const char *edge : {"left", "right", "bottom", "top"}) {
      BcInput &b = bc(edge);
      b.gradient = {p->ex, p->shear, 0.0, p->ex};
      b.gradient_stages = {"-patch_schedule", p->schedule, 0.0};
    }
  } else {
    // Left and bottom edges on rollers, the right edge drawn in X, the top edge drawn in Y
    // (biaxial; pure shear with its own multipliers: Eyy = -Exx is not linear in the schedule,
    // so each stage end gets its own value, interpolated in between) or free (uniaxial).
    bc("left").fix = "x";
    bc("bottom").fix = "y";
    bc("right").move[0] = {"-patch_strain_x", p->schedule, p->ex * p->lx};
    if (p->mode == PatchMode::Biaxial) bc("top").move[1] = {"-patch_strain_y", p->schedule, p->ey * p->ly};
    if (p->mode == PatchMode::PureShear) {
      std::vector<double> sy;
      for (double f : p->schedule) sy.push_back(PureShearStretchY(1.0 + p->ex * f) - 1.0);
      bc("top").move[1] = {"-patch_mode pureshear", sy, p->ly};
    }
  }
  CheckInput &ck = in->check;
  ck.name = "patch", ck.ex = p->ex, ck.ey = p->ey, ck.factor = p->schedule.back(), ck.given = true;
  ck.mode = kModes[(int)p->mode];
  PetscFunctionReturn(0);
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
  PetscBool help = PETSC_FALSE;
  PetscCall(PetscOptionsHasHelp(nullptr, &help));
  if (help && scene->name.empty()) PetscFunctionReturn(0);  // -help without a scene: the options are shown
  PetscCall(StructureBuild(comm, scene, observer, true, PatchPreset, &in));
  PetscFunctionReturn(0);
}

} // namespace etfe
