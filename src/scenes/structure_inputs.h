// The general scene (-scene structure): a user's own structure from a mesh file whose physical
// groups name its parts, and options keyed by those names (docs/own-structure.md). This header
// holds what the options give (structure_options.cpp reads them), what the builder makes of them
// (structure.cpp, structure_supports.cpp, structure_loads.cpp) and what the observer reports
// (structure_report.cpp). Scenes layer, private.
#pragma once
#include <petscsys.h>

#include <string>
#include <vector>

#include "etfe/problem.h"
#include "etfe/scene.h"

namespace etfe {

// A per-stage option: values at the end of each stage; an array shorter than the analysis holds
// its last value in the stages after it.
struct StageArray {
  std::string option;  // "-film_roof_pressure", for messages
  std::vector<double> values;
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
  StageArray move[3];           // per component: stages, or points x stages (point-major)
  StageArray force;             // total force on the group, 3 per stage [N]
};

// -film_<group>_*: a surface group's loads and form-finding ratio.
struct FilmInput {
  std::string group;
  double stress_ratio = 1.0;  // form finding: MD:TD
  double thickness = 0.0;     // mm (0: -membrane_thickness)
  std::vector<double> md;     // MD direction x,y,z (empty: -structure_md)
  bool md_strip = false;      // MD along the group's long axis
  StageArray pressure;        // follower pressure along the elements' normal [kPa]
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

// -cable_<group>_*: a cable along a 1-D group of the mesh (structure_cables.cpp).
struct CableInput {
  std::string group;
  double EA = 0.0, length = 0.0, prestress = 0.0;
  bool sliding = false;
  StageArray weight;  // N/m per stage
};

struct StructureInputs {
  std::vector<std::string> node_groups, element_groups;  // the mesh's, on every rank
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
// Per-element thickness and MD direction of the surface groups that set them.
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

// The observer: per-group report at the end and the history CSV per increment.
PetscErrorCode StructureObserverCreate(const StructureInputs &in, SceneObserver *observer);

} // namespace etfe
