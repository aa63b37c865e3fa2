// Hencky's problem (docs/theory.md §13): a flat circular membrane clamped at its rim under uniform
// follower pressure. The closed form (Foppl theory, coefficients by a shooting solve) gives the
// centre deflection and centre stress; the scene prints both with the relative errors.
//
// A flat membrane has no out-of-plane stiffness at zero load, so Newton cannot start from the
// flat state. The scene starts from a paraboloid bulge (-hencky_initial_bulge, default a/10):
// only the initial guess changes, the converged answer does not.
#include <petscsys.h>

#include <cmath>

#include "etfe/assembly.h"
#include "etfe/mesh/generators.h"
#include "etfe/mesh/mesh_options.h"
#include "etfe/scene_registry.h"
#include "etfe/verification/hencky_closed_form.h"

namespace etfe {

namespace {

struct HenckyContext {
  double radius, pressure;
  PetscInt centre = -1;  // scene id of the centre node (setup)
};

PetscErrorCode HenckySetup(Problem *P, void *vctx) {
  auto *ctx = (HenckyContext *)vctx;
  std::vector<PetscInt> ids;
  PetscFunctionBeginUser;
  PetscCall(ProblemNodeSetIds(P, "centre", &ids));
  PetscCheck(ids.size() == 1, P->comm, PETSC_ERR_PLIB, "hencky: the disc mesh has %zu centre nodes", ids.size());
  ctx->centre = ids[0];
  PetscFunctionReturn(0);
}

PetscErrorCode HenckyReport(Problem *P, void *vctx) {
  auto *ctx = (HenckyContext *)vctx;
  double young, nu, u[3];
  HenckyCoefficients c;
  CellFields cells;
  PetscFunctionBeginUser;
  P->material->ElasticConstants(&young, &nu);
  PetscCheck(HenckyCoefficientsCompute(nu, &c) == 0, P->comm, PETSC_ERR_LIB,
             "Hencky closed form: no solution for nu = %g", nu);
  const double a = ctx->radius, p = ctx->pressure, h = P->thickness;
  const double w_ref = c.deflection * a * std::cbrt(p * a / (young * h));
  const double s_ref = c.centre_stress * std::cbrt(young * p * p * a * a / (h * h));
  PetscCall(ProblemGetNodeDisplacement(P, P->U, ctx->centre, u));
  // Centre stress: mean of (Sxx + Syy)/2 over the elements touching the centre node.
  PetscCall(ComputeCellFields(P, P->U, &cells, false));
  double sum[2] = {0, 0}, tot[2];
  for (PetscInt e = 0; e < P->mesh.num_elements; ++e) {
    const int *t = &P->mesh.tri[3 * e];
    bool at_centre = false;
    for (int k = 0; k < 3; ++k) at_centre |= P->mesh.natural_id[t[k]] == ctx->centre;
    if (!at_centre) continue;
    sum[0] += 0.5 * (cells.stress[3 * e] + cells.stress[3 * e + 1]);
    sum[1] += 1.0;
  }
  PetscCallMPI(MPI_Allreduce(sum, tot, 2, MPI_DOUBLE, MPI_SUM, P->comm));
  const double s = tot[0] / tot[1];
  PetscCall(PetscPrintf(P->comm,
                        "hencky: C_w(nu=%g) = %.6f, C_s = %.6f, p a/(E h) = %.3e\n"
                        "hencky: centre_deflection = %.6e mm, closed_form = %.6e mm, "
                        "relative_error = %.3e\n"
                        "hencky: centre_stress = %.6e MPa, closed_form = %.6e MPa, "
                        "relative_error = %.3e\n",
                        nu, c.deflection, c.centre_stress, p * a / (young * h), u[2], w_ref,
                        std::fabs(u[2] - w_ref) / w_ref, s, s_ref, std::fabs(s - s_ref) / s_ref));
  PetscFunctionReturn(0);
}

} // namespace

PetscErrorCode SceneBuild_Hencky(MPI_Comm comm, SceneSpec *scene, SceneObserver *observer) {
  PetscReal radius = 500.0, pressure = 2e-4, bulge = -1.0;
  PetscFunctionBeginUser;
  PetscOptionsBegin(comm, nullptr, "Hencky scene: clamped circular membrane under pressure", "Scene");
  PetscCall(PetscOptionsReal("-hencky_radius", "Radius a [mm]", "", radius, &radius, nullptr));
  PetscCall(PetscOptionsReal("-hencky_pressure", "Pressure p [MPa]", "", pressure, &pressure, nullptr));
  PetscCall(PetscOptionsReal("-hencky_initial_bulge",
                             "Centre height of the paraboloid initial guess [mm] (default a/10)", "",
                             bulge, &bulge, nullptr));
  PetscOptionsEnd();
  MeshOptions mesh;
  mesh.keys = kMeshRings | kMeshRefine, mesh.rings = 16;
  PetscCall(MeshOptionsFromCommandLine(comm, "hencky scene", &mesh));
  PetscInt rings = mesh.rings;
  const PetscInt refine = mesh.refine;
  PetscCheck(radius > 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "-hencky_radius %g must be positive", radius);
  PetscCheck(rings >= 1 && refine >= 0 && refine < 12, comm, PETSC_ERR_ARG_OUTOFRANGE,
             "-mesh_rings %" PetscInt_FMT " / -mesh_refine %" PetscInt_FMT ": need rings >= 1 and 0 <= refine < 12",
             rings, refine);
  if (bulge < 0) bulge = 0.1 * radius;
  PetscCheck(GeneratedTriangles(rings, rings, 6, refine) <= kMaxGeneratedTriangles, comm, PETSC_ERR_ARG_OUTOFRANGE,
             "-mesh_rings %" PetscInt_FMT " -mesh_refine %" PetscInt_FMT ": %.3g triangles, more than the %.3g a "
             "generated mesh may have", rings, refine, GeneratedTriangles(rings, rings, 6, refine), kMaxGeneratedTriangles);
  rings <<= refine;
  const int s = scene->AddSchedule({"pressure", 0.0, {1.0}});
  scene->pressures.push_back({{}, {{pressure, 0.0}, {s, -1}}});
  if (SceneHoldsMesh(comm)) {
    scene->mesh = MakeDiscMesh(radius, (int)rings);
    for (int n : scene->mesh.node_sets.at("rim"))
      for (int c = 0; c < 3; ++c) scene->constraints.push_back({n, c, {}});
    const int nn = scene->mesh.NumNodes();
    scene->initial_guess.assign(3 * nn, 0.0);
    for (int n = 0; n < nn; ++n) {
      const double x = scene->mesh.coords[3 * n], y = scene->mesh.coords[3 * n + 1];
      scene->initial_guess[3 * n + 2] = bulge * std::max(0.0, 1.0 - (x * x + y * y) / (radius * radius));
    }
  }
  char note[160];
  std::snprintf(note, sizeof note,
                "paraboloid bulge of %g mm (a flat membrane has no out-of-plane stiffness; the "
                "guess does not change the converged answer)",
                bulge);
  scene->initial_guess_note = note;
  auto *ctx = new HenckyContext{radius, pressure};
  observer->setup = HenckySetup;
  observer->report = HenckyReport;
  observer->ctx = ctx;
  observer->destroy = [](void *c) { delete (HenckyContext *)c; };
  PetscFunctionReturn(0);
}

} // namespace etfe
