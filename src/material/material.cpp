// Material registry (-material_type) and the two laws: plane-stress St. Venant-Kirchhoff and the
// ETFE elasto-plastic law (docs/theory.md §3.2); the viscoelastic-plastic law is in
// viscoelastic_plastic.cpp. Parameters come from -material_* options, or for a surface group's own
// law from -film_<group>_material_* over them (material_internal.h).
#include <petscsys.h>

#include <algorithm>
#include <cstring>
#include <string>

#include "etfe/kernels/elastic.h"
#include "etfe/kernels/plasticity.h"
#include "etfe/kernels/status.h"
#include "etfe/material/material.h"
#include "material_internal.h"

namespace etfe {

namespace {

PetscFunctionList material_list = nullptr;

class ElasticMaterial : public Material {
public:
  double young = 800.0, nu = 0.43;
  const char *Name() const override { return "elastic"; }
  void ElasticConstants(double *e, double *n) const override { *e = young, *n = nu; }
  int Evaluate(const double E[3], const double *, double *, double S[3],
               double D[9]) const override {
    ElasticPlaneStress(young, nu, E, S, D);
    return KERNEL_OK;
  }
  PetscErrorCode View(MPI_Comm comm) const override {
    PetscFunctionBeginUser;
    PetscCall(PetscPrintf(comm, "  material: elastic (plane-stress St. Venant-Kirchhoff), E = %g MPa, nu = %g\n",
                          young, nu));
    PetscFunctionReturn(0);
  }
};

class PlasticMaterialLaw : public Material {
public:
  PlasticMaterial m{};
  const char *Name() const override { return "plastic"; }
  void ElasticConstants(double *e, double *n) const override { *e = m.young, *n = m.nu; }
  int HistorySize() const override { return 4; }
  void InitHistory(double *h) const override { h[0] = h[1] = h[2] = h[3] = 0.0; }
  int Evaluate(const double E[3], const double *hold, double *hnew, double S[3],
               double D[9]) const override {
    PlasticState committed, trial;
    std::memcpy(&committed, hold, sizeof committed);
    int st = PlasticReturnMap(m, E, committed, &trial, S, D);
    if (hnew) std::memcpy(hnew, &trial, sizeof trial);
    return st;
  }
  bool HasPlasticStrain() const override { return true; }
  const PlasticMaterial *PlasticLaw() const override { return &m; }
  bool PlasticStrain(const double *h, double ep[3], double *ep_bar) const override {
    ep[0] = h[0], ep[1] = h[1], ep[2] = h[2];
    *ep_bar = h[3];
    return true;
  }
  PetscErrorCode View(MPI_Comm comm) const override {
    PetscFunctionBeginUser;
    PetscCall(PetscPrintf(comm, "  material: plastic (plane-stress von Mises, %d hardening segments), E = %g MPa, nu = %g\n",
                          m.nseg, m.young, m.nu));
    for (int k = 0; k < m.nseg; ++k)
      PetscCall(PetscPrintf(comm, "    segment %d: yield %g MPa, plastic modulus %g MPa\n", k,
                            m.yield[k], m.H[k]));
    PetscFunctionReturn(0);
  }
};

// The prescribed stress lives in the element's "history" (S_MD, S_TD) so that parts of a
// surface may carry different ratios (the saddle: middle 1:1, corners 3:1).
class PrescribedStressMaterial : public Material {
public:
  double s_md, s_td;
  PrescribedStressMaterial(double md, double td) : s_md(md), s_td(td) {}
  const char *Name() const override { return "prescribed_stress"; }
  int HistorySize() const override { return 2; }
  void InitHistory(double *h) const override { h[0] = s_md, h[1] = s_td; }
  // There is no elastic law; the stress level stands in where a stiffness scale is needed.
  void ElasticConstants(double *e, double *n) const override { *e = std::max(s_md, s_td), *n = 0.0; }
  int Evaluate(const double *, const double *hold, double *hnew, double S[3], double D[9]) const override {
    S[0] = hold[0], S[1] = hold[1], S[2] = 0.0;
    if (hnew) hnew[0] = hold[0], hnew[1] = hold[1];
    for (int k = 0; k < 9; ++k) D[k] = 0.0;
    return KERNEL_OK;
  }
  PetscErrorCode View(MPI_Comm comm) const override {
    PetscFunctionBeginUser;
    PetscCall(PetscPrintf(comm, "  material: prescribed stress (form finding), S_MD = %g MPa, S_TD = %g MPa\n",
                          s_md, s_td));
    PetscFunctionReturn(0);
  }
};

PetscErrorCode ReadElasticConstants(const char *pre, double *young, double *nu) {
  PetscFunctionBeginUser;
  for (int pass = 0; pass < MaterialPasses(pre); ++pass) {
    PetscOptionsBegin(PETSC_COMM_WORLD, MaterialPassPrefix(pre, pass), "Material: elastic constants", "Material");
    PetscCall(PetscOptionsReal("-material_young", "Young's modulus [MPa]", "", *young, young, nullptr));
    PetscCall(PetscOptionsReal("-material_poisson", "Poisson's ratio", "", *nu, nu, nullptr));
    PetscOptionsEnd();
  }
  PetscCheck(*young > 0, PETSC_COMM_WORLD, PETSC_ERR_ARG_OUTOFRANGE,
             "-%smaterial_young %g: Young's modulus must be positive (MPa)", MaterialPre(pre), *young);
  PetscCheck(*nu > -1.0 && *nu < 0.5, PETSC_COMM_WORLD, PETSC_ERR_ARG_OUTOFRANGE,
             "-%smaterial_poisson %g: Poisson's ratio must lie in (-1, 0.5)", MaterialPre(pre), *nu);
  PetscFunctionReturn(0);
}

PetscErrorCode CreateElastic(const char *pre, std::unique_ptr<Material> *out) {
  auto mat = std::make_unique<ElasticMaterial>();
  PetscFunctionBeginUser;
  PetscCall(ReadElasticConstants(pre, &mat->young, &mat->nu));
  *out = std::move(mat);
  PetscFunctionReturn(0);
}

PetscErrorCode CreatePlastic(const char *pre, std::unique_ptr<Material> *out) {
  auto mat = std::make_unique<PlasticMaterialLaw>();
  PetscFunctionBeginUser;
  PetscCall(ReadPlasticMaterial(pre, &mat->m));
  *out = std::move(mat);
  PetscFunctionReturn(0);
}

} // namespace

PetscErrorCode ReadPlasticMaterial(const char *pre, PlasticMaterial *mp) {
  PlasticMaterial &m = *mp;
  PetscFunctionBeginUser;
  m.young = 800.0;
  m.nu = 0.43;
  PetscCall(ReadElasticConstants(pre, &m.young, &m.nu));
  // Thesis Table 4.2 (case 1): first yield 13.28 MPa with H' = 80.5, second 23.04 with H' = 3.
  PetscReal yield[kMaxHardeningSegments] = {13.28, 23.04}, H[kMaxHardeningSegments] = {80.5, 3.0};
  PetscInt ny = 2, nH = 2;
  for (int pass = 0; pass < MaterialPasses(pre); ++pass) {
    PetscOptionsBegin(PETSC_COMM_WORLD, MaterialPassPrefix(pre, pass), "Plastic material", "Material");
    PetscCall(MaterialPassRealArray(PetscOptionsObject, "-material_yield",
                                    "Yield stresses where the hardening segments start [MPa, 2nd Piola-Kirchhoff] "
                                    "(default 13.28,23.04: thesis Table 4.2, case 1)",
                                    yield, &ny));
    PetscCall(MaterialPassRealArray(PetscOptionsObject, "-material_hardening",
                                    "Plastic modulus H' of each segment [MPa] (default 80.5,3.0)", H, &nH));
    PetscOptionsEnd();
  }
  PetscCheck(ny == nH && ny >= 1, PETSC_COMM_WORLD, PETSC_ERR_ARG_SIZ,
             "-%smaterial_yield has %" PetscInt_FMT " values but -%smaterial_hardening has %" PetscInt_FMT
             "; give one plastic modulus per yield stress",
             MaterialPre(pre), ny, MaterialPre(pre), nH);
  m.nseg = (int)ny;
  for (int k = 0; k < m.nseg; ++k) m.yield[k] = yield[k], m.H[k] = H[k];
  char msg[256] = "";
  PetscCheck(PlasticMaterialCheck(m, msg, sizeof msg) == 0, PETSC_COMM_WORLD,
             PETSC_ERR_ARG_OUTOFRANGE, "plastic material: %s (options -%smaterial_*)", msg, MaterialPre(pre));
  PetscFunctionReturn(0);
}

std::unique_ptr<Material> MaterialCreatePrescribedStress(double s_md, double s_td) {
  return std::make_unique<PrescribedStressMaterial>(s_md, s_td);
}

PetscErrorCode MaterialRegisterAll(void) {
  PetscFunctionBeginUser;
  if (material_list) PetscFunctionReturn(0);
  PetscCall(PetscFunctionListAdd(&material_list, "elastic", CreateElastic));
  PetscCall(PetscFunctionListAdd(&material_list, "plastic", CreatePlastic));
  PetscCall(PetscFunctionListAdd(&material_list, "viscoelastic_plastic", CreateViscoelasticPlastic));
  PetscFunctionReturn(0);
}

PetscErrorCode MaterialCreateFromOptions(MPI_Comm comm, std::unique_ptr<Material> *material, const char *prefix) {
  char type[64] = "elastic";
  PetscBool set;
  MaterialCreator create = nullptr;
  PetscFunctionBeginUser;
  PetscCall(MaterialRegisterAll());
  for (int pass = 0; pass < MaterialPasses(prefix); ++pass) {
    PetscOptionsBegin(comm, MaterialPassPrefix(prefix, pass), "Material", "Material");
    PetscCall(PetscOptionsFList("-material_type", "Constitutive law", "", material_list, type, type,
                                sizeof type, &set));
    PetscOptionsEnd();
  }
  PetscCall(PetscFunctionListFind(material_list, type, &create));
  PetscCheck(create, comm, PETSC_ERR_ARG_UNKNOWN_TYPE,
             "-%smaterial_type %s is unknown; the registered laws are: elastic, plastic, viscoelastic_plastic",
             MaterialPre(prefix), type);
  PetscCall(create(prefix, material));
  PetscFunctionReturn(0);
}

PetscErrorCode MaterialOptionsGiven(MPI_Comm comm, const char *prefix, PetscBool *given) {
  // Every -material_* option a law reads (material.cpp, viscoelastic_plastic.cpp).
  static const char *const keys[] = {"type",        "young", "poisson",     "yield",
                                     "hardening",   "strain_measure",       "prony_tau",
                                     "prony_g",     "ea",    "temperature", "reference_temperature"};
  PetscFunctionBeginUser;
  *given = PETSC_FALSE;
  for (const char *k : keys) {
    PetscBool has = PETSC_FALSE;
    PetscCall(PetscOptionsHasName(nullptr, prefix, (std::string("-material_") + k).c_str(), &has));
    if (has) *given = PETSC_TRUE;
  }
  PetscFunctionReturn(0);
}

} // namespace etfe
