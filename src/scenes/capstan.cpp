// Capstan (rolling friction) test, SPEC §9 / thesis §5.2: a film strip laid over a fixed pipe
// around a wrap angle theta. Stage 1 applies the tension T1 (a dead load) on end A with end B
// held; stage 2 pulls end B along its tangent (displacement control, so the run passes through
// gross slip without a limit point) while T1 stays. T2 is the reaction at end B; once every
// contact pair slips, Euler's belt formula predicts T2 = T1 exp(mu theta). The scene prints
// T2 at slip onset and mu_eff = ln(T2/T1)/theta.
#include <petscsys.h>

#include <cmath>
#include <string>

#include "etfe/assembly.h"
#include "etfe/contact.h"
#include "etfe/mesh/generators.h"
#include "etfe/mesh/mesh_options.h"
#include "etfe/scene_registry.h"

namespace etfe {

namespace {

struct CapstanContext {
  double theta, t1, tB[3];
  std::vector<char> is_b;    // per local node: on end B (setup)
  double t2_onset = -1.0, t2_last = 0.0;
  PetscInt onset_step = -1;
};

PetscErrorCode CapstanSetup(Problem *P, void *vctx) {
  return ProblemNodeSetFlags(P, "right", &((CapstanContext *)vctx)->is_b);
}

PetscErrorCode EndBTension(Problem *P, CapstanContext *c, double *t2) {
  const PetscScalar *r;
  double mine = 0.0;
  const std::vector<char> &is_b = c->is_b;
  PetscFunctionBeginUser;
  PetscCall(VecGetArrayRead(P->reaction, &r));
  for (PetscInt l = 0; l < P->mesh.num_owned; ++l)
    if (is_b[l])
      for (int i = 0; i < 3; ++i) mine += r[3 * l + i] * c->tB[i];
  PetscCall(VecRestoreArrayRead(P->reaction, &r));
  PetscCallMPI(MPI_Allreduce(&mine, t2, 1, MPI_DOUBLE, MPI_SUM, P->comm));
  PetscFunctionReturn(0);
}

PetscErrorCode CapstanStep(Problem *P, void *vctx, PetscInt step, double t, PetscInt print_every) {
  auto *c = (CapstanContext *)vctx;
  double t2;
  PetscInt local[2] = {0, 0}, global[2];
  PetscFunctionBeginUser;
  PetscCall(EndBTension(P, c, &t2));
  const std::vector<char> &is_b = c->is_b;
  const ContactSet &contact = *FindTerm<ContactSet>(*P);  // the scene's supports make it
  for (const ContactPair &pr : contact.pairs) {
    if (is_b[pr.local_node]) continue;  // held by the grip: their slide is prescribed
    local[0] += pr.committed.status != CONTACT_OPEN;
    // Slipping, or sticking at the Coulomb limit: the lagged law commits a slipping pair whose
    // node stopped or turned back within the increment as sticking with its force still on the
    // cone (kernels/contact_law.cpp), so in gross slip pairs pass between the two; either way
    // their friction is fully mobilised. (The implicit law's sticking pairs lie inside the cone.)
    const ContactPairReport r = ContactReport(contact, pr);
    const double limit = contact.params.mu * std::fabs(r.force[2]);
    local[1] += pr.committed.status == CONTACT_SLIP ||
                (pr.committed.status == CONTACT_STICK && std::hypot(r.force[0], r.force[1]) >= limit * (1.0 - 1e-9));
  }
  PetscCallMPI(MPI_Allreduce(local, global, 2, MPIU_INT, MPI_SUM, P->comm));
  c->t2_last = t2;
  const bool gross = global[0] > 0 && global[1] == global[0];
  if (gross && c->onset_step < 0 && t > 1.0) {
    c->onset_step = step;
    c->t2_onset = t2;
  }
  // Thinned like the progress line (-load_monitor n); the slip onset is always shown.
  if (print_every > 0 && (step % print_every == 0 || c->onset_step == step))
    PetscCall(PetscPrintf(P->comm, "             capstan: T2 = %.6e N, T2/T1 = %.6f, slipping pairs %" PetscInt_FMT "/%" PetscInt_FMT "%s%s\n",
                        t2, t2 / c->t1, global[1], global[0], gross ? " (gross slip)" : "",
                        c->onset_step == step ? (" <- slip onset at step " + std::to_string(step)).c_str() : ""));
  PetscFunctionReturn(0);
}

PetscErrorCode CapstanReport(Problem *P, void *vctx) {
  auto *c = (CapstanContext *)vctx;
  PetscFunctionBeginUser;
  PetscCheck(c->onset_step >= 0, P->comm, PETSC_ERR_NOT_CONVERGED,
             "capstan: no gross slip by the end of the pull (T2/T1 = %.4f); increase -capstan_pull",
             c->t2_last / c->t1);
  const double mu_eff = std::log(c->t2_onset / c->t1) / c->theta;
  double mu = FindTerm<ContactSet>(*P)->params.mu;
  PetscCall(PetscPrintf(P->comm,
                        "capstan: theta = %.6f rad, T1 = %.6e N, T2 at slip onset = %.6e N (step %" PetscInt_FMT "), "
                        "T2 at the end = %.6e N, exp(mu theta) = %.6f\n",
                        c->theta, c->t1, c->t2_onset, c->onset_step, c->t2_last, std::exp(mu * c->theta)));
  PetscCall(PetscPrintf(P->comm, "mu_eff = %.8f\n", mu_eff));
  PetscCall(PetscPrintf(P->comm, "capstan: mu = %.6f, relative_error = %.3e\n", mu,
                        mu > 0 ? std::fabs(mu_eff - mu) / mu : std::fabs(mu_eff)));
  PetscFunctionReturn(0);
}

} // namespace

PetscErrorCode SceneBuild_Capstan(MPI_Comm comm, SceneSpec *scene, SceneObserver *observer) {
  PetscReal radius = 21.35, angle = 180.0, width = 50.0, t1 = 2.5, pull = 1.0;
  PetscFunctionBeginUser;
  PetscOptionsBegin(comm, nullptr, "Capstan scene: film strip over a fixed pipe", "Scene");
  PetscCall(PetscOptionsReal("-capstan_radius", "Pipe radius [mm] (JIS G3452 pipe: 42.7/2)", "", radius, &radius, nullptr));
  PetscCall(PetscOptionsReal("-capstan_angle", "Wrap angle theta [degrees]", "", angle, &angle, nullptr));
  PetscCall(PetscOptionsReal("-capstan_width", "Strip width [mm]", "", width, &width, nullptr));
  PetscCall(PetscOptionsReal("-capstan_t1", "Tension T1 held on end A [N]", "", t1, &t1, nullptr));
  PetscCall(PetscOptionsReal("-capstan_pull", "Pull of end B along its tangent in stage 2 [mm]", "", pull, &pull, nullptr));
  PetscOptionsEnd();
  MeshOptions mesh;
  mesh.keys = kMeshGrid | kMeshRefine, mesh.nx = 60, mesh.ny = 4;
  PetscCall(MeshOptionsFromCommandLine(comm, "capstan scene", &mesh));
  PetscInt nx = mesh.nx, ny = mesh.ny;
  const PetscInt refine = mesh.refine;
  PetscCheck(radius > 0 && width > 0 && t1 > 0 && pull > 0, comm, PETSC_ERR_ARG_OUTOFRANGE,
             "capstan: -capstan_radius, -capstan_width, -capstan_t1 and -capstan_pull must be positive");
  PetscCheck(angle > 0 && angle <= 350, comm, PETSC_ERR_ARG_OUTOFRANGE,
             "-capstan_angle %g: the wrap angle must lie in (0, 350] degrees", angle);
  PetscCheck(nx >= 2 && ny >= 1 && refine >= 0 && refine < 10, comm, PETSC_ERR_ARG_OUTOFRANGE,
             "capstan: need -mesh_nx >= 2, -mesh_ny >= 1, 0 <= -mesh_refine < 10");
  PetscCheck(GeneratedTriangles(nx, ny, 2, refine) <= kMaxGeneratedTriangles, comm, PETSC_ERR_ARG_OUTOFRANGE,
             "-mesh_nx %" PetscInt_FMT " -mesh_ny %" PetscInt_FMT " -mesh_refine %" PetscInt_FMT ": %.3g triangles, more "
             "than the %.3g a generated mesh may have", nx, ny, refine, GeneratedTriangles(nx, ny, 2, refine),
             kMaxGeneratedTriangles);
  nx <<= refine;
  ny <<= refine;
  const double theta = angle * M_PI / 180.0;
  const int s_t1 = scene->AddSchedule({"tension", 0.0, {1.0, 1.0}});
  const int s_pull = scene->AddSchedule({"pull", 0.0, {0.0, 1.0}});
  const double phiA = -0.5 * theta, phiB = 0.5 * theta;
  const double tA[3] = {std::cos(phiA), 0.0, -std::sin(phiA)};
  auto *ctx = new CapstanContext{theta, t1, {std::cos(phiB), 0.0, -std::sin(phiB)}, {}};
  scene->thickness = 0.2;  // the friction-test film (thesis §5.2)
  if (SceneHoldsMesh(comm)) {
    // Strip laid on the pipe (stress free): arc length s along the wrap, y across.
    MeshData &m = scene->mesh;
    m = MakeRectangleMesh(0.0, -0.5 * width, radius * theta, width, (int)nx, (int)ny, DiagonalPattern::Alternate, 0.0, 0u);
    m.source = "capstan strip " + std::to_string(nx) + "x" + std::to_string(ny);
    for (int n = 0; n < m.NumNodes(); ++n) {
      double *x = &m.coords[3 * n];
      const double phi = x[0] / radius - 0.5 * theta;
      x[0] = radius * std::sin(phi);
      x[2] = radius * std::cos(phi);
    }
    for (int n : m.node_sets.at("left")) {
      const double y = m.coords[3 * n + 1];
      const double share = (std::fabs(std::fabs(y) - 0.5 * width) < 1e-9 * width ? 0.5 : 1.0) / ny;
      for (int i = 0; i < 3; ++i)
        if (tA[i] != 0.0) scene->nodal_forces.push_back({n, i, {{-t1 * share * tA[i], 0.0}, {s_t1, -1}}});
    }
    for (int n : m.node_sets.at("right"))
      for (int i = 0; i < 3; ++i) scene->constraints.push_back({n, i, {{pull * ctx->tB[i], 0.0}, {s_pull, -1}}});
  }
  // Every node rests on the pipe. The grip holds end B, so its pairs carry no normal force and
  // the wrap that feels friction is theta minus half a segment: mu_eff converges as O(1/nx).
  scene->contact.active = true;
  scene->contact.search_tol = 1e-6 * radius;
  SupportSpec pipe;
  pipe.name = "pipe";
  pipe.type = "cylinder";
  pipe.radius = radius;
  scene->contact.supports.push_back(pipe);
  observer->setup = CapstanSetup;
  observer->step_monitor = CapstanStep;
  observer->state_get = [](void *c, std::vector<double> *v) {
    auto *x = (CapstanContext *)c;
    *v = {x->t2_onset, (double)x->onset_step, x->t2_last};
  };
  observer->state_set = [](void *c, const std::vector<double> &v) {
    auto *x = (CapstanContext *)c;
    x->t2_onset = v.at(0), x->onset_step = (PetscInt)v.at(1), x->t2_last = v.at(2);
  };
  observer->report = CapstanReport;
  observer->ctx = ctx;
  observer->destroy = [](void *c) { delete (CapstanContext *)c; };
  PetscFunctionReturn(0);
}

} // namespace etfe
