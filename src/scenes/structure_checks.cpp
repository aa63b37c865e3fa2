// The general scene's closed-form checks (-structure_check): which check a case asks for, and
// what it needs, taken from the case's own supports, loads and mesh (or exactly from the built-in
// scene that knows them: -scene hencky, patch, annulus, strip, capstan, catenoid, the saddle's form
// finding), so a verification case is an options file (options/structure/verify_*.opts). The
// reports themselves: structure_check_reports.cpp, structure_check_capstan.cpp.
#include <petscsys.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "etfe/base/rank0.h"
#include "etfe/scenes/scene_registry.h"
#include "structure_inputs.h"

namespace etfe {

namespace {

// Rank 0's largest plan distance from the origin of a node group, on every rank (0: no group).
PetscErrorCode GroupRadius(MPI_Comm comm, const MeshData &m, const char *group, double *r) {
  PetscFunctionBeginUser;
  *r = 0.0;
  if (SceneHoldsMesh(comm) && m.node_sets.count(group))
    for (int n : m.node_sets.at(group)) *r = std::max(*r, std::hypot(m.coords[3 * n], m.coords[3 * n + 1]));
  PetscCallMPI(MPI_Bcast(r, 1, MPI_DOUBLE, 0, comm));
  PetscFunctionReturn(0);
}

// Rank 0's plan extent of the mesh (x0, y0, x1, y1) and largest plan distance from the origin, on every rank.
PetscErrorCode PlanExtent(MPI_Comm comm, const MeshData &m, double box[5]) {
  PetscFunctionBeginUser;
  box[0] = box[1] = 1e300, box[2] = box[3] = -1e300, box[4] = 0.0;
  if (SceneHoldsMesh(comm))
    for (int n = 0; n < m.NumNodes(); ++n) {
      const double x = m.coords[3 * n], y = m.coords[3 * n + 1];
      box[0] = std::min(box[0], x), box[1] = std::min(box[1], y), box[2] = std::max(box[2], x);
      box[3] = std::max(box[3], y), box[4] = std::max(box[4], std::hypot(x, y));
    }
  PetscCallMPI(MPI_Bcast(box, 5, MPI_DOUBLE, 0, comm));
  PetscFunctionReturn(0);
}

// The last stage's value of a per-stage option, in the solver's unit (kPa options: scale 1e-3).
double LastValue(const StageArray &a, double unit) {
  return a.coef != 0.0 ? a.coef * a.values.back() : unit * a.values.back();
}

const BcInput *FindBc(const StructureInputs &in, const char *group) {
  for (const BcInput &bc : in.bcs)
    if (bc.group == group) return &bc;
  return nullptr;
}

} // namespace

PetscErrorCode StructureCheckResolve(MPI_Comm comm, const SceneSpec &scene, StructureInputs *in,
                                     StructureCheckFn *fn) {
  CheckInput &ck = in->check;
  double box[5];
  PetscFunctionBeginUser;
  *fn = StructureCheckFns();
  if (ck.name.empty()) PetscFunctionReturn(0);
  // Every check's closed form has one film law.
  PetscCheck(scene.material_prefixes.empty(), comm, PETSC_ERR_ARG_INCOMP,
             "-structure_check %s compares against a closed form for a film of one law; drop -%smaterial_* (a "
             "surface group's own law) or the check",
             ck.name.c_str(), scene.material_prefixes.front().c_str());
  if (ck.name == "hencky") {
    fn->report = HenckyCheck;
    if (ck.given) PetscFunctionReturn(0);
    // The disc's radius (the generator's, or the mesh's largest distance from the origin) and the
    // pressure of the one loaded surface group at the last stage.
    PetscCall(PlanExtent(comm, scene.mesh, box));
    ck.radius = in->generator.name == "disc" ? in->generator.radius : box[4];
    const FilmInput *loaded = nullptr;
    for (const FilmInput &f : in->films)
      if (f.pressure.Given()) {
        PetscCheck(!loaded, comm, PETSC_ERR_ARG_WRONG,
                   "-structure_check hencky: surface groups %s and %s are both under pressure; the closed form is for "
                   "one uniform pressure on the whole disc",
                   loaded->group.c_str(), f.group.c_str());
        loaded = &f;
      }
    PetscCheck(loaded, comm, PETSC_ERR_ARG_WRONG,
               "-structure_check hencky: no surface group is under pressure (-film_all_pressure <kPa>)");
    ck.pressure = LastValue(loaded->pressure, 1e-3);
    PetscFunctionReturn(0);
  }
  if (ck.name == "annulus") {
    fn->report = AnnulusCheck;
    if (ck.given) PetscFunctionReturn(0);
    // The radii (the generator's, or the hub's and outer edge's), the pretension strain of the
    // hub's isotropic stretch and its rotation at the last stage.
    const BcInput *hub = FindBc(*in, "hub");
    PetscCheck(hub && hub->rotation != 0.0 && hub->gradient.size() == 4 && hub->gradient[0] == hub->gradient[3] &&
                   hub->gradient[1] == 0.0 && hub->gradient[2] == 0.0,
               comm, PETSC_ERR_ARG_WRONG,
               "-structure_check annulus: the node group hub needs a pretension -bc_hub_gradient e,0,0,e and a turn "
               "-bc_hub_rotation <rad>");
    if (in->generator.name == "annulus") {
      ck.a = in->generator.radii[0], ck.b = in->generator.radii[1];
    } else {
      PetscCall(GroupRadius(comm, scene.mesh, "hub", &ck.a));
      PetscCall(GroupRadius(comm, scene.mesh, "outer", &ck.b));
    }
    ck.eps0 = hub->gradient[0], ck.phi = hub->rotation * hub->rotation_stages.values.back();
    PetscFunctionReturn(0);
  }
  if (ck.name == "strip") {
    fn->report = StripReport, fn->step = StripStep;
    if (ck.given) PetscFunctionReturn(0);
    // Relaxation when the right edge is drawn, creep when it is pulled by a force.
    const BcInput *right = FindBc(*in, "right");
    PetscCheck(right && (right->move[0].Given() || right->force.Given()), comm, PETSC_ERR_ARG_WRONG,
               "-structure_check strip: draw the right edge (-bc_right_ux, relaxation) or pull it (-bc_right_force, "
               "creep)");
    ck.test = right->move[0].Given() ? "relaxation" : "creep";
    PetscFunctionReturn(0);
  }
  if (ck.name == "capstan") {
    fn->report = CapstanCheckReport, fn->step = CapstanCheckStep, fn->state = CapstanCheckStart();
    if (ck.given) PetscFunctionReturn(0);
    // The wrap angle (the generator's), T1 = the size of end A's (node group left) force and the
    // direction end B (node group right) is pulled in, at the last stage.
    const BcInput *left = FindBc(*in, "left"), *right = FindBc(*in, "right");
    PetscCheck(in->generator.name == "capstan" && left && left->force.Given() && right, comm, PETSC_ERR_ARG_WRONG,
               "-structure_check capstan: needs -structure_mesh_generator capstan, a force on end A "
               "(-bc_left_force) and end B pulled (-bc_right_ux/uy/uz)");
    const std::vector<double> &f = left->force.values;
    ck.theta = in->generator.wrap_angle * M_PI / 180.0;
    ck.t1 = std::hypot(f[f.size() - 3], f[f.size() - 2], f[f.size() - 1]);
    double d[3], len = 0.0;
    for (int i = 0; i < 3; ++i) d[i] = right->move[i].Given() ? LastValue(right->move[i], 1.0) : 0.0, len += d[i] * d[i];
    len = std::sqrt(len);
    PetscCheck(len > 0, comm, PETSC_ERR_ARG_WRONG, "-structure_check capstan: end B (node group right) is not pulled");
    for (int i = 0; i < 3; ++i) ck.tB[i] = d[i] / len;
    PetscFunctionReturn(0);
  }
  if (ck.name == "catenoid") {
    fn->report = CatenoidCheck;
    if (ck.given) PetscFunctionReturn(0);
    PetscCheck(in->generator.name == "tube" && scene.form_finding, comm, PETSC_ERR_ARG_WRONG,
               "-structure_check catenoid: form finding (-analysis formfind) of a generated tube "
               "(-structure_mesh_generator tube) held at its rings");
    ck.ring_radius = in->generator.radius, ck.separation = in->generator.length;
    PetscFunctionReturn(0);
  }
  if (ck.name == "saddle") {
    fn->report = SaddleCheck;
    PetscCheck(ck.given, comm, PETSC_ERR_ARG_WRONG,
               "-structure_check saddle: the saddle's shape report is the saddle scene's (-scene saddle)");
    PetscFunctionReturn(0);
  }
  if (ck.name == "saddle_stretch") {
    fn->setup = SaddleStretchCheckSetup, fn->step = SaddleStretchCheckStep, fn->report = SaddleStretchCheckReport;
    fn->replaces_report = true;
    if (ck.given) PetscFunctionReturn(0);
    // The thesis's quarter saddle (saddle_geometry.h): its rise is the crown of the arch support,
    // its middle cutting line the node group sym_x; the probes are the thesis's.
    const RigidInput *arch = nullptr;
    for (const RigidInput &r : in->rigids)
      if (r.name == "arch") arch = &r;
    const bool sym_x = std::find(in->node_groups.begin(), in->node_groups.end(), "sym_x") != in->node_groups.end();
    PetscCheck(!scene.form_finding, comm, PETSC_ERR_ARG_WRONG,
               "-structure_check saddle_stretch reports a drawn film; form finding's shape report is the saddle "
               "scene's (-scene saddle -analysis formfind)");
    PetscCheck(arch && arch->type == "arch" && arch->radius > 0 && sym_x, comm, PETSC_ERR_ARG_WRONG,
               "-structure_check saddle_stretch: the saddle's report needs its arch as the rigid support arch "
               "(-structure_rigid arch -rigid_arch_type arch -rigid_arch_centre 1000,0,H-R -rigid_arch_radius R: its "
               "crown is the rise H) and the middle cutting line X = 0 as node group sym_x (%s)",
               sym_x ? "the arch is missing" : "no node group sym_x in the mesh");
    ck.rise = arch->centre[2] + arch->radius;
    ck.saddle = SaddleStretchProbesDefault(ck.rise, in->history);
    PetscFunctionReturn(0);
  }
  PetscCheck(ck.name == "patch", comm, PETSC_ERR_ARG_UNKNOWN_TYPE,
             "-structure_check %s: use hencky, patch, annulus, strip, capstan, catenoid or saddle_stretch",
             ck.name.c_str());
  fn->report = PatchCheck;
  if (ck.given) PetscFunctionReturn(0);
  // The strains from the supports: the right edge drawn in x (uniaxial, the top edge free in y;
  // biaxial with the top edge drawn in y), or a panel whose edges follow a displacement gradient.
  PetscCall(PlanExtent(comm, scene.mesh, box));
  const BcInput *right = FindBc(*in, "right"), *top = FindBc(*in, "top");
  bool shear = false;
  for (const BcInput &bc : in->bcs) shear |= !bc.gradient.empty();
  if (shear) {
    ck.mode = "shear";
    PetscFunctionReturn(0);
  }
  PetscCheck(right && right->move[0].Given(), comm, PETSC_ERR_ARG_WRONG,
             "-structure_check patch: the right edge is not drawn (-bc_right_ux <mm per stage>), or give the edges a "
             "-bc_<group>_gradient");
  ck.ex = LastValue(right->move[0], 1.0) / (box[2] - box[0]);
  ck.mode = "uniaxial";
  if (top && top->move[1].Given()) ck.mode = "biaxial", ck.ey = LastValue(top->move[1], 1.0) / (box[3] - box[1]);
  PetscFunctionReturn(0);
}

} // namespace etfe
