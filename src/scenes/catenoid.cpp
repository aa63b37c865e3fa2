// Catenoid (a check of form finding): a soap film between two coaxial rings of radius R a
// distance H apart. Isotropic form finding must give the catenoid r(z) = c cosh(z/c) with
// R = c cosh(H/(2c)) (the larger root: the stable one). Beyond the Goldschmidt limit
// (H/R > 1.3255) no catenoid exists and the run must end with an error, not a shape.
// Prints neck_radius = <value> with the closed form and the relative error.
#include <petscsys.h>

#include <cmath>

#include "etfe/assembly.h"
#include "etfe/mesh/generators.h"
#include "etfe/mesh/mesh_options.h"
#include "etfe/scene_registry.h"

namespace etfe {

namespace {

struct CatenoidContext {
  double radius, separation;
};

// Larger root c of c cosh(a/c) = R, or -1 when there is none (beyond the Goldschmidt limit).
double CatenoidNeck(double R, double a) {
  // g(c) = c cosh(a/c) has its minimum at c* with (a/c*) tanh(a/c*) = 1, i.e. a/c* = 1.19968.
  double lo = a / 1.1996786402577338, hi = R;
  if (lo * std::cosh(a / lo) > R) return -1.0;
  if (hi * std::cosh(a / hi) < R) return -1.0;
  for (int k = 0; k < 200; ++k) {  // g increases on [c*, inf)
    const double mid = 0.5 * (lo + hi);
    (mid * std::cosh(a / mid) > R ? hi : lo) = mid;
  }
  return 0.5 * (lo + hi);
}

PetscErrorCode CatenoidReport(Problem *P, void *vctx) {
  auto *c = (CatenoidContext *)vctx;
  PetscFunctionBeginUser;
  std::vector<PetscInt> middle;
  PetscCall(ProblemNodeSetIds(P, "middle", &middle));
  double sum = 0.0;
  for (int n : middle) {
    double x[3];
    PetscCall(ProblemGetNodePosition(P, P->U, n, x));
    sum += std::hypot(x[0], x[1]);
  }
  const double neck = sum / middle.size();
  const double ref = CatenoidNeck(c->radius, 0.5 * c->separation);
  PetscCall(PetscPrintf(P->comm, "neck_radius = %.8e\n", neck));
  PetscCall(PetscPrintf(P->comm, "catenoid: ring radius %g mm, separation %g mm, closed_form = %.8e mm, relative_error = %.3e\n",
                        c->radius, c->separation, ref, std::fabs(neck - ref) / ref));
  PetscFunctionReturn(0);
}

} // namespace

PetscErrorCode SceneBuild_Catenoid(MPI_Comm comm, SceneSpec *scene, SceneObserver *observer) {
  PetscReal radius = 1000.0, separation = 1000.0;
  PetscFunctionBeginUser;
  PetscOptionsBegin(comm, nullptr, "Catenoid scene: film between two coaxial rings", "Scene");
  PetscCall(PetscOptionsReal("-catenoid_radius", "Ring radius R [mm]", "", radius, &radius, nullptr));
  PetscCall(PetscOptionsReal("-catenoid_separation", "Ring separation H [mm]", "", separation, &separation, nullptr));
  PetscOptionsEnd();
  MeshOptions mesh;
  mesh.keys = kMeshTube | kMeshRefine, mesh.ntheta = 48, mesh.nz = 16;
  PetscCall(MeshOptionsFromCommandLine(comm, "catenoid scene", &mesh));
  PetscInt ntheta = mesh.ntheta, nz = mesh.nz;
  const PetscInt refine = mesh.refine;
  PetscCheck(radius > 0 && separation > 0, comm, PETSC_ERR_ARG_OUTOFRANGE,
             "-catenoid_radius and -catenoid_separation must be positive");
  PetscCheck(ntheta >= 6 && nz >= 2 && nz % 2 == 0 && refine >= 0 && refine < 8, comm, PETSC_ERR_ARG_OUTOFRANGE,
             "catenoid: need -mesh_ntheta >= 6, an even -mesh_nz >= 2, 0 <= -mesh_refine < 8");
  PetscCheck(GeneratedTriangles(ntheta, nz, 2, refine) <= kMaxGeneratedTriangles, comm, PETSC_ERR_ARG_OUTOFRANGE,
             "-mesh_ntheta %" PetscInt_FMT " -mesh_nz %" PetscInt_FMT " -mesh_refine %" PetscInt_FMT ": %.3g triangles, "
             "more than the %.3g a generated mesh may have", ntheta, nz, refine, GeneratedTriangles(ntheta, nz, 2, refine),
             kMaxGeneratedTriangles);
  ntheta <<= refine;
  nz <<= refine;
  // Start from the cylinder spanning the rings; the rings stay where they are.
  if (SceneHoldsMesh(comm)) scene->mesh = MakeTubeMesh(radius, -0.5 * separation, separation, (int)ntheta, (int)nz);
  scene->AddSchedule({"boundary", 0.0, {1.0}});
  for (const char *set : {"bottom", "top"})
    for (int n : scene->mesh.node_sets[set])
      for (int c = 0; c < 3; ++c) scene->constraints.push_back({n, c, {}});
  auto *ctx = new CatenoidContext{radius, separation};
  observer->report = CatenoidReport;
  observer->ctx = ctx;
  observer->destroy = [](void *c) { delete (CatenoidContext *)c; };
  PetscFunctionReturn(0);
}

} // namespace etfe
