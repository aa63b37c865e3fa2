// The general scene's options (structure_inputs.h): scene-wide ones (-structure_*) and those keyed
// by the mesh's group names (-bc_<group>_*, -film_<group>_*), by rigid support (-rigid_<name>_*)
// and by report region (-region_<name>_box). The group names live in the mesh, which only rank 0
// holds: they are sent to every rank first, so every rank reads the same options (-help lists
// them per group). An option keyed by a name the mesh does not have is an error naming it and
// the names there are, before anything is computed.
#include <petscsys.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <set>
#include <string>
#include <vector>

#include "etfe/assembly/input_plausibility.h"
#include "etfe/material/material.h"
#include "real_array_option.h"
#include "structure_inputs.h"

namespace etfe {

namespace {


// A comma-separated list of names.
PetscErrorCode OptionsNameList(PetscOptionItems *PetscOptionsObject, const char *name, const char *help,
                               std::vector<std::string> *list) {
  char buf[PETSC_MAX_PATH_LEN] = "";
  PetscBool set = PETSC_FALSE;
  PetscFunctionBeginUser;
  std::string shown;
  for (const std::string &s : *list) shown += (shown.empty() ? "" : ",") + s;
  PetscCall(PetscStrncpy(buf, shown.c_str(), sizeof buf));
  PetscCall(PetscOptionsString(name, help, "", shown.c_str(), buf, sizeof buf, &set));
  if (!set) PetscFunctionReturn(0);
  list->clear();
  for (char *tok = std::strtok(buf, ","); tok; tok = std::strtok(nullptr, ","))
    if (*tok) list->push_back(tok);
  PetscFunctionReturn(0);
}

PetscErrorCode ReadStageArray(PetscOptionItems *PetscOptionsObject, const std::string &prefix, const char *key,
                              const char *help, StageArray *a) {
  PetscFunctionBeginUser;
  a->option = "-" + prefix + key;
  // OptionsRealArray refuses values that are not finite, by the option's name.
  PetscCall(OptionsRealArray(PetscOptionsObject, (std::string("-") + key).c_str(), help, &a->values, nullptr));
  PetscFunctionReturn(0);
}

// kPa per plan area: above it a snow load is one in Pa (0.75 kPa typed as 750).
constexpr double kSnowMax = 20.0;

PetscErrorCode ReadBc(MPI_Comm comm, const std::string &group, BcInput *bc) {
  const std::string prefix = "bc_" + group + "_";
  char fix[16] = "";
  static const char *const comp[3] = {"ux", "uy", "uz"};
  PetscFunctionBeginUser;
  bc->group = group;
  PetscOptionsBegin(comm, prefix.c_str(), ("Support of node group " + group).c_str(), "Scene");
  PetscCall(PetscOptionsString("-fix", "Components held where they are: any of x, y, z (xyz: clamped)", "", fix, fix,
                               sizeof fix, nullptr));
  PetscCall(OptionsRealArray(PetscOptionsObject, "-points",
                             "Control points x,y,z,... [mm]: the -ux/-uy/-uz values are given at each point (point "
                             "after point, each with one value per stage) and interpolated along the polyline "
                             "through them",
                             &bc->points, nullptr));
  {
    const char *modes[] = {"projection", "axis"};
    PetscInt k = 0;
    PetscCall(PetscOptionsEList("-points_interpolation",
                                "How a node takes the control points' values: projection (its nearest point on the "
                                "polyline, in 3D) or axis (segments parallel to the x or y axis in plan; a node on "
                                "the first segment it lies on, in the points' order, at its coordinate along that "
                                "axis, (X - lo)/(hi - lo) from the segment's lower end: a frame drawn edge by edge, as "
                                "the saddle scene draws it)",
                                "", modes, 2, modes[0], &k, nullptr));
    bc->interpolation = modes[k];
  }
  for (int c = 0; c < 3; ++c)
    PetscCall(ReadStageArray(PetscOptionsObject, prefix, comp[c],
                             "Prescribed displacement [mm] at the end of each stage (cumulative)", &bc->move[c]));
  PetscCall(OptionsRealArray(PetscOptionsObject, "-gradient",
                             "In-plane displacement gradient du_x/dX,du_x/dY,du_y/dX,du_y/dY: the group's x and y "
                             "displacements are u = G X (a homogeneous stretch or shear of a panel), times "
                             "-gradient_stages",
                             &bc->gradient, nullptr));
  PetscCall(ReadStageArray(PetscOptionsObject, prefix, "gradient_stages",
                           "Multiplier of -gradient at the end of each stage (default 1 in one stage)",
                           &bc->gradient_stages));
  PetscCall(OptionsRealFinite(PetscOptionsObject, "-rotation",
                              "Turn the group rigidly about the z axis through the origin by this angle [rad] (a hub; "
                              "of its position stretched by -gradient), times -rotation_stages",
                              "rad", &bc->rotation, nullptr));
  PetscCall(ReadStageArray(PetscOptionsObject, prefix, "rotation_stages",
                           "Multiplier of -rotation at the end of each stage (default 1 in one stage)",
                           &bc->rotation_stages));
  PetscCall(ReadStageArray(PetscOptionsObject, prefix, "force",
                           "Total force on the group fx,fy,fz [N] at the end of each stage (3 values a stage), "
                           "shared by the nodes in proportion to their length along the group",
                           &bc->force));
  PetscOptionsEnd();
  bc->fix = fix;
  for (char ch : bc->fix)
    PetscCheck(ch == 'x' || ch == 'y' || ch == 'z', comm, PETSC_ERR_ARG_WRONG,
               "-%sfix %s: give the held components as letters x, y, z (e.g. xyz clamps, z holds the height)",
               prefix.c_str(), fix);
  PetscCheck(bc->points.size() % 3 == 0 && bc->points.size() != 3, comm, PETSC_ERR_ARG_SIZ,
             "-%spoints: give two or more control points, 3 coordinates each (%zu values given)", prefix.c_str(),
             bc->points.size());
  // Two equal consecutive points make a segment of no length: the nodes there would take the
  // first point's values, not the ones interpolated between its neighbours.
  for (size_t k = 3; k < bc->points.size(); k += 3) {
    const double *a = &bc->points[k - 3], *b = &bc->points[k];
    const double scale = std::max({1.0, std::fabs(a[0]), std::fabs(a[1]), std::fabs(a[2])});
    PetscCheck(std::hypot(b[0] - a[0], b[1] - a[1], b[2] - a[2]) > 1e-9 * scale, comm, PETSC_ERR_ARG_WRONG,
               "-%spoints: control points %zu and %zu are the same point (%s, %s, %s): give each point once (a "
               "closed loop repeats only its first point, as its last)",
               prefix.c_str(), k / 3, k / 3 + 1, OptionNum(b[0]).c_str(), OptionNum(b[1]).c_str(),
               OptionNum(b[2]).c_str());
  }
  PetscCheck(bc->interpolation == "projection" || !bc->points.empty(), comm, PETSC_ERR_ARG_WRONG,
             "-%spoints_interpolation %s: give the control points it interpolates between (-%spoints)",
             prefix.c_str(), bc->interpolation.c_str(), prefix.c_str());
  // Axis: each segment runs along x or along y in plan (its other plan coordinate the same at
  // both ends), else the fraction along "its" axis would not say where a node is on it.
  for (size_t k = 3; bc->interpolation == "axis" && k < bc->points.size(); k += 3) {
    const double *a = &bc->points[k - 3], *b = &bc->points[k];
    const double scale = std::max({1.0, std::fabs(a[0]), std::fabs(a[1]), std::fabs(b[0]), std::fabs(b[1])});
    PetscCheck(std::fabs(b[0] - a[0]) <= 1e-9 * scale || std::fabs(b[1] - a[1]) <= 1e-9 * scale, comm,
               PETSC_ERR_ARG_WRONG,
               "-%spoints_interpolation axis: control points %zu (%s, %s) and %zu (%s, %s) make a segment parallel to "
               "neither the x nor the y axis in plan; use -%spoints_interpolation projection, or add a point at the "
               "corner",
               prefix.c_str(), k / 3, OptionNum(a[0]).c_str(), OptionNum(a[1]).c_str(), k / 3 + 1,
               OptionNum(b[0]).c_str(), OptionNum(b[1]).c_str(), prefix.c_str());
    // A vertical segment has no length in plan to take a fraction of.
    PetscCheck(std::hypot(b[0] - a[0], b[1] - a[1]) > 1e-9 * scale, comm, PETSC_ERR_ARG_WRONG,
               "-%spoints_interpolation axis: control points %zu and %zu are at one place in plan (%s, %s): a segment "
               "of the drawn line needs a length in plan; use -%spoints_interpolation projection",
               prefix.c_str(), k / 3, k / 3 + 1, OptionNum(a[0]).c_str(), OptionNum(a[1]).c_str(), prefix.c_str());
  }
  PetscCheck(bc->gradient.empty() || bc->gradient.size() == 4, comm, PETSC_ERR_ARG_SIZ,
             "-%sgradient: give the four components du_x/dX,du_x/dY,du_y/dX,du_y/dY (%zu values given)",
             prefix.c_str(), bc->gradient.size());
  PetscCheck(bc->gradient.empty() || (bc->fix.find('x') == std::string::npos && bc->fix.find('y') == std::string::npos &&
                                      bc->points.empty()),
             comm, PETSC_ERR_ARG_WRONG,
             "-%sgradient prescribes the group's x and y displacements: give no -%sfix x or y and no -%spoints with it",
             prefix.c_str(), prefix.c_str(), prefix.c_str());
  if (!bc->gradient.empty() && !bc->gradient_stages.Given()) bc->gradient_stages.values = {1.0};
  if (bc->rotation != 0.0 && !bc->rotation_stages.Given()) bc->rotation_stages.values = {1.0};
  PetscCheck(bc->rotation == 0.0 || (bc->fix.find('x') == std::string::npos && bc->fix.find('y') == std::string::npos &&
                                     bc->points.empty()),
             comm, PETSC_ERR_ARG_WRONG,
             "-%srotation turns the group's x and y displacements: give no -%sfix x or y and no -%spoints with it",
             prefix.c_str(), prefix.c_str(), prefix.c_str());
  PetscCheck(bc->force.values.size() % 3 == 0, comm, PETSC_ERR_ARG_SIZ,
             "-%sforce: give fx,fy,fz for each stage (%zu values given)", prefix.c_str(), bc->force.values.size());
  PetscFunctionReturn(0);
}

PetscErrorCode ReadFilm(MPI_Comm comm, const std::string &group, FilmInput *f) {
  const std::string prefix = "film_" + group + "_";
  PetscBool set = PETSC_FALSE, h_set = PETSC_FALSE, ratio_set = PETSC_FALSE;
  char md[256] = "";
  PetscFunctionBeginUser;
  f->group = group;
  PetscOptionsBegin(comm, prefix.c_str(), ("Film surface group " + group).c_str(), "Scene");
  PetscCall(OptionsRealFinite(PetscOptionsObject, "-thickness",
                              "Film thickness of this group [mm] (default -membrane_thickness)", "mm", &f->thickness,
                              &h_set, "-membrane_thickness"));
  PetscCall(PetscOptionsString("-md",
                               "MD (roll) direction of this group: x,y,z, or strip (its long axis, as the strips "
                               "of the cutting patterns run)",
                               "", md, md, sizeof md, nullptr));
  PetscCall(OptionsRealFinite(PetscOptionsObject, "-stress_ratio",
                              "Form finding: MD:TD prestress ratio of this group (default -formfind_ratio)", "",
                              &f->stress_ratio, &ratio_set));
  PetscCall(ReadStageArray(PetscOptionsObject, prefix, "pressure",
                           "Follower pressure [kPa] at the end of each stage, along the elements' normal (the side "
                           "the triangles' orientation points to)",
                           &f->pressure));
  PetscCall(OptionsRealFinite(PetscOptionsObject, "-wind_cp",
                              "Wind pressure coefficient on the face the normal points to (> 0 pushes onto it, < 0 "
                              "suction); times -structure_wind",
                              "", &f->wind_cp, &set));
  PetscCall(ReadStageArray(PetscOptionsObject, prefix, "snow",
                           "Snow [kPa per plan area] at the end of each stage: a vertical dead load", &f->snow));
  {
    // Listed here for -help; the law itself is made with the film's (MaterialOptionsGiven below).
    char law[64] = "";
    PetscCall(PetscOptionsString("-material_type",
                                 "A law of this group's own (elastic, plastic, viscoelastic_plastic; default the "
                                 "film's -material_type): every -material_* option given as -film_<group>_material_* is "
                                 "this group's, the others the film's",
                                 "", law, law, sizeof law, nullptr));
  }
  PetscOptionsEnd();
  f->wind_given = set;
  f->stress_ratio_given = ratio_set;
  // Given, the thickness is this group's, with -membrane_thickness's checks; an explicit 0 is no
  // thickness (not "the default", which is what leaving the option out gives).
  if (h_set) {
    PetscCheck(f->thickness > 0, comm, PETSC_ERR_ARG_OUTOFRANGE,
               "-%sthickness %s must be positive (mm): give the group's thickness, or leave the option out for "
               "-membrane_thickness",
               prefix.c_str(), OptionNum(f->thickness).c_str());
    PetscCall(ReportPlausibility(comm, CheckThickness(f->thickness, ("-" + prefix + "thickness").c_str())));
  }
  // Snow presses down on the plan, in kPa: a negative value would lift the film, and a value no
  // roof carries is a load in Pa (a warning here would only be followed by a failed increment).
  for (double x : f->snow.values) {
    PetscCheck(x >= 0, comm, PETSC_ERR_ARG_OUTOFRANGE,
               "%s %s: snow is a downward load in kPa per plan area and cannot be negative; for an upward load give "
               "-%swind_cp (suction) or -%spressure",
               f->snow.option.c_str(), OptionNum(x).c_str(), prefix.c_str(), prefix.c_str());
    PetscCheck(x <= kSnowMax, comm, PETSC_ERR_ARG_OUTOFRANGE,
               "%s %s: snow is in kPa per plan area and the heaviest roof snow loads are about 10 kPa (above %s kPa "
               "no foil roof carries it). Did you mean %s (the value in Pa)?",
               f->snow.option.c_str(), OptionNum(x).c_str(), OptionNum(kSnowMax).c_str(), OptionNum(1e-3 * x).c_str());
  }
  if (std::strcmp(md, "strip") == 0) {
    f->md_strip = true;
  } else if (md[0]) {
    for (char *tok = std::strtok(md, ","); tok; tok = std::strtok(nullptr, ",")) {
      char *end = nullptr;
      f->md.push_back(std::strtod(tok, &end));
      PetscCheck(end != tok && *end == '\0' && std::isfinite(f->md.back()), comm, PETSC_ERR_ARG_WRONG,
                 "-%smd: \"%s\" is not a finite number; give a non-zero direction x,y,z or the word strip",
                 prefix.c_str(), tok);
    }
    PetscCheck(f->md.size() == 3 && std::hypot(f->md[0], f->md[1], f->md[2]) > 0, comm, PETSC_ERR_ARG_WRONG,
               "-%smd: give a non-zero direction x,y,z or the word strip", prefix.c_str());
  }
  PetscCheck(f->stress_ratio > 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "-%sstress_ratio %g must be positive",
             prefix.c_str(), f->stress_ratio);
  // Its own law: read and checked with the film's when the problem is made (case_setup.cpp).
  PetscBool own = PETSC_FALSE;
  PetscCall(MaterialOptionsGiven(comm, prefix.c_str(), &own));
  f->own_material = own;
  PetscFunctionReturn(0);
}

PetscErrorCode ReadRigid(MPI_Comm comm, const std::string &name, RigidInput *r) {
  const std::string prefix = "rigid_" + name + "_";
  const char *types[] = {"cylinder", "arch", "curve", "plane"};
  PetscInt type = 0;
  char curve[256] = "";
  std::vector<double> centre, axis = {0, 1, 0};
  PetscBool fixed = PETSC_FALSE;
  PetscFunctionBeginUser;
  r->name = name;
  PetscOptionsBegin(comm, prefix.c_str(), ("Rigid support " + name).c_str(), "Scene");
  PetscCall(PetscOptionsEList("-type",
                              "cylinder (a pipe), arch (a cylinder the film touches along its crown line), curve "
                              "(the circle through a node group of the mesh, fitted) or plane (through -centre, "
                              "outward normal -axis)",
                              "", types, 4, types[0], &type, nullptr));
  PetscCall(OptionsRealArray(PetscOptionsObject, "-centre", "A point on the axis x,y,z [mm]", &centre, nullptr));
  PetscCall(OptionsRealArray(PetscOptionsObject, "-axis", "Axis direction x,y,z", &axis, nullptr));
  PetscCall(OptionsRealFinite(PetscOptionsObject, "-radius", "Radius [mm]", "mm", &r->radius, nullptr));
  PetscCall(PetscOptionsString("-curve", "type curve: the node group (a circular arc) whose circle is the support", "",
                               curve, curve, sizeof curve, nullptr));
  PetscCall(OptionsNameList(PetscOptionsObject, "-nodes",
                            "Node groups that may touch it (default: every node within -contact_search_tol)",
                            &r->nodes));
  PetscCall(PetscOptionsBool("-fixed_nodes",
                             "Also pair nodes whose three displacements are prescribed (a grip on the support; "
                             "their contact force then adds to the reaction)",
                             "", fixed, &fixed, nullptr));
  PetscOptionsEnd();
  r->fixed_nodes = fixed;
  r->type = types[type];
  r->curve = curve;
  if (r->type == "curve") {
    PetscCheck(!r->curve.empty(), comm, PETSC_ERR_ARG_WRONG,
               "-%stype curve needs -%scurve <node group>: the arc of the mesh the support's circle is fitted to",
               prefix.c_str(), prefix.c_str());
    if (r->nodes.empty()) r->nodes.push_back(r->curve);
    PetscFunctionReturn(0);
  }
  PetscCheck(centre.size() == 3 && axis.size() == 3 && (r->radius > 0 || r->type == "plane"), comm, PETSC_ERR_ARG_WRONG,
             "rigid support %s: give -%scentre x,y,z, -%saxis x,y,z and -%sradius > 0 (a plane: its point and outward "
             "normal; or -%stype curve)",
             name.c_str(), prefix.c_str(), prefix.c_str(), prefix.c_str(), prefix.c_str());
  for (int i = 0; i < 3; ++i) r->centre[i] = centre[i], r->axis[i] = axis[i];
  PetscCheck(std::hypot(axis[0], axis[1], axis[2]) > 0, comm, PETSC_ERR_ARG_WRONG, "-%saxis must not be zero",
             prefix.c_str());
  PetscFunctionReturn(0);
}

PetscErrorCode ReadChamber(MPI_Comm comm, const std::string &name, ChamberInput *c) {
  const std::string prefix = "chamber_" + name + "_";
  PetscFunctionBeginUser;
  c->name = name;
  PetscOptionsBegin(comm, prefix.c_str(), ("Gas chamber " + name).c_str(), "Scene");
  PetscCall(OptionsNameList(PetscOptionsObject, "-groups", "Surface groups that bound it", &c->groups));
  PetscCall(OptionsRealArray(PetscOptionsObject, "-signs",
                             "Per group +1 where its normals point out of the chamber, -1 where they point in "
                             "(default +1)",
                             &c->signs, nullptr));
  PetscCall(OptionsRealArray(PetscOptionsObject, "-origin",
                             "A point on the planes that close it, if any (symmetry planes, a rigid base) [mm]",
                             &c->origin, nullptr));
  PetscCall(ReadStageArray(PetscOptionsObject, prefix, "pressure",
                           "Supplied gauge pressure [kPa] at the end of each stage (while not sealed)", &c->pressure));
  PetscCall(PetscOptionsInt("-sealed_from_stage",
                            "Sealed from the start of this stage on (1: from the start; 0: supplied throughout): "
                            "p V^kappa keeps the value it has then",
                            "", c->sealed_from_stage, &c->sealed_from_stage, nullptr));
  PetscCall(OptionsRealArray(PetscOptionsObject, "-sealed",
                             "Per stage 1 sealed, 0 supplied (e.g. 0,1,0: a power cut in stage 2; the supply "
                             "takes over again from the sealed pressure over stage 3); instead of -sealed_from_stage",
                             &c->sealed, nullptr));
  PetscCall(OptionsRealFinite(PetscOptionsObject, "-kappa",
                              "Gas law exponent when sealed (1 isothermal, 1.4 adiabatic air)", "", &c->kappa, nullptr));
  PetscCall(OptionsRealFinite(PetscOptionsObject, "-extra_volume",
                              "Volume beyond the membranes (ducts, a reservoir) [m^3]", "m^3", &c->extra_volume,
                              nullptr));
  PetscOptionsEnd();
  PetscCheck(!c->groups.empty(), comm, PETSC_ERR_ARG_WRONG,
             "chamber %s: give the surface groups that bound it (-%sgroups top,bottom)", name.c_str(), prefix.c_str());
  // A group listed twice would be met as two triangles on every one of its edges, facing the same way.
  for (size_t g = 0; g < c->groups.size(); ++g)
    for (size_t h = 0; h < g; ++h)
      PetscCheck(c->groups[g] != c->groups[h], comm, PETSC_ERR_ARG_WRONG,
                 "-%sgroups: group %s is listed twice (entries %zu and %zu): list each surface that bounds the "
                 "chamber once",
                 prefix.c_str(), c->groups[g].c_str(), h + 1, g + 1);
  PetscCheck(c->kappa >= 1.0 && c->kappa <= 5.0 / 3.0, comm, PETSC_ERR_ARG_OUTOFRANGE,
             "-%skappa %s: the exponent of the sealed gas law p V^kappa = const lies between 1 (isothermal) and the "
             "ratio of specific heats (adiabatic: 1.4 for air, 5/3 at most for any gas)",
             prefix.c_str(), OptionNum(c->kappa).c_str());
  if (c->signs.empty()) c->signs.assign(c->groups.size(), 1.0);
  PetscCheck(c->signs.size() == c->groups.size(), comm, PETSC_ERR_ARG_SIZ,
             "-%ssigns: one sign per group of -%sgroups (%zu for %zu)", prefix.c_str(), prefix.c_str(), c->signs.size(),
             c->groups.size());
  for (double s : c->signs)
    PetscCheck(s == 1.0 || s == -1.0, comm, PETSC_ERR_ARG_WRONG, "-%ssigns: each sign is 1 or -1", prefix.c_str());
  PetscCheck(c->sealed.empty() || c->sealed_from_stage == 0, comm, PETSC_ERR_ARG_WRONG,
             "chamber %s: give -%ssealed (per stage) or -%ssealed_from_stage, not both", name.c_str(), prefix.c_str(),
             prefix.c_str());
  for (double s : c->sealed)
    PetscCheck(s == 0.0 || s == 1.0, comm, PETSC_ERR_ARG_WRONG, "-%ssealed: one flag per stage, 1 sealed or 0 supplied",
               prefix.c_str());
  PetscCheck(c->origin.size() == 3, comm, PETSC_ERR_ARG_SIZ, "-%sorigin: give x,y,z", prefix.c_str());
  PetscCheck(c->kappa > 0 && c->extra_volume >= 0 && c->sealed_from_stage >= 0, comm, PETSC_ERR_ARG_OUTOFRANGE,
             "chamber %s: -%skappa must be positive, -%sextra_volume and -%ssealed_from_stage not negative",
             name.c_str(), prefix.c_str(), prefix.c_str(), prefix.c_str());
  PetscFunctionReturn(0);
}

PetscErrorCode ReadRegion(MPI_Comm comm, const std::string &name, RegionInput *r) {
  const std::string prefix = "region_" + name + "_";
  PetscFunctionBeginUser;
  r->name = name;
  PetscOptionsBegin(comm, prefix.c_str(), ("Report region " + name).c_str(), "Scene");
  PetscCall(OptionsRealArray(PetscOptionsObject, "-box",
                             "Plan box x0,y0,x1,y1 [mm]: the elements whose centroid lies in it", &r->box, nullptr));
  PetscOptionsEnd();
  PetscCheck(r->box.size() == 4 && r->box[0] <= r->box[2] && r->box[1] <= r->box[3], comm, PETSC_ERR_ARG_WRONG,
             "-%sbox: give x0,y0,x1,y1 with x0 <= x1 and y0 <= y1", prefix.c_str());
  PetscFunctionReturn(0);
}

// Options keyed by a group, support or region that does not exist: stated before the run, with
// the names there are (the app's own check would only call them unknown).
PetscErrorCode CheckKeyedOptions(MPI_Comm comm, const StructureInputs &in) {
  PetscInt n;
  char **names, **values;
  PetscFunctionBeginUser;
  PetscCall(PetscOptionsLeftGet(nullptr, &n, &names, &values));
  std::string bad;
  // A surface group's own law is read when the problem is made: its -film_<group>_material_*
  // options are not left over yet (a misspelt one is refused after, with the unused options).
  auto later = [&in](const char *name) {
    for (const FilmInput &f : in.films)
      if (f.own_material && std::strncmp(name, ("film_" + f.group + "_material_").c_str(), f.group.size() + 15) == 0)
        return true;
    return false;
  };
  for (PetscInt i = 0; i < n && bad.empty(); ++i)
    for (const char *p : {"bc_", "film_", "rigid_", "region_", "chamber_"})
      // -chamber_rank_one belongs to the chambers' component, read when the problem is made.
      if (std::strncmp(names[i], p, std::strlen(p)) == 0 && std::strcmp(names[i], "chamber_rank_one") != 0 &&
          !later(names[i]))
        bad = names[i];
  PetscCall(PetscOptionsLeftRestore(nullptr, &n, &names, &values));
  if (bad.empty()) PetscFunctionReturn(0);
  auto join = [](const std::vector<std::string> &v) {
    std::string s;
    for (const std::string &x : v) s += (s.empty() ? "" : ", ") + x;
    return s.empty() ? std::string("none") : s;
  };
  std::vector<std::string> rigid, region;
  for (const RigidInput &r : in.rigids) rigid.push_back(r.name);
  for (const RegionInput &r : in.regions) region.push_back(r.name);
  SETERRQ(comm, PETSC_ERR_ARG_WRONG,
          "-%s: no such group, support or option. -bc_<group>_* takes a node group of the mesh (%s), -film_<group>_* "
          "a surface group (%s), -rigid_<name>_* a name listed in -structure_rigid (%s), -region_<name>_box one in "
          "-structure_regions (%s), -chamber_<name>_* one in -structure_chambers; -help lists each one's options",
          bad.c_str(), join(in.node_groups).c_str(), join(in.element_groups).c_str(), join(rigid).c_str(),
          join(region).c_str());
}

PetscErrorCode ReadSceneWide(MPI_Comm comm, bool form_finding, StructureInputs *in, std::vector<std::string> *rigid,
                             std::vector<std::string> *regions, std::vector<std::string> *chambers) {
  const char *references[] = {"mesh", "pattern"};
  char history[PETSC_MAX_PATH_LEN] = "";
  std::vector<double> md = {1, 0, 0};
  PetscFunctionBeginUser;
  PetscOptionsBegin(comm, nullptr, "General scene: a structure from a mesh file and its groups", "Scene");
  PetscCall(PetscOptionsInt("-structure_stages", "Number of load stages (default: the longest per-stage option)", "",
                            in->stages, &in->stages, nullptr));
  PetscCall(OptionsRealArray(PetscOptionsObject, "-structure_md", "MD (roll) direction of the film x,y,z", &md, nullptr));
  PetscCall(PetscOptionsEList("-structure_reference",
                              "Stress-free state: mesh (the surface as meshed or form-found) or pattern (the flat "
                              "cutting patterns of -structure_pattern_strips, laid on in the first stage)",
                              "", references, 2, references[in->reference], &in->reference, nullptr));
  PetscCall(OptionsNameList(PetscOptionsObject, "-structure_pattern_strips",
                            "Surface groups cut as one strip each (-structure_reference pattern)", &in->pattern_strips));
  PetscCall(PetscOptionsBool("-structure_pattern_lay_on",
                             "Blend the reference from the mesh to the patterns over the first stage (where the "
                             "patterns fit the supports only with compression); false: the patterns are the reference "
                             "from the start and the mesh's shape is the first guess (a cushion's lens, stretched)",
                             "", in->pattern_lay_on, &in->pattern_lay_on, nullptr));
  PetscCall(OptionsRealFinite(PetscOptionsObject, "-structure_initial_bulge",
                              "Initial guess: lift the free film by up to this much [mm] along its normal (a flat "
                              "film under pressure has no out-of-plane stiffness to start from)",
                              "mm", &in->initial_bulge, nullptr));
  PetscCall(OptionsRealFinite(PetscOptionsObject, "-structure_initial_bulge_radius",
                              "Initial guess: instead of along the normal, a paraboloid h (1 - r^2/R^2) in z over this "
                              "radius R [mm] about -structure_initial_bulge_centre (a clamped disc's own shape)",
                              "mm", &in->bulge_radius, nullptr));
  PetscCall(OptionsRealArray(PetscOptionsObject, "-structure_initial_bulge_centre",
                             "Plan centre x,y of the paraboloid initial guess [mm]", &in->bulge_centre, nullptr));
  {
    const char *checks[] = {"none", "hencky", "patch", "annulus", "strip", "capstan", "catenoid", "saddle_stretch"};
    PetscInt k = 0;
    PetscCall(PetscOptionsEList("-structure_check",
                                "Closed-form check printed after the report: hencky (a clamped disc under pressure: "
                                "centre deflection and stress against Hencky's solution) or patch (a rectangle "
                                "stretched in its plane: every element's stress, against Hooke's law) or annulus (a "
                                "pretensioned annulus whose hub, node group hub, is turned: wrinkled zone and torque "
                                "against the tension-field closed form); strip: a lab strip's relaxation or creep, its "
                                "strain and stress per increment to <results>_strip.csv; capstan: a strip pulled over "
                                "a pipe to gross slip (T2 on end B, node group right, and mu_eff = ln(T2/T1)/theta); "
                                "catenoid: form finding between two rings, the neck radius against c cosh(z/c); "
                                "saddle_stretch: the thesis's drawn saddle (arch support arch, node group sym_x), the "
                                "saddle scene's report and history CSV instead of the structure's (parts A and B, "
                                "elements I and II, slides I-V, Mises distribution, heights h1 and h2)",
                                "", checks, 8, checks[0], &k, nullptr));
    if (k > 0) in->check.name = checks[k];
  }
  PetscCall(ReadStageArray(PetscOptionsObject, "", "structure_wind",
                           "Wind velocity pressure q [kPa] at the end of each stage (times -film_<group>_wind_cp)",
                           &in->wind));
  PetscCall(ReadStageArray(PetscOptionsObject, "", "structure_self_weight",
                           "Self-weight factor at the end of each stage (1: the film's weight)", &in->self_weight));
  PetscCall(OptionsRealFinite(PetscOptionsObject, "-structure_density",
                              "Film density [kg/m^3] for the self-weight (ETFE: 1750)", "kg/m^3", &in->density, nullptr));
  PetscCall(OptionsNameList(PetscOptionsObject, "-structure_rigid", "Rigid supports by name (-rigid_<name>_*)", rigid));
  PetscCall(OptionsNameList(PetscOptionsObject, "-structure_regions", "Report regions by name (-region_<name>_box)",
                            regions));
  PetscCall(OptionsNameList(PetscOptionsObject, "-structure_chambers", "Gas chambers by name (-chamber_<name>_*)",
                            chambers));
  PetscCall(OptionsRealFinite(PetscOptionsObject, "-structure_atmosphere",
                              "Atmospheric pressure [kPa, absolute] for the chambers' gas laws", "kPa", &in->atmosphere,
                              nullptr));
  PetscCall(OptionsNameList(PetscOptionsObject, "-structure_report",
                            "Surface groups and regions reported and written to the history (default: all)",
                            &in->report));
  PetscCall(OptionsRealArray(PetscOptionsObject, "-structure_probe_elements",
                             "Plan points x,y,...: the element nearest each; its smallest principal stress and strain "
                             "go to the history (wrinkling)",
                             &in->probe_elements, nullptr));
  PetscCall(OptionsRealArray(PetscOptionsObject, "-structure_probe_nodes",
                             "Plan points x,y,...: the node nearest each; its displacement (and slide on a rigid "
                             "support) go to the history",
                             &in->probe_nodes, nullptr));
  PetscCall(PetscOptionsString("-structure_history", "History CSV (default beside -output_file)", "", history, history,
                               sizeof history, nullptr));
  PetscOptionsEnd();
  in->history = history;
  PetscCheck(md.size() == 3 && std::hypot(md[0], md[1], md[2]) > 0, comm, PETSC_ERR_ARG_WRONG,
             "-structure_md: give a non-zero direction x,y,z");
  for (int i = 0; i < 3; ++i) in->md[i] = md[i];
  PetscCheck(in->probe_elements.size() % 2 == 0 && in->probe_nodes.size() % 2 == 0, comm, PETSC_ERR_ARG_SIZ,
             "-structure_probe_elements / -structure_probe_nodes: give plan points, 2 values (x,y) each");
  PetscCheck(in->bulge_radius >= 0 && in->bulge_centre.size() == 2, comm, PETSC_ERR_ARG_WRONG,
             "-structure_initial_bulge_radius must not be negative and -structure_initial_bulge_centre is x,y");
  PetscCheck(in->stages >= 0, comm, PETSC_ERR_ARG_OUTOFRANGE,
             "-structure_stages %d: give the number of load stages (1 or more), or 0 to take it from the longest "
             "per-stage option",
             (int)in->stages);
  PetscCheck(in->density > 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "-structure_density %g must be positive (kg/m^3)",
             in->density);
  PetscCall(ReportPlausibility(comm, CheckDensity(in->density)));
  PetscCall(ReportPlausibility(comm, CheckAtmosphere(in->atmosphere)));
  PetscCheck(!(form_finding && in->reference == 1), comm, PETSC_ERR_ARG_WRONG,
             "-structure_reference pattern: form finding finds the surface the patterns are cut from; run it without");
  PetscFunctionReturn(0);
}

} // namespace

PetscErrorCode StructureOptionsRead(MPI_Comm comm, const MeshData &mesh, bool form_finding, StructureInputs *in) {
  std::vector<std::string> rigid, regions, chambers;
  PetscFunctionBeginUser;
  for (const auto &kv : mesh.node_sets) in->node_groups.push_back(kv.first);
  for (const auto &kv : mesh.element_sets) in->element_groups.push_back(kv.first);
  PetscCall(BroadcastNames(comm, &in->node_groups));
  PetscCall(BroadcastNames(comm, &in->element_groups));
  PetscCall(ReadSceneWide(comm, form_finding, in, &rigid, &regions, &chambers));
  for (const std::string &g : in->node_groups) {
    BcInput bc;
    PetscCall(ReadBc(comm, g, &bc));
    const bool any = !bc.fix.empty() || bc.move[0].Given() || bc.move[1].Given() || bc.move[2].Given() ||
                     bc.force.Given() || !bc.points.empty() ||
                     !bc.gradient.empty() || bc.rotation != 0.0;
    if (any) in->bcs.push_back(bc);
  }
  for (const std::string &g : in->element_groups) {
    FilmInput f;
    PetscCall(ReadFilm(comm, g, &f));
    in->films.push_back(f);
  }
  const std::set<std::string> nodes(in->node_groups.begin(), in->node_groups.end());
  for (const std::string &name : rigid) {
    RigidInput r;
    PetscCall(ReadRigid(comm, name, &r));
    for (const std::string &g : r.nodes)
      PetscCheck(nodes.count(g), comm, PETSC_ERR_ARG_WRONG,
                 "-rigid_%s_nodes / -rigid_%s_curve: the mesh has no node group %s", name.c_str(), name.c_str(),
                 g.c_str());
    in->rigids.push_back(r);
  }
  for (const std::string &name : regions) {
    RegionInput r;
    PetscCall(ReadRegion(comm, name, &r));
    in->regions.push_back(r);
  }
  const std::set<std::string> surfaces(in->element_groups.begin(), in->element_groups.end());
  for (const std::string &name : chambers) {
    ChamberInput c;
    PetscCall(ReadChamber(comm, name, &c));
    for (const std::string &g : c.groups)
      PetscCheck(surfaces.count(g), comm, PETSC_ERR_ARG_WRONG, "-chamber_%s_groups: the mesh has no surface group %s",
                 name.c_str(), g.c_str());
    in->chambers.push_back(c);
  }
  PetscCheck(in->atmosphere > 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "-structure_atmosphere %g kPa must be positive",
             in->atmosphere);
  for (const std::string &g : in->pattern_strips)
    PetscCheck(surfaces.count(g), comm, PETSC_ERR_ARG_WRONG,
               "-structure_pattern_strips: the mesh has no surface group %s", g.c_str());
  for (const std::string &g : in->report) {
    bool found = surfaces.count(g) > 0;
    for (const std::string &r : regions) found |= r == g;
    PetscCheck(found, comm, PETSC_ERR_ARG_WRONG,
               "-structure_report: %s is neither a surface group of the mesh nor a region of -structure_regions",
               g.c_str());
  }
  PetscCall(StructureCablesRead(comm, mesh, form_finding, in));  // cables (structure_cables.cpp)
  PetscCall(CheckKeyedOptions(comm, *in));
  PetscFunctionReturn(0);
}

PetscErrorCode BroadcastNames(MPI_Comm comm, std::vector<std::string> *names) {
  std::string joined;
  PetscFunctionBeginUser;
  for (const std::string &n : *names) joined += n + '\n';
  unsigned long long len = joined.size();
  PetscCallMPI(MPI_Bcast(&len, 1, MPI_UNSIGNED_LONG_LONG, 0, comm));
  joined.resize(len);
  PetscCallMPI(MPI_Bcast(joined.data(), (int)len, MPI_CHAR, 0, comm));
  names->clear();
  for (size_t a = 0, b; a < joined.size(); a = b + 1) {
    b = joined.find('\n', a);
    names->push_back(joined.substr(a, b - a));
  }
  PetscFunctionReturn(0);
}

} // namespace etfe
