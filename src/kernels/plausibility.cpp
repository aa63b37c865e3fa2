// Plausibility of inputs (etfe/kernels/plausibility.h): thresholds there, messages here.
#include "etfe/kernels/plausibility.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace etfe {

namespace {

using namespace plausible;

struct Reading {
  double factor;     // the value times this is the value in the project's unit
  const char *unit;  // the unit the value was then given in
};

std::string Num(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

// " did you mean X (the value in <unit>)?" for the first reading that lands in [lo, hi], else "".
std::string Intent(double value, double lo, double hi, std::initializer_list<Reading> readings) {
  for (const Reading &r : readings) {
    const double v = value * r.factor;
    if (v >= lo && v <= hi) return " Did you mean " + Num(v) + " (the value in " + r.unit + ")?";
  }
  return "";
}

PlausibilityCheck Verdict(Plausibility level, const std::string &message) {
  PlausibilityCheck c;
  c.level = level;
  c.message = message;
  return c;
}

} // namespace

PlausibilityCheck CheckMeshExtent(const double *coords, int num_nodes, const std::string &file) {
  if (num_nodes == 0) return {};
  double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};
  for (int i = 0; i < num_nodes; ++i)
    for (int c = 0; c < 3; ++c) {
      lo[c] = std::min(lo[c], coords[3 * i + c]);
      hi[c] = std::max(hi[c], coords[3 * i + c]);
    }
  const double d = std::sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                             (hi[2] - lo[2]) * (hi[2] - lo[2]));
  if (d >= kMeshExtentMin && d <= kMeshExtentMax) return {};
  std::string why = d < kMeshExtentMin ? "was the file in m (or cm)?" : "was the file in um (or scaled)?";
  return Verdict(Plausibility::Warning,
                 "mesh " + file + " spans " + Num(d) + " mm (its bounding-box diagonal): coordinates are in mm, so " +
                     why + " A membrane structure spans " + Num(kMeshExtentMin) + " mm to " + Num(kMeshExtentMax) +
                     " mm; scale the mesh (e.g. Gmsh's Mesh.ScalingFactor) if this is not meant.");
}

PlausibilityCheck CheckThickness(double h, const char *option) {
  if (h >= kThicknessMin && h <= kThicknessMax) return {};
  const std::string intent = Intent(h, kThicknessMin, kThicknessMax, {{1e3, "m"}, {1e-3, "um"}, {10.0, "cm"}});
  const bool error = h < kThicknessErrorMin || h > kThicknessErrorMax;
  return Verdict(error ? Plausibility::Error : Plausibility::Warning,
                 std::string(option) + " " + Num(h) + ": the thickness is in mm and ETFE foils are " +
                     Num(kThicknessMin) + "-" + Num(kThicknessMax) + " mm thick" +
                     (error ? "; below " + Num(kThicknessErrorMin) + " mm or above " + Num(kThicknessErrorMax) +
                                  " mm no film has it."
                            : ".") +
                     intent);
}

PlausibilityCheck CheckYoung(double E, const char *prefix) {
  if (E >= kYoungMin && E <= kYoungMax) return {};
  const std::string intent = Intent(E, kYoungMin, kYoungMax, {{1e-6, "Pa"}, {1e-3, "kPa"}, {1e3, "GPa"}});
  const bool error = E > kYoungErrorMax;
  return Verdict(error ? Plausibility::Error : Plausibility::Warning,
                 "-" + std::string(prefix) + "material_young " + Num(E) +
                     ": Young's modulus is in MPa and foils have " + Num(kYoungMin) + "-" +
                     Num(kYoungMax) + " MPa (ETFE about 800)" +
                     (error ? "; above " + Num(kYoungErrorMax) + " MPa no solid is." : ".") + intent);
}

PlausibilityCheck CheckYield(const double *yield, int n, double young, const char *prefix) {
  for (int k = 0; k < n; ++k) {
    const double s = yield[k];
    if (s >= kYieldMin && s <= kYieldMax && s < young) continue;
    const std::string intent = Intent(s, kYieldMin, kYieldMax, {{1e-6, "Pa"}, {1e-3, "kPa"}, {1e3, "GPa"}});
    const bool error = s >= young;
    return Verdict(error ? Plausibility::Error : Plausibility::Warning,
                   "-" + std::string(prefix) + "material_yield " + Num(s) + " (value " + std::to_string(k + 1) +
                       "): yield stresses are in MPa and ETFE yields at 10-30 MPa (the range checked: " +
                       Num(kYieldMin) + "-" + Num(kYieldMax) + " MPa)" +
                       (error ? "; it is not below -" + std::string(prefix) + "material_young " + Num(young) +
                                    " MPa (a yield strain of 100 % or more): the two are in different units."
                              : ".") +
                       intent);
  }
  return {};
}

PlausibilityCheck CheckCompensation(const char *option, double c) {
  if (std::fabs(c) <= kCompensationWarn) return {};
  const bool error = std::fabs(c) >= kCompensationError;
  const std::string intent = " Did you mean " + Num(0.01 * c) + " (" + Num(c) + " %)?";
  return Verdict(error ? Plausibility::Error : Plausibility::Warning,
                 std::string(option) + " " + Num(c) + ": the compensation is a fraction (0.01 = 1 %), so this is " +
                     Num(100 * c) + " % and cuts the strips at 1/" + Num(1 + c) + " of the design" +
                     (error ? "; from " + Num(100 * kCompensationError) + " % on no film is drawn so far."
                            : "; films are drawn 0.5-3 %, more than " + Num(100 * kCompensationWarn) +
                                  " % is unusual.") +
                     intent);
}

PlausibilityCheck CheckPrestress(const char *option, double S) {
  if (S <= kPrestressMax) return {};
  return Verdict(Plausibility::Warning,
                 std::string(option) + ": the larger principal stress " + Num(S) +
                     " MPa is above ETFE's yield (10-30 MPa; films are prestressed to 1-10 MPa); stresses are in "
                     "MPa." +
                     Intent(S, 0.1, kPrestressMax, {{1e-3, "kPa"}, {1e-6, "Pa"}}));
}

PlausibilityCheck CheckPressure(const std::string &what, double p) {
  if (std::fabs(p) <= kPressureWarn) return {};
  const bool error = std::fabs(p) > kPressureError;
  std::string intent;
  for (double f : {1e-3, 1e-6})
    if (intent.empty() && std::fabs(p) * f <= kPressureWarn && std::fabs(p) * f >= 1e-5)
      intent = " Did you mean " + Num(p * f) + " MPa (a unit " + Num(1 / f) + " times smaller)?";
  return Verdict(error ? Plausibility::Error : Plausibility::Warning,
                 what + " reaches " + Num(p) + " MPa (" + Num(1e3 * p) +
                     " kPa): roofs and cushions carry 0.2-5 kPa" +
                     (error ? "; above " + Num(kPressureError) + " MPa a foil bursts even over 1 cm."
                            : ", above " + Num(1e3 * kPressureWarn) + " kPa a foil bursts unless its span is a "
                                                                    "few cm.") +
                     intent);
}

PlausibilityCheck CheckAtmosphere(double p) {
  if (p >= kAtmosphereMin && p <= kAtmosphereMax) return {};
  const std::string intent =
      Intent(p, kAtmosphereMin, kAtmosphereMax, {{1e-3, "Pa"}, {1e3, "MPa"}, {100.0, "bar"}, {101.325, "atm"}});
  const bool error = p < kAtmosphereErrorMin || p > kAtmosphereErrorMax;
  return Verdict(error ? Plausibility::Error : Plausibility::Warning,
                 "-structure_atmosphere " + Num(p) + ": the atmospheric pressure is in kPa (absolute) and is " +
                     Num(kAtmosphereMin) + "-" + Num(kAtmosphereMax) + " kPa where roofs stand (101.325 at sea level)" +
                     (error ? "; below " + Num(kAtmosphereErrorMin) + " or above " + Num(kAtmosphereErrorMax) +
                                  " kPa it is nowhere on Earth, and the chambers' gas laws would be off by that much."
                            : ".") +
                     intent);
}

PlausibilityCheck CheckDensity(double rho) {
  if (rho >= kDensityMin && rho <= kDensityMax) return {};
  const std::string intent = Intent(rho, kDensityMin, kDensityMax, {{1e3, "g/cm^3"}, {1e-3, "g/m^3"}});
  const bool error = rho < kDensityErrorMin || rho > kDensityErrorMax;
  return Verdict(error ? Plausibility::Error : Plausibility::Warning,
                 "-structure_density " + Num(rho) + ": the density is in kg/m^3 and foils have " + Num(kDensityMin) +
                     "-" + Num(kDensityMax) + " kg/m^3 (ETFE 1750)" +
                     (error ? "; below " + Num(kDensityErrorMin) + " or above " + Num(kDensityErrorMax) +
                                  " kg/m^3 no solid has it."
                            : ".") +
                     intent);
}

PlausibilityCheck CheckTemperature(const char *option, double T) {
  if (T >= kTemperatureMin && T <= kTemperatureMax) return {};
  std::string intent;  // a value in kelvin: an offset, not a factor
  if (T - 273.15 >= kTemperatureMin && T - 273.15 <= kTemperatureMax)
    intent = " Did you mean " + Num(T - 273.15) + " (the value in K)?";
  const bool error = T > kTemperatureErrorMax;
  return Verdict(error ? Plausibility::Error : Plausibility::Warning,
                 std::string(option) + " " + Num(T) + ": the temperature is in deg C and ETFE roofs see " +
                     Num(kTemperatureMin) + " to " + Num(kTemperatureMax) + " C" +
                     (error ? "; above " + Num(kTemperatureErrorMax) + " C ETFE has melted." : ".") + intent);
}

} // namespace etfe
