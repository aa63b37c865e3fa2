// The general scene (-scene structure): everything from a mesh file and options keyed by its
// physical groups (structure_inputs.h, docs/own-structure.md). The film is every triangle of the
// mesh; node groups are held or moved (-bc_*), surface groups loaded (-film_*), rigid supports
// given by geometry or fitted to a curve of the mesh (-rigid_*). With -analysis formfind the
// supported nodes stay where they are and each surface group takes its MD:TD prestress ratio.
#include <petscsys.h>

#include <algorithm>
#include <cmath>

#include "etfe/kernels/nearest.h"
#include "etfe/mesh/mesh_options.h"
#include "etfe/base/rank0.h"
#include "etfe/scenes/scene_registry.h"
#include "pattern_reference.h"
#include "structure_inputs.h"

namespace etfe {

namespace {

// Rank 0: the report regions as element sets (centroid in the plan box).
void AddRegions(const StructureInputs &in, MeshData *m) {
  for (const RegionInput &r : in.regions) {
    std::vector<int> &set = m->element_sets[r.name];
    set.clear();
    for (int e = 0; e < m->NumElements(); ++e) {
      double cx = 0, cy = 0;
      for (int a = 0; a < 3; ++a) cx += m->coords[3 * m->triangles[3 * e + a]] / 3, cy += m->coords[3 * m->triangles[3 * e + a] + 1] / 3;
      if (cx >= r.box[0] && cx <= r.box[2] && cy >= r.box[1] && cy <= r.box[3]) set.push_back(e);
    }
  }
}

// Rank 0: a region or report group without elements cannot be reported.
std::string EmptyRegion(const StructureInputs &in, const MeshData &m) {
  for (const RegionInput &r : in.regions)
    if (m.element_sets.at(r.name).empty())
      return "-region_" + r.name + "_box: no element of " + m.source + " has its centroid in the box";
  return "";
}

// Form finding: MD:TD per element from its surface group (the last group listed wins where
// groups overlap; an element in none takes -formfind_ratio, `ratio`). No group with a ratio of its
// own: none per element, so the analysis's -formfind_ratio holds everywhere.
void FormFindingRatios(const StructureInputs &in, double ratio, SceneSpec *scene) {
  const MeshData &m = scene->mesh;
  scene->element_stress_ratio.clear();
  for (const FilmInput &f : in.films) {
    if (!f.stress_ratio_given) continue;
    if (scene->element_stress_ratio.empty()) scene->element_stress_ratio.assign(m.NumElements(), ratio);
    for (int e : m.element_sets.at(f.group)) scene->element_stress_ratio[e] = f.stress_ratio;
  }
}

// Rank 0: -structure_initial_bulge h lifts each free node along the film's mean normal by
// h (d/D)(2 - d/D), d its distance to the nearest fully held node and D the largest such distance
// (on a clamped disc the paraboloid h (1 - r^2/a^2)).
std::string InitialBulge(double h, SceneSpec *scene) {
  const MeshData &m = scene->mesh;
  std::vector<int> held(m.NumNodes(), 0);
  for (const DofConstraint &c : scene->constraints) held[c.node]++;
  std::vector<int> anchors;
  for (int n = 0; n < m.NumNodes(); ++n)
    if (held[n] == 3) anchors.push_back(n);
  if (anchors.empty()) return "-structure_initial_bulge: no node is held in all three directions to lift the film from";
  double normal[3] = {0, 0, 0};
  for (int e = 0; e < m.NumElements(); ++e) {
    double n[3];
    StructureTriangleNormal(m, e, n);
    for (int i = 0; i < 3; ++i) normal[i] += n[i];
  }
  const double len = std::hypot(normal[0], normal[1], normal[2]);
  if (!(len > 0)) return "-structure_initial_bulge: the film has no mean normal (a closed surface?)";
  std::vector<double> anchor_xyz;
  for (int a : anchors) anchor_xyz.insert(anchor_xyz.end(), &m.coords[3 * a], &m.coords[3 * a] + 3);
  const std::vector<double> d = NearestAnchorDistances(m.coords, anchor_xyz);  // 0 at the held nodes
  const double dmax = *std::max_element(d.begin(), d.end());
  scene->initial_guess.assign(3 * (size_t)m.NumNodes(), 0.0);
  for (int n = 0; n < m.NumNodes(); ++n) {
    const double s = dmax > 0 ? d[n] / dmax : 0.0, lift = h * s * (2.0 - s);
    for (int i = 0; i < 3; ++i) scene->initial_guess[3 * n + i] = lift * normal[i] / len;
  }
  return "";
}

// Rank 0: -structure_initial_bulge_radius R lifts each node in z by h (1 - r^2/R^2), r its plan
// distance from the centre (0 beyond R): the clamped disc's paraboloid, as the hencky scene
// always started from.
void InitialParaboloid(const StructureInputs &in, SceneSpec *scene) {
  const MeshData &m = scene->mesh;
  const double h = in.initial_bulge, R = in.bulge_radius;
  scene->initial_guess.assign(3 * (size_t)m.NumNodes(), 0.0);
  for (int n = 0; n < m.NumNodes(); ++n) {
    const double x = m.coords[3 * n] - in.bulge_centre[0], y = m.coords[3 * n + 1] - in.bulge_centre[1];
    scene->initial_guess[3 * n + 2] = h * std::max(0.0, 1.0 - (x * x + y * y) / (R * R));
  }
}

PetscErrorCode BuildLoadHistory(MPI_Comm comm, const StructureInputs &in, int stages, SceneSpec *scene) {
  PetscFunctionBeginUser;
  PetscCall(StructureAddLoads(comm, in, stages, scene));
  PetscCall(StructureAddChambers(comm, in, stages, scene));
  PetscCall(StructureAddRigid(comm, in, scene));
  if (in.reference == 1) {
    PatternStrips strips{in.pattern_strips, "-structure_reference pattern", "structure",
                         "list the mesh's surface groups cut as strips in -structure_pattern_strips"};
    if (strips.strips.empty()) strips.strips = in.element_groups;
    // The patterns as -cutpattern cuts them: with -cutpattern_compensation they are cut smaller,
    // so the laid-on film reaches its prestress (a form-found design's installed state).
    CutPatternOptions cut;
    PetscCall(CutPatternOptionsFromCommandLine(comm, &cut));
    PetscCheck(cut.compensation != Compensation::Stress || cut.prestress_given, comm, PETSC_ERR_USER_INPUT,
               "-structure_reference pattern with -cutpattern_compensation stress: give the design prestress "
               "-cutpattern_prestress S_MD,S_TD (MPa), or use -cutpattern_compensation uniform; a static run has no "
               "form-finding stress to compensate for");
    strips.cut = &cut;
    PetscCall(PatternReference(comm, scene->mesh, strips, &scene->element_reference));
    // Laid on during the first stage, while the supports draw the film (pattern_reference.cpp);
    // or the reference from the start, where the mesh only stretches the patterns (a lens).
    const double start = in.pattern_lay_on ? 0.0 : 1.0;
    const int sl = scene->AddSchedule({"lay_on", start, std::vector<double>(stages, 1.0), ""});
    scene->reference_blend = {{1.0, 0.0}, {sl, -1}};
  }
  if (in.initial_bulge != 0.0 && in.bulge_radius > 0.0) {
    if (SceneHoldsMesh(comm)) InitialParaboloid(in, scene);
    char note[160];
    std::snprintf(note, sizeof note,
                  "paraboloid bulge of %g mm (a flat membrane has no out-of-plane stiffness; the guess does not "
                  "change the converged answer)",
                  in.initial_bulge);
    scene->initial_guess_note = note;
  } else if (in.initial_bulge != 0.0) {
    std::string err;
    if (SceneHoldsMesh(comm)) err = InitialBulge(in.initial_bulge, scene);
    PetscCall(Rank0Outcome(comm, err.empty() ? 1 : 0, err, PETSC_ERR_ARG_WRONG));
    char note[160];
    std::snprintf(note, sizeof note,
                  "film lifted by up to %g mm along its mean normal (-structure_initial_bulge; the guess does not "
                  "change the converged answer)",
                  in.initial_bulge);
    scene->initial_guess_note = note;
  }
  PetscFunctionReturn(0);
}

} // namespace

PetscErrorCode StructureBuild(MPI_Comm comm, SceneSpec *scene, SceneObserver *observer, bool mesh_given,
                              StructurePresetFn preset, void *ctx) {
  MeshOptions mesh;
  StructureInputs in;
  PetscFunctionBeginUser;
  bool generated = mesh_given;
  if (!mesh_given) PetscCall(StructureMeshFromOptions(comm, &in, scene, &generated));
  if (!generated) {
    mesh.keys = kMeshFile;
    PetscCall(MeshOptionsFromCommandLine(comm, "structure scene", &mesh));
    PetscBool help = PETSC_FALSE;
    PetscCall(PetscOptionsHasHelp(nullptr, &help));
    if (help && mesh.file.empty()) {
      // -help without a mesh: the scene-wide options; the per-group ones need the mesh's groups.
      PetscCall(StructureOptionsRead(comm, scene->mesh, scene->form_finding, &in));
      PetscCall(PetscPrintf(comm, "  (-scene structure -mesh_file <mesh> -help also lists -bc_<group>_*, "
                                  "-film_<group>_*, -cable_<group>_*, -rigid_<name>_* and -region_<name>_* for the groups of that mesh)\n"));
      PetscFunctionReturn(0);
    }
    PetscCheck(!mesh.file.empty(), comm, PETSC_ERR_ARG_WRONG,
               "-scene structure needs -mesh_file <mesh.msh>: a Gmsh mesh whose physical groups name the film's "
               "surfaces and the supported curves (scripts/surface2msh makes one from OBJ/STL; docs/own-structure.md), "
               "or -structure_mesh_generator disc|rectangle");
    PetscCall(SceneReadMesh(comm, mesh.file.c_str(), &scene->mesh));
  }
  // "all" always names the whole film, so a mesh without surface groups can be loaded too.
  if (SceneHoldsMesh(comm) && !scene->mesh.element_sets.count("all")) {
    std::vector<int> &all = scene->mesh.element_sets["all"];
    for (int e = 0; e < scene->mesh.NumElements(); ++e) all.push_back(e);
  }
  PetscCall(StructureOptionsRead(comm, scene->mesh, scene->form_finding, &in));
  if (preset) PetscCall(preset(comm, &in, ctx));
  for (int i = 0; i < 3; ++i) scene->md_axis[i] = in.md[i];
  int stages = 1;
  PetscCall(StructureStageCount(comm, in, &stages));
  std::string err;
  if (SceneHoldsMesh(comm)) AddRegions(in, &scene->mesh), err = EmptyRegion(in, scene->mesh);
  PetscCall(Rank0Outcome(comm, err.empty() ? 1 : 0, err, PETSC_ERR_ARG_WRONG));
  if (scene->form_finding) {
    PetscCheck(!in.bcs.empty(), comm, PETSC_ERR_ARG_WRONG,
               "form finding needs a boundary: hold the supported node groups with -bc_<group>_fix xyz");
    scene->AddSchedule({"boundary", 0.0, {1.0}});
    PetscCall(StructureAddSupports(comm, in, 1, scene));
    // The analysis's -formfind_ratio (read there, with its checks) for the groups without their own.
    PetscReal ratio = 1.0;
    PetscCall(PetscOptionsGetReal(nullptr, nullptr, "-formfind_ratio", &ratio, nullptr));
    if (SceneHoldsMesh(comm)) FormFindingRatios(in, ratio, scene);
    PetscCall(StructureFilmParts(comm, in, scene));
    PetscCall(StructureAddCables(comm, in, 1, scene));
  } else {
    PetscCall(StructureFilmParts(comm, in, scene));
    PetscCall(StructureAddSupports(comm, in, stages, scene));
    PetscCall(BuildLoadHistory(comm, in, stages, scene));
    PetscCall(StructureAddCables(comm, in, stages, scene));
  }
  // Form finding reports its own figures (the surface found is written as a mesh), then the check.
  StructureCheckFn check;
  PetscCall(StructureCheckResolve(comm, *scene, &in, &check));
  if (!scene->form_finding) PetscCall(StructureObserverCreate(in, check, observer));
  else if (check.report) PetscCall(StructureCheckObserverCreate(in, check, observer));
  PetscFunctionReturn(0);
}

PetscErrorCode SceneBuild_Structure(MPI_Comm comm, SceneSpec *scene, SceneObserver *observer) {
  PetscFunctionBeginUser;
  PetscCall(StructureBuild(comm, scene, observer, false, nullptr, nullptr));
  PetscFunctionReturn(0);
}

} // namespace etfe
