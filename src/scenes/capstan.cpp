// -scene capstan (rolling friction test, docs/theory.md §5.6 / thesis §5.2) as a case of the general scene: a
// film strip laid over a fixed pipe around a wrap angle theta (-structure_mesh_generator capstan).
// Stage 1 applies the tension T1 (a dead load) on end A with end B held; stage 2 pulls end B along
// its tangent (displacement control, so the run passes through gross slip without a limit point)
// while T1 stays. T2 is the reaction at end B; once every contact pair slips, Euler's belt formula
// predicts T2 = T1 exp(mu theta): -structure_check capstan prints T2 at slip onset and
// mu_eff = ln(T2/T1)/theta. The same case as options only: options/structure/verify_capstan.opts;
// this scene keeps its own option names (-capstan_*).
#include <petscsys.h>

#include <cmath>
#include <string>

#include "etfe/scenes/scene_registry.h"
#include "structure_inputs.h"

namespace etfe {

namespace {

struct CapstanInputs {
  PetscReal radius = 21.35, angle = 180.0, width = 50.0, t1 = 2.5, pull = 1.0;
  double theta = 0.0, tA[3] = {0, 0, 0}, tB[3] = {0, 0, 0};  // wrap [rad]; the ends' tangents
};

// What the capstan options give, as the general scene's inputs: end B gripped and pulled
// along its tangent in stage 2, the pipe (every node may touch it, the grip's too), the check.
PetscErrorCode CapstanPreset(MPI_Comm, StructureInputs *in, void *vctx) {
  const auto *c = (const CapstanInputs *)vctx;
  PetscFunctionBeginUser;
  in->bcs.push_back(BcInput());
  BcInput &b = in->bcs.back();
  b.group = "right";
  // Each component: pull x its tangent component times 0 then 1 (a zero component: held at 0).
  for (int i = 0; i < 3; ++i)
    b.move[i] = c->tB[i] != 0.0 ? StageArray{"-capstan_pull", {0.0, 1.0}, c->pull * c->tB[i]}
                                : StageArray{"-capstan_pull", {0.0, 0.0}, 0.0};
  RigidInput pipe;
  pipe.name = "pipe", pipe.type = "cylinder", pipe.radius = c->radius, pipe.fixed_nodes = true;
  in->rigids.push_back(pipe);
  CheckInput &ck = in->check;
  ck.name = "capstan", ck.theta = c->theta, ck.t1 = c->t1, ck.given = true;
  for (int i = 0; i < 3; ++i) ck.tB[i] = c->tB[i];
  PetscFunctionReturn(0);
}

} // namespace

PetscErrorCode SceneBuild_Capstan(MPI_Comm comm, SceneSpec *scene, SceneObserver *observer) {
  CapstanInputs c;
  PetscFunctionBeginUser;
  PetscOptionsBegin(comm, nullptr, "Capstan scene: film strip over a fixed pipe", "Scene");
  PetscCall(PetscOptionsReal("-capstan_radius", "Pipe radius [mm] (JIS G3452 pipe: 42.7/2)", "", c.radius, &c.radius,
                             nullptr));
  PetscCall(PetscOptionsReal("-capstan_angle", "Wrap angle theta [degrees]", "", c.angle, &c.angle, nullptr));
  PetscCall(PetscOptionsReal("-capstan_width", "Strip width [mm]", "", c.width, &c.width, nullptr));
  PetscCall(PetscOptionsReal("-capstan_t1", "Tension T1 held on end A [N]", "", c.t1, &c.t1, nullptr));
  PetscCall(PetscOptionsReal("-capstan_pull", "Pull of end B along its tangent in stage 2 [mm]", "", c.pull, &c.pull,
                             nullptr));
  PetscOptionsEnd();
  PetscCheck(c.radius > 0 && c.width > 0 && c.t1 > 0 && c.pull > 0, comm, PETSC_ERR_ARG_OUTOFRANGE,
             "capstan: -capstan_radius, -capstan_width, -capstan_t1 and -capstan_pull must be positive");
  PetscCheck(c.angle > 0 && c.angle <= 350, comm, PETSC_ERR_ARG_OUTOFRANGE,
             "-capstan_angle %g: the wrap angle must lie in (0, 350] degrees", c.angle);
  MeshGenInput gen;
  gen.name = "capstan", gen.wrap_radius = c.radius, gen.wrap_angle = c.angle, gen.wrap_width = c.width;
  PetscCall(StructureGenerateMesh(comm, "capstan scene", gen, &scene->mesh));
  PetscBool help = PETSC_FALSE;
  PetscCall(PetscOptionsHasHelp(nullptr, &help));
  if (help && scene->name.empty()) PetscFunctionReturn(0);  // -help without a scene: the options are shown
  c.theta = c.angle * M_PI / 180.0;
  const double phiA = -0.5 * c.theta, phiB = 0.5 * c.theta;
  const double tA[3] = {std::cos(phiA), 0.0, -std::sin(phiA)}, tB[3] = {std::cos(phiB), 0.0, -std::sin(phiB)};
  for (int i = 0; i < 3; ++i) c.tA[i] = tA[i], c.tB[i] = tB[i];
  scene->thickness = 0.2;  // the friction-test film (thesis §5.2)
  PetscCall(StructureBuild(comm, scene, observer, true, CapstanPreset, &c));
  // T1 on end A along -t_A in both stages, each node its share of the width (half at the edges).
  const int s_t1 = scene->AddSchedule({"tension", 0.0, {1.0, 1.0}});
  if (SceneHoldsMesh(comm)) {
    const MeshData &m = scene->mesh;
    const std::vector<int> &left = m.node_sets.at("left");
    const double ny = (double)left.size() - 1.0;
    for (int n : left) {
      const double y = m.coords[3 * n + 1];
      const double share = (std::fabs(std::fabs(y) - 0.5 * c.width) < 1e-9 * c.width ? 0.5 : 1.0) / ny;
      for (int i = 0; i < 3; ++i)
        if (c.tA[i] != 0.0) scene->nodal_forces.push_back({n, i, {{-c.t1 * share * c.tA[i], 0.0}, {s_t1, -1}}});
    }
  }
  // The pipe's search tolerance as this scene always had it, every node a candidate.
  scene->contact.search_tol = 1e-6 * c.radius;
  scene->contact.node_set.clear();
  PetscFunctionReturn(0);
}

} // namespace etfe
