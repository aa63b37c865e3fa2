// The reports of the general scene's checks (-structure_check, structure_checks.cpp picks one):
// each prints what a verification case or a lab test gives against its closed form
// (src/verification/), after the structure report (the strip also per increment).
#include <petscsys.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "etfe/assembly/assembly.h"
#include "etfe/base/csv_history.h"
#include "etfe/verification/annulus_closed_form.h"
#include "etfe/verification/hencky_closed_form.h"
#include "etfe/verification/patch_closed_form.h"
#include "saddle_geometry.h"
#include "structure_inputs.h"

namespace etfe {

// Hencky (docs/theory.md §13): the centre deflection and the centre stress (mean of (Sxx + Syy)/2 over the
// elements touching the centre node) against the Foppl closed form.
PetscErrorCode HenckyCheck(Problem *P, const CheckInput &ck, std::vector<double> *) {
  double young, nu, u[3];
  HenckyCoefficients c;
  CellFields cells;
  PetscInt centre;
  PetscFunctionBeginUser;
  P->material->ElasticConstants(&young, &nu);
  PetscCheck(HenckyCoefficientsCompute(nu, &c) == 0, P->comm, PETSC_ERR_LIB,
             "Hencky closed form: no solution for nu = %g", nu);
  const double a = ck.radius, p = ck.pressure, h = P->thickness;
  const double w_ref = c.deflection * a * std::cbrt(p * a / (young * h));
  const double s_ref = c.centre_stress * std::cbrt(young * p * p * a * a / (h * h));
  PetscCall(ProblemNearestNode(P, 0.0, 0.0, &centre));
  PetscCall(ProblemGetNodeDisplacement(P, P->U, centre, u));
  PetscCall(ComputeCellFields(P, P->U, &cells, false));
  double sum[2] = {0, 0}, tot[2];
  for (PetscInt e = 0; e < P->mesh.num_elements; ++e) {
    const int *t = &P->mesh.tri[3 * e];
    bool at_centre = false;
    for (int k = 0; k < 3; ++k) at_centre |= P->mesh.natural_id[t[k]] == centre;
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

// Stretch in Y that makes Eyy = -Exx (pure shear in the principal axes).
static double PureShearStretchY(double lx) { return std::sqrt(std::max(0.0, 2.0 - lx * lx)); }

// The patch test: every element carries the same stress; elastic, the plane-stress Hooke value.
PetscErrorCode PatchCheck(Problem *P, const CheckInput &ck, std::vector<double> *) {
  CellFields c;
  PetscFunctionBeginUser;
  PetscCall(ComputeCellFields(P, P->U, &c, false));
  double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300}, glo[3], ghi[3];
  for (PetscInt e = 0; e < P->mesh.num_elements; ++e)
    for (int i = 0; i < 3; ++i) {
      lo[i] = std::min(lo[i], c.stress[3 * e + i]);
      hi[i] = std::max(hi[i], c.stress[3 * e + i]);
    }
  PetscCallMPI(MPI_Allreduce(lo, glo, 3, MPI_DOUBLE, MPI_MIN, P->comm));
  PetscCallMPI(MPI_Allreduce(hi, ghi, 3, MPI_DOUBLE, MPI_MAX, P->comm));
  const double scale = std::max({std::fabs(ghi[0]), std::fabs(ghi[1]), std::fabs(glo[0]), std::fabs(glo[1]), 1e-30});
  const double spread = std::max({ghi[0] - glo[0], ghi[1] - glo[1], ghi[2] - glo[2]}) / scale;
  PetscCall(PetscPrintf(P->comm,
                        "patch: Sxx in [%.10e, %.10e], Syy in [%.10e, %.10e], Sxy in [%.3e, %.3e] MPa\n"
                        "patch: stress_spread = %.3e (max - min over elements, relative)\n",
                        glo[0], ghi[0], glo[1], ghi[1], glo[2], ghi[2], spread));
  if (std::string(P->material->Name()) == "elastic" && ck.mode != "shear") {
    double young, nu, S[2];
    P->material->ElasticConstants(&young, &nu);
    const double lx = 1.0 + ck.ex * ck.factor;
    const double Exx = 0.5 * (lx * lx - 1.0);
    double Eyy = 0.0;
    if (ck.mode != "uniaxial") {
      const double ly = ck.mode == "biaxial" ? 1.0 + ck.ey * ck.factor : PureShearStretchY(lx);
      Eyy = 0.5 * (ly * ly - 1.0);
    }
    PatchClosedFormStress(young, nu, Exx, Eyy, ck.mode == "uniaxial", S);
    const double err = std::max(std::fabs(ghi[0] - S[0]), std::fabs(glo[0] - S[0])) / std::fabs(S[0]);
    PetscCall(PetscPrintf(P->comm, "patch: closed_form Sxx = %.10e Syy = %.10e, relative_error = %.3e\n", S[0], S[1],
                          err));
  }
  PetscFunctionReturn(0);
}

// The annulus (Stein & Hedgepeth 1961, Mikulas 1964): the wrinkled zone's area-equivalent radius
// R = sqrt(a^2 + A_w/pi) (A_w the reference area of the wrinkled elements) and the torque of the
// hub's reactions against the tension-field closed form; the hub's rotation is the control, so
// the closed form's rotation is taken at the film's torque and its torque at the rotation.
PetscErrorCode AnnulusCheck(Problem *P, const CheckInput &ck, std::vector<double> *) {
  CellFields f;
  const PetscScalar *r, *u;
  double young, nu;
  std::vector<char> is_hub;
  PetscFunctionBeginUser;
  P->material->ElasticConstants(&young, &nu);
  PetscCall(ProblemNodeSetFlags(P, "hub", &is_hub));
  PetscCall(ComputeCellFields(P, P->U, &f, false));
  // [0] wrinkled area, [1] slack area, [2] torque of the hub reactions about the axis.
  double loc[3] = {0, 0, 0}, glob[3];
  for (PetscInt e = 0; e < P->mesh.num_elements; ++e) {
    // Without the tension field the flag is the compressive minor principal stress.
    const int state = f.wrinkle_state.empty() ? (f.smin[e] < 0 ? 1 : 0) : (int)f.wrinkle_state[e];
    if (state == 1) loc[0] += P->mesh.ref[e].area;
    if (state == 2) loc[1] += P->mesh.ref[e].area;
  }
  PetscCall(VecGetArrayRead(P->reaction, &r));
  PetscCall(VecGetArrayRead(P->U, &u));
  for (PetscInt l = 0; l < P->mesh.num_owned; ++l) {
    if (!is_hub[l]) continue;
    const double x = P->mesh.X[3 * l] + u[3 * l], y = P->mesh.X[3 * l + 1] + u[3 * l + 1];
    loc[2] += x * r[3 * l + 1] - y * r[3 * l];
  }
  PetscCall(VecRestoreArrayRead(P->U, &u));
  PetscCall(VecRestoreArrayRead(P->reaction, &r));
  PetscCallMPI(MPI_Allreduce(loc, glob, 3, MPI_DOUBLE, MPI_SUM, P->comm));
  const double pi = std::acos(-1.0), t = P->thickness;
  const double R = std::sqrt(ck.a * ck.a + glob[0] / pi), torque = std::fabs(glob[2]);
  AnnulusTorsion p{ck.a, ck.b, young, nu, ck.eps0};
  AnnulusTorsionResult at_phi, at_torque;
  const int s1 = AnnulusStateAtRotation(p, ck.phi, &at_phi);
  const int s2 = AnnulusStateAtTorque(p, torque / (2 * pi * t), &at_torque);
  PetscCheck(s1 == 0 && s2 == 0, P->comm, PETSC_ERR_ARG_OUTOFRANGE,
             "annulus closed form: no partly wrinkled state at the hub rotation %g (torque %g N mm); lower the "
             "rotation", ck.phi, torque);
  const double M_cf = 2 * pi * t * at_phi.C;
  PetscCall(PetscPrintf(P->comm,
                        "annulus: pretension sigma0 = %.6e MPa, onset rotation %.6e rad; wrinkled area %.6e mm^2, "
                        "slack area %.6e mm^2%s\n"
                        "annulus: wrinkle_radius = %.6e mm, closed_form = %.6e mm, relative_error = %.3e\n"
                        "annulus: hub_rotation = %.6e rad, closed_form = %.6e rad, relative_error = %.3e "
                        "(closed form at the film's torque)\n"
                        "annulus: torque = %.6e N mm, closed_form = %.6e N mm, relative_error = %.3e\n",
                        young * ck.eps0 / (1 - nu), AnnulusOnsetRotation(p), glob[0], glob[1],
                        f.wrinkle_state.empty() ? " (no tension field: compressed elements counted)" : "",
                        R, at_phi.wrinkle_radius, std::fabs(R - at_phi.wrinkle_radius) / at_phi.wrinkle_radius,
                        ck.phi, at_torque.phi, std::fabs(ck.phi - at_torque.phi) / at_torque.phi, torque, M_cf,
                        std::fabs(torque - M_cf) / M_cf));
  PetscFunctionReturn(0);
}

// The strip lab test (relaxation or creep of a homogeneous strip): its state as the elements'
// mean, GL strain Exx and PK2 Sxx, and from them the engineering strain and the nominal (force
// per reference area) stress.
static PetscErrorCode MeasureStrip(Problem *P, double *E, double *S, double *e_eng, double *s_nom) {
  CellFields c;
  double loc[3] = {0.0, 0.0, 0.0}, glob[3];
  PetscFunctionBeginUser;
  PetscCall(ComputeCellFields(P, P->U, &c, false));
  for (PetscInt e = 0; e < P->mesh.num_elements; ++e) {
    loc[0] += c.strain[3 * e], loc[1] += c.stress[3 * e];
    loc[2] += 1.0;
  }
  PetscCallMPI(MPI_Allreduce(loc, glob, 3, MPI_DOUBLE, MPI_SUM, P->comm));
  *E = glob[0] / glob[2], *S = glob[1] / glob[2];
  const double stretch = std::sqrt(1.0 + 2.0 * *E);
  *e_eng = stretch - 1.0, *s_nom = stretch * *S;
  PetscFunctionReturn(0);
}

// Each increment: time, strain and stress to <results>_strip.csv (or the given path) and, at the
// monitor's rate, a line.
PetscErrorCode StripStep(Problem *P, const CheckInput &ck, std::vector<double> *, PetscInt step, double t,
                         PetscInt print_every) {
  double E, S, e, s;
  PetscFunctionBeginUser;
  PetscCall(MeasureStrip(P, &E, &S, &e, &s));
  const double seconds = P->clock.Seconds(t);
  if (print_every > 0 && step % print_every == 0)
    PetscCall(PetscPrintf(P->comm, "strip: %s  time %.6g s  strain %.6e  stress %.6e MPa (nominal %.6e)\n",
                          ck.test.c_str(), seconds, e, S, s));
  const std::string path = CsvHistoryPath(ck.history, P->observer.results_stem, "_strip.csv");
  if (path.empty() || P->rank != 0) PetscFunctionReturn(0);
  FILE *out = CsvHistoryOpen(path, step, "step,load_time,seconds,strain_gl,strain,stress_pk2,stress_nominal");
  PetscCheck(out, PETSC_COMM_SELF, PETSC_ERR_FILE_OPEN, "strip: cannot write %s", path.c_str());
  std::fprintf(out, "%lld,%.10g,%.10g,%.12e,%.12e,%.12e,%.12e\n", (long long)step, t, seconds, E, e, S, s);
  std::fclose(out);
  PetscFunctionReturn(0);
}

PetscErrorCode StripReport(Problem *P, const CheckInput &ck, std::vector<double> *) {
  double E, S, e, s;
  PetscFunctionBeginUser;
  PetscCall(MeasureStrip(P, &E, &S, &e, &s));
  PetscCall(PetscPrintf(P->comm, "strip: %s at the end (%.6g s): strain %.9e, stress %.9e MPa (nominal %.9e)\n",
                        ck.test.c_str(), P->clock.Seconds(P->time), e, S, s));
  PetscFunctionReturn(0);
}

// Larger root c of c cosh(a/c) = R, or -1 when there is none (beyond the Goldschmidt limit).
static double CatenoidNeck(double R, double a) {
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

// The catenoid (a check of form finding): a film between two coaxial rings of radius R a distance
// H apart must find r(z) = c cosh(z/c) with R = c cosh(H/(2c)) (the larger root: the stable one).
// The neck radius is the mean radius of the ring of nodes half way (node group middle).
PetscErrorCode CatenoidCheck(Problem *P, const CheckInput &ck, std::vector<double> *) {
  std::vector<PetscInt> middle;
  PetscFunctionBeginUser;
  PetscCall(ProblemNodeSetIds(P, "middle", &middle));
  double sum = 0.0;
  for (PetscInt n : middle) {
    double x[3];
    PetscCall(ProblemGetNodePosition(P, P->U, n, x));
    sum += std::hypot(x[0], x[1]);
  }
  const double neck = sum / middle.size();
  const double ref = CatenoidNeck(ck.ring_radius, 0.5 * ck.separation);
  PetscCall(PetscPrintf(P->comm, "neck_radius = %.8e\n", neck));
  PetscCall(PetscPrintf(P->comm,
                        "catenoid: ring radius %g mm, separation %g mm, closed_form = %.8e mm, relative_error = %.3e\n",
                        ck.ring_radius, ck.separation, ref, std::fabs(neck - ref) / ref));
  PetscFunctionReturn(0);
}

// The thesis's saddle (quarter model, saddle_geometry.h): h1, h2, the middle part's sag and
// curvature and the middle cutting line of the surface found.
PetscErrorCode SaddleCheck(Problem *P, const CheckInput &ck, std::vector<double> *) {
  SaddleGeometry g;
  SaddleShapeNodes n;
  PetscFunctionBeginUser;
  g.rise = ck.rise;
  PetscCall(SaddleShapeNodesFind(P, g, &n));
  PetscCall(SaddleShapeReport(P, g, n, false));
  PetscFunctionReturn(0);
}

} // namespace etfe
