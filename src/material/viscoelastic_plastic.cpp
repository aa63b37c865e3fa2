// -material_type viscoelastic_plastic: the ETFE law with time (kernels/viscoelastic_plastic.h):
// a Prony-series relaxation spectrum on the elastic strain of the plastic law (-material_young is
// the instantaneous modulus E0, the yield curve the plastic law's), and an Arrhenius
// time-temperature shift: an increment of dt physical seconds is dt / a_T of reduced time with
//   a_T = exp(Ea/R (1/T - 1/T_ref))   (T, T_ref in kelvin; a_T < 1 above T_ref: faster relaxation).
// The history (plastic state, the instantaneous elastic stress and each branch's internal stress)
// lives in the element history arrays, so checkpoints carry it. -material_strain_measure picks the
// measures the numbers are in: Green-Lagrange/PK2 (the plastic law's) or engineering (Biot), the
// measures of a uniaxial lab curve (kernels/viscoelastic_plastic.h).
#include <petscsys.h>

#include <cmath>
#include <cstring>
#include <string>

#include "etfe/assembly/input_plausibility.h"
#include "etfe/kernels/viscoelastic_plastic.h"
#include "material_internal.h"

namespace etfe {

namespace {

constexpr double kGasConstant = 8.31446261815324;  // J/(mol K)
constexpr double kZeroCelsius = 273.15;            // K

class ViscoelasticPlasticLaw : public Material {
public:
  ViscoelasticPlasticMaterial m{};
  double ea = 0.0, temperature = 20.0, reference_temperature = 20.0;  // kJ/mol, deg C
  double shift = 1.0;    // a_T
  double seconds = 0.0;  // physical seconds of the increment being solved

  const char *Name() const override { return "viscoelastic_plastic"; }
  void ElasticConstants(double *e, double *n) const override { *e = m.plastic.young, *n = m.plastic.nu; }
  int HistorySize() const override { return ViscoelasticPlasticHistorySize(m.nterms); }
  void InitHistory(double *h) const override {
    for (int k = 0; k < HistorySize(); ++k) h[k] = 0.0;
  }
  void SetIncrementSeconds(double s) override { seconds = s; }
  int Evaluate(const double E[3], const double *hold, double *hnew, double S[3], double D[9]) const override {
    return ViscoelasticPlasticUpdate(m, seconds / shift, E, hold, hnew, S, D);
  }
  bool HasPlasticStrain() const override { return true; }
  // The yield curve (reports of the yield stress). The tension-field wrapper's plastic wrinkling
  // would drop the relaxation, so CreateViscoelasticPlastic's caller refuses that combination.
  const PlasticMaterial *PlasticLaw() const override { return &m.plastic; }
  bool PlasticStrain(const double *h, double ep[3], double *ep_bar) const override {
    ep[0] = h[0], ep[1] = h[1], ep[2] = h[2];
    *ep_bar = h[3];
    return true;
  }
  PetscErrorCode View(MPI_Comm comm) const override {
    PetscFunctionBeginUser;
    PetscCall(PetscPrintf(comm,
                          "  material: viscoelastic_plastic (Prony series on the elastic strain, %d terms; plane-stress "
                          "von Mises, %d hardening segments; %s), E0 = %g MPa, relaxed %g MPa, nu = %g\n",
                          m.nterms, m.plastic.nseg,
                          m.measure == kMeasureBiot ? "engineering measures: Biot strain and stress"
                                                    : "Green-Lagrange strain, PK2 stress",
                          m.plastic.young,
                          m.plastic.young * ViscoelasticPlasticRelaxationFraction(m, HUGE_VAL), m.plastic.nu));
    for (int k = 0; k < m.plastic.nseg; ++k)
      PetscCall(PetscPrintf(comm, "    segment %d: yield %g MPa, plastic modulus %g MPa\n", k, m.plastic.yield[k],
                            m.plastic.H[k]));
    for (int i = 0; i < m.nterms; ++i)
      PetscCall(PetscPrintf(comm, "    branch %d: tau %g s, g %g\n", i, m.tau[i], m.g[i]));
    PetscCall(PetscPrintf(comm,
                          "    temperature %g C, reference %g C, Ea %g kJ/mol: shift factor a_T = %g; E(t)/E0 at 1 s "
                          "%.4f, 1 h %.4f, 10 h %.4f\n",
                          temperature, reference_temperature, ea, shift,
                          ViscoelasticPlasticRelaxationFraction(m, 1.0 / shift),
                          ViscoelasticPlasticRelaxationFraction(m, 3600.0 / shift),
                          ViscoelasticPlasticRelaxationFraction(m, 36000.0 / shift)));
    PetscFunctionReturn(0);
  }
};

// -material_prony_tau / -material_prony_g, checked by name.
PetscErrorCode ReadSpectrum(const char *pre, ViscoelasticPlasticMaterial *m) {
  PetscReal tau[kMaxPronyTerms] = {0.0}, g[kMaxPronyTerms] = {0.0};
  PetscInt nt = 0, ng = 0;
  PetscFunctionBeginUser;
  const char *measures[] = {"green_lagrange", "engineering"};
  PetscInt measure = m->measure;
  for (int pass = 0; pass < MaterialPasses(pre); ++pass) {
    PetscOptionsBegin(PETSC_COMM_WORLD, MaterialPassPrefix(pre, pass), "Viscoelastic-plastic material", "Material");
    PetscCall(PetscOptionsEList("-material_strain_measure",
                                "Strain and stress the law's numbers are in: green_lagrange (Green-Lagrange strain, PK2 "
                                "stress, as the plastic law) or engineering (Biot strain U - I and its conjugate stress: "
                                "uniaxially the engineering strain and nominal stress of a lab curve, for parameters "
                                "fitted to one)",
                                "", measures, 2, measures[measure], &measure, nullptr));
    PetscCall(MaterialPassRealArray(PetscOptionsObject, "-material_prony_tau",
                                    "Relaxation times of the Maxwell branches [s at the reference temperature], "
                                    "increasing (none: the plastic law)",
                                    tau, &nt));
    PetscCall(MaterialPassRealArray(PetscOptionsObject, "-material_prony_g",
                                    "Moduli of the Maxwell branches as fractions of -material_young (the instantaneous "
                                    "modulus E0); E(t) = E0 (1 - sum g_i (1 - exp(-t/tau_i)))",
                                    g, &ng));
    PetscOptionsEnd();
  }
  m->measure = measure == 1 ? kMeasureBiot : kMeasureGreenLagrange;
  const char *p = MaterialPre(pre);
  PetscCheck(nt == ng, PETSC_COMM_WORLD, PETSC_ERR_ARG_SIZ,
             "-%smaterial_prony_tau has %" PetscInt_FMT " values but -%smaterial_prony_g has %" PetscInt_FMT
             "; give one modulus fraction per relaxation time",
             p, nt, p, ng);
  double sum = 0.0;
  for (PetscInt i = 0; i < nt; ++i) {
    PetscCheck(tau[i] > 0 && std::isfinite(tau[i]), PETSC_COMM_WORLD, PETSC_ERR_ARG_OUTOFRANGE,
               "-%smaterial_prony_tau: relaxation time %" PetscInt_FMT " is %g s; relaxation times must be > 0", p, i + 1,
               (double)tau[i]);
    PetscCheck(i == 0 || tau[i] > tau[i - 1], PETSC_COMM_WORLD, PETSC_ERR_ARG_OUTOFRANGE,
               "-%smaterial_prony_tau: the spectrum is not sorted (%g s after %g s); list the relaxation times "
               "increasing, -%smaterial_prony_g in the same order",
               p, (double)tau[i], (double)tau[i - 1], p);
    PetscCheck(g[i] > 0 && std::isfinite(g[i]), PETSC_COMM_WORLD, PETSC_ERR_ARG_OUTOFRANGE,
               "-%smaterial_prony_g: modulus fraction %" PetscInt_FMT " is %g; a branch's modulus must be > 0", p,
               i + 1, (double)g[i]);
    sum += g[i];
    m->tau[i] = tau[i], m->g[i] = g[i];
  }
  PetscCheck(sum < 1.0, PETSC_COMM_WORLD, PETSC_ERR_ARG_OUTOFRANGE,
             "-%smaterial_prony_g sums to %g: the fractions must sum to < 1 (1 - sum is the relaxed modulus's)", p,
             sum);
  m->nterms = (int)nt;
  PetscFunctionReturn(0);
}

// -material_ea, -material_temperature, -material_reference_temperature: the shift factor.
PetscErrorCode ReadTemperatureShift(const char *pre, ViscoelasticPlasticLaw *law) {
  PetscBool temperature_set = PETSC_FALSE;
  PetscFunctionBeginUser;
  for (int pass = 0; pass < MaterialPasses(pre); ++pass) {
    PetscBool set = PETSC_FALSE;
    PetscOptionsBegin(PETSC_COMM_WORLD, MaterialPassPrefix(pre, pass), "Viscoelastic-plastic material: temperature",
                      "Material");
    PetscCall(PetscOptionsReal("-material_ea",
                               "Activation energy of the Arrhenius time-temperature shift [kJ/mol] (0: no shift)", "",
                               law->ea, &law->ea, nullptr));
    PetscCall(PetscOptionsReal("-material_reference_temperature",
                               "Temperature the relaxation times are given at [deg C]", "", law->reference_temperature,
                               &law->reference_temperature, nullptr));
    // The temperature defaults to the reference: a group's own reference moves it unless a
    // temperature was given (the film's or the group's).
    if (!temperature_set) law->temperature = law->reference_temperature;
    PetscCall(PetscOptionsReal("-material_temperature", "Temperature of the film [deg C] (default: the reference)", "",
                               law->temperature, &law->temperature, &set));
    PetscOptionsEnd();
    temperature_set = (PetscBool)(temperature_set || set);
  }
  const char *p = MaterialPre(pre);
  const std::string t_opt = std::string("-") + p + "material_temperature";
  const std::string tref_opt = std::string("-") + p + "material_reference_temperature";
  // PETSc reads "inf" as a number: an infinite temperature would give a_T = 0 (the film fully
  // relaxed at once) without a word. Then the range: a value in K, or past the melting point.
  PetscCheck(std::isfinite(law->reference_temperature), PETSC_COMM_WORLD, PETSC_ERR_ARG_OUTOFRANGE,
             "-%smaterial_reference_temperature %s: not a finite number; give the temperature in deg C", p,
             std::isnan(law->reference_temperature) ? "nan" : "inf");
  PetscCheck(std::isfinite(law->temperature), PETSC_COMM_WORLD, PETSC_ERR_ARG_OUTOFRANGE,
             "-%smaterial_temperature %s: not a finite number; give the temperature in deg C (default: the reference, "
             "-%smaterial_reference_temperature)",
             p, std::isnan(law->temperature) ? "nan" : "inf", p);
  PetscCheck(law->reference_temperature > -kZeroCelsius, PETSC_COMM_WORLD, PETSC_ERR_ARG_OUTOFRANGE,
             "-%smaterial_reference_temperature %g C is below absolute zero (-273.15 C)", p,
             law->reference_temperature);
  PetscCheck(law->temperature > -kZeroCelsius, PETSC_COMM_WORLD, PETSC_ERR_ARG_OUTOFRANGE,
             "-%smaterial_temperature %g C is below absolute zero (-273.15 C)", p, law->temperature);
  PetscCall(ReportPlausibility(PETSC_COMM_WORLD, CheckTemperature(t_opt.c_str(), law->temperature)));
  PetscCall(ReportPlausibility(PETSC_COMM_WORLD,
                               CheckTemperature(tref_opt.c_str(), law->reference_temperature)));
  PetscCheck(law->ea >= 0 && std::isfinite(law->ea), PETSC_COMM_WORLD, PETSC_ERR_ARG_OUTOFRANGE,
             "-%smaterial_ea %g kJ/mol: the activation energy must be >= 0", p, law->ea);
  const double T = law->temperature + kZeroCelsius, Tref = law->reference_temperature + kZeroCelsius;
  law->shift = std::exp(1e3 * law->ea / kGasConstant * (1.0 / T - 1.0 / Tref));
  PetscCheck(std::isfinite(law->shift) && law->shift > 0, PETSC_COMM_WORLD, PETSC_ERR_ARG_OUTOFRANGE,
             "-%smaterial_ea %g kJ/mol at -%smaterial_temperature %g C (reference %g C): the shift factor a_T = %g "
             "is out of range",
             p, law->ea, p, law->temperature, law->reference_temperature, law->shift);
  PetscFunctionReturn(0);
}

} // namespace

PetscErrorCode CreateViscoelasticPlastic(const char *pre, std::unique_ptr<Material> *out) {
  auto law = std::make_unique<ViscoelasticPlasticLaw>();
  PetscFunctionBeginUser;
  PetscCall(ReadPlasticMaterial(pre, &law->m.plastic));
  PetscCall(ReadSpectrum(pre, &law->m));
  PetscCall(ReadTemperatureShift(pre, law.get()));
  char msg[256] = "";
  PetscCheck(ViscoelasticPlasticMaterialCheck(law->m, msg, sizeof msg) == 0, PETSC_COMM_WORLD,
             PETSC_ERR_ARG_OUTOFRANGE, "viscoelastic_plastic material: %s (options -%smaterial_*)", msg,
             MaterialPre(pre));
  *out = std::move(law);
  PetscFunctionReturn(0);
}

} // namespace etfe
