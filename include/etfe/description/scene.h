// The scene description: mesh, supports, loads, schedule. Plain data (no PETSc, no solver
// types): the scenes layer fills it (scene_registry.h), the layers below read it (the problem's
// constraints and loads, the contact pairs' supports, the progress lines' schedules).
#pragma once
#include <map>
#include <string>
#include <vector>

#include "etfe/mesh/mesh_data.h"
#include "etfe/description/schedule.h"

namespace etfe {

// Per-stage option values by option name without '-' ("saddle_draw_a" -> one value per stage).
typedef std::map<std::string, std::vector<double>> StageValues;

// Prescribed displacement of one DOF of one node (node id in the scene's mesh numbering).
struct DofConstraint {
  int node;
  int comp;  // 0 = X, 1 = Y, 2 = Z
  ScheduledValue value;
};

// Follower pressure on a set of elements (empty set = all elements). A scene may have several
// (one per loaded group, each with its own schedule); on an element in more than one they add.
struct PressureSpec {
  std::vector<int> elements;
  ScheduledValue value;  // MPa
  // The boundary of gas chamber `chamber` (-1: none): its pressure is the chamber's (its gas law),
  // times `sign` (-1 where the elements' normals point into the chamber); value is unused.
  int chamber = -1;
  double sign = 1.0;
};

// A gas chamber (kernels/chamber.h, src/assembly/chamber.cpp): the pressure loads with its index
// bound it. Supplied: the gauge pressure follows `supplied`; from the start of stage
// `sealed_from_stage` (1-based; 0: never) it is sealed with the gas it holds then. Or per stage
// (`sealed_stages`, one flag per stage): sealed where a stage is flagged, the supply on again
// where the next is not (taking over from the sealed gas's pressure over that stage).
struct ChamberSpec {
  std::string name;
  // The surface groups that bound it and their signs (+1 where the group's normals point out of
  // it): the set-up checks name them, and layer contact between them lets it empty.
  std::vector<std::string> groups;
  std::vector<double> signs;
  double origin[3] = {0, 0, 0};  // on the planes that close it, if any
  ScheduledValue supplied;       // gauge pressure [MPa] while supplied
  int sealed_from_stage = 0;
  std::vector<char> sealed_stages;  // empty: sealed_from_stage decides
  bool SealedIn(int stage) const {  // 1-based
    if (!sealed_stages.empty()) return stage >= 1 && stage <= (int)sealed_stages.size() && sealed_stages[stage - 1];
    return sealed_from_stage > 0 && stage >= sealed_from_stage;
  }
  bool EverSealed() const {
    for (char s : sealed_stages) if (s) return true;
    return sealed_from_stage > 0;
  }
  double kappa = 1.0;            // p V^kappa = const when sealed
  double extra_volume = 0.0;     // mm^3 beyond the membranes (ducts, a reservoir)
};

// A dead nodal force (e.g. the tension T1 held on one end of the capstan strip).
struct NodalForce {
  int node;
  int comp;
  ScheduledValue value;  // N
};

// A rigid support: a circle of radius `radius` around the axis through `centre` (an arch, whose
// contact line is its crown line) or a cylinder (a pipe), both with the outward normal n = radial
// direction from the axis, the tangent x0 = axis x n and y0 = n x x0 = axis; or a plane through
// `centre` with the outward normal `axis` (kernels/contact_frame.h).
struct SupportSpec {
  std::string name;
  std::string type = "cylinder";  // "arch", "cylinder" or "plane"
  double centre[3] = {0, 0, 0};
  double axis[3] = {0, 1, 0};
  double radius = 1.0;
  // The node set of the nodes that may touch this support (empty: ContactSpec::node_set's): a
  // node within reach of two supports pairs with one that lists it.
  std::string node_set;
};

// Contact candidates: the scene names the supports and the film nodes that may touch them
// (a node set, or every node within the search tolerance of a support).
struct ContactSpec {
  bool active = false;
  std::vector<SupportSpec> supports;
  std::string node_set;      // empty: search all nodes
  double search_tol = 1e-6;  // mm, | distance to the support surface | below this makes a pair
};

// A cable along a chain of the film's nodes (the general scene's -cable_<group>_*; the physics is
// a term, src/assembly/cable_term.cpp). Small: the same on every rank.
struct CableSpec {
  std::string name;        // its 1-D group
  std::vector<int> nodes;  // the chain n0 ... nk, scene node ids
  double EA = 0.0;         // axial stiffness [N]
  double length = 0.0;     // stress-free length of the whole cable [mm] (0: from prestress)
  double prestress = 0.0;  // force at the reference geometry [N]; form finding: the prescribed force
  // Form finding: the prescribed force density [N/mm] (each segment's force q l), 0: none (then
  // prestress is the force, given or found from a target sag).
  double force_density = 0.0;
  bool sliding = false;    // one force along the whole chain (a frictionless pocket)
  // Sliding only: interior chain nodes that split it into sub-chains of their own force, the
  // stress-free length crossing them by capstan friction (mu); in chain order. Empty: none.
  std::vector<int> clamps;
  double mu = 0.0;
  bool weighted = false;
  ScheduledValue weight;   // self-weight [N/mm of stress-free length], acting along -z
};

// The mesh and every list indexed by its nodes or elements (constraints, nodal forces, pressure
// elements, element ratios and stress-free shapes, initial guess) are filled on rank 0 only, the
// reader; the other fields are the same on every rank (scene_registry.h).
struct SceneSpec {
  std::string name;
  // Set by the app before the builder runs (-analysis formfind): a scene that offers both
  // analyses builds the form-finding problem instead of the load history.
  bool form_finding = false;
  // Set by the caller before the builder runs: per-stage values that replace what the options
  // give (the drawing planner's trial schedules; a scene applies those it offers in stage_options).
  StageValues stage_overrides;
  MeshData mesh;
  double md_axis[3] = {1.0, 0.0, 0.0};   // MD direction for the element frames
  double thickness = 0.25;               // film thickness [mm] (-membrane_thickness overrides)
  std::vector<Schedule> schedules;       // every schedule has the same number of stages
  std::vector<DofConstraint> constraints;
  std::vector<PressureSpec> pressures;
  std::vector<ChamberSpec> chambers;
  double atmosphere = 0.101325;  // MPa, absolute: the chambers' gas laws
  std::vector<NodalForce> nodal_forces;
  std::vector<CableSpec> cables;  // every rank
  ContactSpec contact;
  std::vector<double> element_stress_ratio;  // form finding: MD:TD per element (empty: uniform)
  std::vector<double> initial_guess;     // 3 per node or empty (zero displacement)
  // Per element where the film differs by part (the general scene's surface groups): its
  // thickness [mm] (empty: -membrane_thickness everywhere) and MD direction (3 per element;
  // empty: md_axis everywhere).
  std::vector<double> element_thickness, element_md;
  // Surface groups with a law of their own (-film_<group>_material_*): the options prefix of each
  // ("film_<group>_", every rank), and per element which law it takes, 0 the film's (-material_*)
  // and k the prefix k-1's (rank 0; empty, as material_prefixes: one law for the whole film).
  std::vector<std::string> material_prefixes;
  std::vector<int> element_material;
  // Stress-free shape of each element where it differs from the nodes' positions (a cutting
  // pattern laid onto the surface: -saddle_reference pattern): 9 coordinates per element in
  // scene order, any placement; empty: every element is stress free where its nodes are.
  std::vector<double> element_reference;
  // How far the elements' reference has gone from the placed shape (0) to element_reference (1)
  // at load time t: a lay-on stage ramps it, so the misfit is loaded gradually.
  ScheduledValue reference_blend;
  std::string initial_guess_note;        // printed in the header when a guess is used
  // Per-stage option arrays as the builder resolved them, defaults included (name without '-'):
  // the drawing planner's start and staging (-analysis plan).
  StageValues stage_options;
  // Inputs a reader of the results needs and cannot take from the options alone (defaults the
  // builder chose, e.g. the saddle's part boxes and number of drawing stages): written as root
  // attributes of the results file, one double array each (docs/results.md).
  StageValues result_attributes;
  // The builder has checked each of its load options' scale itself, naming the option (the
  // general scene): the registry's scene-wide pressure check is then skipped.
  bool loads_checked = false;

  int NumStages() const { return schedules.empty() ? 1 : schedules[0].NumStages(); }
  int AddSchedule(const Schedule &s) {
    schedules.push_back(s);
    return (int)schedules.size() - 1;
  }
};

} // namespace etfe
