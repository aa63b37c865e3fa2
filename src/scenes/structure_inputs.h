// The general scene (-scene structure): a user's own structure from a mesh file whose physical
// groups name its parts, and options keyed by those names (docs/own-structure.md). This header
// holds what the options give (structure_options.cpp reads them), what the builder makes of them
// (structure.cpp, structure_supports.cpp, structure_loads.cpp) and what the observer reports
// (structure_report.cpp). Scenes layer, private.
#pragma once
#include <petscsys.h>

#include <memory>
#include <string>
#include <vector>

#include "etfe/assembly/problem.h"
#include "etfe/description/scene.h"

namespace etfe {

// A per-stage option: values at the end of each stage; an array shorter than the analysis holds
// its last value in the stages after it.
struct StageArray {
  std::string option;  // "-film_roof_pressure", for messages
  std::vector<double> values;
  // 0: the values are in the option's unit (kPa, mm). Non-zero (a built-in scene's own input,
  // StructureBuild below): the values are multipliers of this coefficient, in the solver's units
  // (MPa, mm), so the load is coef x schedule exactly as that scene always built it.
  double coef = 0.0;
  bool Given() const { return !values.empty(); }
};

// -bc_<group>_*: a node group held or moved. Components a prescribed displacement moves are
// given per stage (cumulative, mm); with -bc_<group>_points the values are given at each control
// point and interpolated along the polyline through them (an edge drawn by different amounts at
// its ends, as the saddle's frame at a, b, c, d).
struct BcInput {
  std::string group;
  std::string fix;              // held components, any of "xyz"
  std::vector<double> points;   // 3 per control point (empty: the values hold on every node)
  // How a node's values come from the control points (-bc_<group>_points_interpolation):
  // "projection": the nearest point of the polyline in 3D, its fraction along the segment;
  // "axis": segments parallel to the x or y axis in plan, the fraction of the node's coordinate
  // along that axis from the segment's lower end, (X - lo) / (hi - lo) (the saddle's frame, whose
  // drawing is interpolated as Y/W and X/A along each edge, to the bit).
  std::string interpolation = "projection";
  // A built-in scene's names of the control points (the saddle's draw_a..draw_d): each point's
  // schedule takes its name, a point's components with the same values share one schedule and
  // all-zero values make none (the values are the same to the bit; the stage line and the
  // checkpoints name the scene's schedules). Empty: <group>.<component>@<point>.
  std::vector<std::string> point_names;
  StageArray move[3];           // per component: stages, or points x stages (point-major)
  StageArray force;             // total force on the group, 3 per stage [N]
  // In-plane displacement gradient at multiplier 1 (du_x/dX, du_x/dY, du_y/dX, du_y/dY): the
  // group's x and y displacements follow u = G X (a homogeneous stretch or shear of a panel's
  // edges), times the per-stage multipliers of gradient_stages.
  std::vector<double> gradient;
  StageArray gradient_stages;
  // A rigid turn about the z axis through the origin by `rotation` [rad] at multiplier 1 (a hub),
  // of the group's position stretched by the gradient, times the multipliers of rotation_stages.
  double rotation = 0.0;
  StageArray rotation_stages;
};

// -film_<group>_*: a surface group's loads and form-finding ratio.
struct FilmInput {
  std::string group;
  double stress_ratio = 1.0;  // form finding: MD:TD
  bool stress_ratio_given = false;  // else the group takes -formfind_ratio
  double thickness = 0.0;     // mm (0: -membrane_thickness)
  std::vector<double> md;     // MD direction x,y,z (empty: -structure_md)
  bool md_strip = false;      // MD along the group's long axis
  // A law of its own (-film_<group>_material_*, each option over the film's -material_*): read
  // with the film's law when the problem is made (case_setup.cpp), not here.
  bool own_material = false;
  StageArray pressure;        // follower pressure along the elements' normal [kPa]
  std::string pressure_schedule;  // its schedule's name ("": <group>.pressure); a built-in scene's own
  double wind_cp = 0.0;       // pressure coefficient on the face the normal points to
  bool wind_given = false;
  StageArray snow;            // vertical load per plan area [kPa]
};

// -rigid_<name>_*: a rigid support the film can slide on (contact with friction, -contact_*).
struct RigidInput {
  std::string name;
  std::string type = "cylinder";  // cylinder, arch (a cylinder whose contact is its crown line), curve or plane
  double centre[3] = {0, 0, 0}, axis[3] = {0, 1, 0}, radius = 0.0;
  std::string curve;              // type curve: the node group whose circle is fitted
  std::vector<std::string> nodes; // candidate node groups (empty: every node)
  bool fixed_nodes = false;       // also pair nodes whose three DOFs are prescribed (a grip)
};

// -chamber_<name>_*: a gas chamber bounded by surface groups (signs -1 where their normals point
// into it), supplied with a gauge pressure per stage, sealed from a stage on.
struct ChamberInput {
  std::string name;
  std::vector<std::string> groups;
  std::vector<double> signs, origin = {0, 0, 0};
  StageArray pressure;         // supplied gauge pressure [kPa]
  PetscInt sealed_from_stage = 0;
  std::vector<double> sealed;  // per stage 1 sealed / 0 supplied (-chamber_<name>_sealed)
  double kappa = 1.0, extra_volume = 0.0;  // extra volume in m^3
};

// -region_<name>_box: the elements whose centroid lies in a plan box, reported as a group.
struct RegionInput {
  std::string name;
  std::vector<double> box;  // x0, y0, x1, y1
};

// -structure_mesh_generator: a generated mesh instead of -mesh_file (structure_mesh.cpp).
struct MeshGenInput {
  std::string name;                   // "" (a mesh file), disc, annulus or rectangle
  double radius = 500.0;              // disc [mm]
  std::vector<double> radii = {100.0, 500.0};  // annulus hub a, outer b [mm]
  // capstan: a strip (length along the wrap, -mesh_nx x -mesh_ny cells) laid on a cylinder of
  // axis y through the origin, symmetric about the z axis: radius, wrap angle [degrees], width [mm]
  double wrap_radius = 21.35, wrap_angle = 180.0, wrap_width = 50.0;
  double length = 1000.0;             // tube: its length along z (radius: `radius`), centred at z = 0
  std::vector<double> size = {1000.0, 500.0};  // rectangle lx, ly [mm]
};

struct SaddleStretchProbes;  // saddle_stretch.cpp

// -structure_check: a closed-form check printed after the report (structure_checks.cpp).
struct CheckInput {
  std::string name;          // "", hencky, patch, annulus, strip, capstan, catenoid or saddle
  // Filled by the check from the other inputs, or by a built-in scene that knows them exactly.
  double radius = 0.0, pressure = 0.0;      // hencky: a [mm], p [MPa] (0: from the mesh and the film's pressure)
  double ex = 0.0, ey = 0.0, factor = 1.0;  // patch: strains at multiplier 1, the last multiplier
  std::string mode;                         // patch: uniaxial, biaxial, pureshear, shear ("": from the supports)
  double a = 0.0, b = 0.0, eps0 = 0.0, phi = 0.0;  // annulus: radii, pretension strain, hub rotation
  std::string test, history;                // strip: relaxation or creep; its CSV ("": <results>_strip.csv)
  double theta = 0.0, t1 = 0.0, tB[3] = {0, 0, 0};  // capstan: wrap angle, end A's tension, end B's pull direction
  double ring_radius = 0.0, separation = 0.0;        // catenoid: the rings' radius and distance
  double rise = 0.0;                                  // saddle: the arch's rise H (saddle_geometry.h)
  // saddle_stretch: the stretch fabrication's probes and history (saddle_stretch.cpp), found at set-up.
  std::shared_ptr<SaddleStretchProbes> saddle;
  bool given = false;                       // the values above are set
};

// -cable_<group>_*: a cable along a 1-D group of the mesh (structure_cables.cpp).
struct CableInput {
  std::string group;
  double EA = 0.0, length = 0.0, prestress = 0.0;
  double force_density = 0.0;  // -cable_<group>_force_density: form finding, N/mm
  double sag = 0.0;            // -cable_<group>_sag: form finding, an edge cable's target sag [mm]
  bool sliding = false;
  StageArray weight;  // N/m per stage
  std::vector<std::string> clamps;  // -cable_<group>_clamps: node groups or node tags of the file
  double mu = 0.0;                  // -cable_<group>_mu: capstan friction at the clamps and saddles
  bool mu_set = false;
};

struct StructureInputs {
  std::vector<std::string> node_groups, element_groups;  // the mesh's, on every rank
  MeshGenInput generator;
  CheckInput check;
  std::vector<double> bulge_centre = {0.0, 0.0};          // -structure_initial_bulge_centre
  double bulge_radius = 0.0;                              // > 0: a paraboloid over this radius
  PetscInt stages = 0;                                    // -structure_stages (0: the longest array)
  double md[3] = {1.0, 0.0, 0.0};
  PetscInt reference = 0;                                 // 0 mesh, 1 pattern
  PetscBool pattern_lay_on = PETSC_TRUE;                  // blend mesh -> pattern over stage 1
  std::vector<std::string> pattern_strips;
  double initial_bulge = 0.0;
  StageArray wind, self_weight;
  double density = 1750.0;                                // kg/m^3
  std::vector<BcInput> bcs;
  std::vector<FilmInput> films;
  std::vector<RigidInput> rigids;
  std::vector<RegionInput> regions;
  std::vector<ChamberInput> chambers;
  std::vector<CableInput> cables;
  double atmosphere = 101.325;                            // kPa
  std::vector<std::string> report;                        // element groups and regions reported
  std::vector<double> probe_elements, probe_nodes;        // plan points, 2 each
  std::string history;                                    // -structure_history ("": beside the results)
};

// Rank 0: the area vector times 2 of element e, (x2 - x1) x (x3 - x1).
void StructureTriangleNormal(const MeshData &m, int e, double n[3]);

// Rank 0: per node of the scene's mesh, bit i set where its component i is prescribed
// (scene.constraints so far): 7 is a node held in x, y and z, 0 a free one.
std::vector<int> StructureHeldMask(const SceneSpec &scene);

// Rank 0's names (group names) on every rank (collective).
PetscErrorCode BroadcastNames(MPI_Comm comm, std::vector<std::string> *names);

PetscErrorCode StructureOptionsRead(MPI_Comm comm, const MeshData &mesh, bool form_finding, StructureInputs *in);

// The analysis' stage count (every per-stage array fits it) and the schedule of one array.
PetscErrorCode StructureStageCount(MPI_Comm comm, const StructureInputs &in, int *stages);
int StructureAddSchedule(SceneSpec *scene, const std::string &name, const std::vector<double> &values, int stages,
                         const std::string &unit, double display_scale);

// Supports (constraints), fills scene->constraints on rank 0; a DOF held by two groups must get
// the same value from both (an error names the node and the groups otherwise).
PetscErrorCode StructureAddSupports(MPI_Comm comm, const StructureInputs &in, int stages, SceneSpec *scene);
// Follower pressures, wind, snow, self-weight and group forces.
PetscErrorCode StructureAddLoads(MPI_Comm comm, const StructureInputs &in, int stages, SceneSpec *scene);
// Per-element thickness, MD direction and law of the surface groups that set them.
PetscErrorCode StructureFilmParts(MPI_Comm comm, const StructureInputs &in, SceneSpec *scene);
// Gas chambers: their specs and boundary pressure loads.
PetscErrorCode StructureAddChambers(MPI_Comm comm, const StructureInputs &in, int stages, SceneSpec *scene);
// Rigid supports and their candidate nodes (node set "structure_contact").
PetscErrorCode StructureAddRigid(MPI_Comm comm, const StructureInputs &in, SceneSpec *scene);

// -cable_<group>_* for the mesh's 1-D groups (every rank; refuses a cable option of a group that
// is not one); then the cables' chains and weights into scene->cables. With form finding, a free
// edge of the film that has neither a cable nor a support is refused.
PetscErrorCode StructureCablesRead(MPI_Comm comm, const MeshData &mesh, bool form_finding, StructureInputs *in);
PetscErrorCode StructureAddCables(MPI_Comm comm, const StructureInputs &in, int stages, SceneSpec *scene);

// The observer: per-group report at the end and the history CSV per increment, then the
// closed-form check of -structure_check.
// A check's hooks; `state` is what it carries from increment to increment (kept in checkpoints).
struct StructureCheckFns {
  // After the structure report.
  PetscErrorCode (*report)(Problem *P, const CheckInput &check, std::vector<double> *state) = nullptr;
  // Per increment, before the history row (a lab test's state line and CSV); may be null.
  PetscErrorCode (*step)(Problem *P, const CheckInput &check, std::vector<double> *state, PetscInt step, double t,
                         PetscInt print_every) = nullptr;
  std::vector<double> state;  // its start (empty: the check keeps none)
  // Once on the distributed problem, before the first increment (probes to find); may be null.
  PetscErrorCode (*setup)(Problem *P, const CheckInput &check) = nullptr;
  // The check's history CSV and report lines stand in for the structure's: a built-in scene whose
  // lines and columns scripts and tests read (the saddle's stretch fabrication).
  bool replaces_report = false;
};
using StructureCheckFn = StructureCheckFns;
PetscErrorCode StructureObserverCreate(const StructureInputs &in, StructureCheckFn check, SceneObserver *observer);
// Form finding: an observer that prints only the check (the surface found is the run's own report).
PetscErrorCode StructureCheckObserverCreate(const StructureInputs &in, StructureCheckFn check, SceneObserver *observer);

// -structure_mesh_generator: reads it and its size options; on rank 0 generates scene->mesh
// (false in *generated: no generator, read -mesh_file).
PetscErrorCode StructureMeshFromOptions(MPI_Comm comm, StructureInputs *in, SceneSpec *scene, bool *generated);
// A disc or rectangle with the -mesh_* keys of that generator (read here, checked, on rank 0 made).
PetscErrorCode StructureGenerateMesh(MPI_Comm comm, const char *owner, const MeshGenInput &gen, MeshData *mesh);

// -structure_check: completes in->check from the inputs (after the supports and loads are known)
// and gives the hooks that print it (none when no check is asked for).
// The checks' reports (structure_check_reports.cpp, structure_check_capstan.cpp).
PetscErrorCode HenckyCheck(Problem *P, const CheckInput &check, std::vector<double> *state);
PetscErrorCode PatchCheck(Problem *P, const CheckInput &check, std::vector<double> *state);
PetscErrorCode AnnulusCheck(Problem *P, const CheckInput &check, std::vector<double> *state);
PetscErrorCode CatenoidCheck(Problem *P, const CheckInput &check, std::vector<double> *state);
PetscErrorCode SaddleCheck(Problem *P, const CheckInput &check, std::vector<double> *state);
// The saddle's stretch fabrication (saddle_stretch.cpp): parts A and B, elements I and II, the arch
// slides, the Mises distribution and the heights; one history row per increment.
PetscErrorCode SaddleStretchCheckSetup(Problem *P, const CheckInput &check);
PetscErrorCode SaddleStretchCheckStep(Problem *P, const CheckInput &check, std::vector<double> *state, PetscInt step,
                                      double t, PetscInt print_every);
PetscErrorCode SaddleStretchCheckReport(Problem *P, const CheckInput &check, std::vector<double> *state);
// The thesis's probes (parts A and B, elements I and II, slide points I-V) of a saddle of rise H,
// for -structure_check saddle_stretch given as an option; history: its CSV ("": beside the results).
std::shared_ptr<SaddleStretchProbes> SaddleStretchProbesDefault(double rise, const std::string &history);
PetscErrorCode StripReport(Problem *P, const CheckInput &check, std::vector<double> *state);
PetscErrorCode StripStep(Problem *P, const CheckInput &check, std::vector<double> *state, PetscInt step, double t,
                         PetscInt print_every);
std::vector<double> CapstanCheckStart();
PetscErrorCode CapstanCheckStep(Problem *P, const CheckInput &check, std::vector<double> *state, PetscInt step,
                                double t, PetscInt print_every);
PetscErrorCode CapstanCheckReport(Problem *P, const CheckInput &check, std::vector<double> *state);
PetscErrorCode StructureCheckResolve(MPI_Comm comm, const SceneSpec &scene, StructureInputs *in,
                                     StructureCheckFn *fn);

// The general scene built with `preset` (may be null) applied to the options' inputs: a built-in
// scene (-scene hencky, -scene patch) is the general scene with its supports, loads, mesh and
// check given here instead of by options (src/scenes/<scene>.cpp). scene->mesh is already made
// when mesh_given.
using StructurePresetFn = PetscErrorCode (*)(MPI_Comm comm, StructureInputs *in, void *ctx);
PetscErrorCode StructureBuild(MPI_Comm comm, SceneSpec *scene, SceneObserver *observer, bool mesh_given,
                              StructurePresetFn preset, void *ctx);

} // namespace etfe
