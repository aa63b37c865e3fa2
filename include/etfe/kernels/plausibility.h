// Plausibility of inputs: a value off by a unit or a scale (metres for mm, Pa for MPa, percent
// for a fraction) is stated before the run, not found in its results. PETSc-free: each check
// returns its verdict and the message; input_plausibility.h prints a warning or stops the run.
//
// The thresholds, all in the project's units (mm, MPa, fractions), for an ETFE foil:
//   quantity                         warning outside      error                         why the error
//   mesh extent (bounding-box diag.) 100 mm .. 1 km       -                             a mesh may be anything
//   -membrane_thickness              0.05 .. 0.5 mm       < 0.001 mm or > 10 mm         no foil: 1 um, 1 cm
//     (and -film_<group>_thickness)
//   -material_young                  100 .. 5000 MPa      > 1e6 MPa                     stiffer than any solid
//   -material_yield (each)           1 .. 100 MPa         above -material_young         yield strain > 100 %
//   -cutpattern_compensation_md/td   |c| > 0.05 (5 %)     |c| >= 0.5 (50 %)             the strips cut at 2/3 or less
//   -cutpattern_prestress (larger    above 30 MPa         -                             (the stress compensation
//     principal stress)                                                                  refuses what no stretch reaches)
//   a scene's pressure (largest |p|  above 0.05 MPa       above 10 MPa                  bursts a foil even over 1 cm
//     over its stages)               (50 kPa)
//   -structure_atmosphere            50 .. 110 kPa        < 10 kPa or > 200 kPa         no roof stands there (16 km
//                                                                                        up; twice sea level)
//   -structure_density               800 .. 2500 kg/m^3   < 100 or > 25000 kg/m^3       lighter than any solid foil;
//                                                                                        denser than any element
//   -material_temperature and        -50 .. 150 C         above 270 C                   ETFE melts at 260-280 C
//     -material_reference_temperature                     (below -273.15 C: refused where read)
// A warning names the option, the unit and, when the value times a power of 1000 (or 0.01 for a
// fraction) falls in the range, the likely intent ("did you mean 0.25?"). An error is reserved
// for values no film can have, so a study outside ETFE's range (another foil, a thick test
// specimen) still runs, with the warning.
#pragma once
#include <string>


namespace etfe {

namespace plausible {
constexpr double kMeshExtentMin = 100.0;      // mm: smaller is a model in m (3 m read as 3 mm)
constexpr double kMeshExtentMax = 1e6;        // mm: larger is a model in um (or 1000x scaled)
constexpr double kThicknessMin = 0.05;        // mm: ETFE foils are 50-500 um thick
constexpr double kThicknessMax = 0.5;         // mm
constexpr double kThicknessErrorMin = 1e-3;   // mm: 1 um, thinner than any foil
constexpr double kThicknessErrorMax = 10.0;   // mm: 1 cm, a plate, not a membrane
constexpr double kYoungMin = 100.0;           // MPa: soft foils (THV, hot ETFE)
constexpr double kYoungMax = 5000.0;          // MPa: stiff foils (PET)
constexpr double kYoungErrorMax = 1e6;        // MPa: 1000 GPa, stiffer than diamond: a value in Pa
constexpr double kYieldMin = 1.0;             // MPa
constexpr double kYieldMax = 100.0;           // MPa: ETFE yields at 10-30 MPa
constexpr double kCompensationWarn = 0.05;    // fraction: films are drawn 0.5-3 %
constexpr double kCompensationError = 0.5;    // fraction: a percentage typed as a fraction
constexpr double kPrestressMax = 30.0;        // MPa: ETFE yields at 10-30 MPa, films are prestressed 1-10
constexpr double kPressureWarn = 0.05;        // MPa: 50 kPa, 10x the heaviest snow or wind on a roof
constexpr double kPressureError = 10.0;       // MPa: p R / 2h is 200 MPa at R = 10 mm, h = 0.25 mm
constexpr double kAtmosphereMin = 50.0;       // kPa: 5500 m above the sea
constexpr double kAtmosphereMax = 110.0;      // kPa: the highest sea-level pressures (108 kPa)
constexpr double kAtmosphereErrorMin = 10.0;  // kPa: 16 km up
constexpr double kAtmosphereErrorMax = 200.0; // kPa: twice sea level
constexpr double kDensityMin = 800.0;         // kg/m^3: polyolefin foils (PE 900)
constexpr double kDensityMax = 2500.0;        // kg/m^3: fluoropolymer foils (PTFE 2200; ETFE 1750)
constexpr double kDensityErrorMin = 100.0;    // kg/m^3: no solid film is lighter (1.75: g/cm^3)
constexpr double kDensityErrorMax = 25000.0;  // kg/m^3: denser than osmium
constexpr double kTemperatureMin = -50.0;     // deg C: the coldest roofs
constexpr double kTemperatureMax = 150.0;     // deg C: ETFE's upper service temperature
constexpr double kTemperatureErrorMax = 270.0;// deg C: ETFE melts at 260-280 C (293 would be 20 C in K)
} // namespace plausible

enum class Plausibility { Fine, Warning, Error };

struct PlausibilityCheck {
  Plausibility level = Plausibility::Fine;
  std::string message;  // empty when Fine; names the option (or file), the unit and the intent
};

// A mesh read from `file` (num_nodes coordinates x y z in mm): its bounding-box diagonal against
// the extent range. Plain arrays: the kernels stay below the mesh layer.
PlausibilityCheck CheckMeshExtent(const double *coords, int num_nodes, const std::string &file);
// A film thickness (mm) given by `option` (-membrane_thickness, -film_<group>_thickness).
PlausibilityCheck CheckThickness(double thickness, const char *option = "-membrane_thickness");
// -material_young (MPa); prefix "film_<group>_": a surface group's own -film_<group>_material_young.
PlausibilityCheck CheckYoung(double young, const char *prefix = "");
// -material_yield: the n yield stresses (MPa) of a law with Young's modulus `young` (MPa) (prefix
// as CheckYoung's).
PlausibilityCheck CheckYield(const double *yield, int n, double young, const char *prefix = "");
// A uniform cutting-pattern compensation given by `option` (a fraction: 0.01 = 1 %).
PlausibilityCheck CheckCompensation(const char *option, double compensation);
// A design prestress given by `option`: its larger principal stress (MPa).
PlausibilityCheck CheckPrestress(const char *option, double stress);
// The largest |pressure| (MPa) over the stages of a load; `what` names it and its options.
PlausibilityCheck CheckPressure(const std::string &what, double pressure);
// -structure_atmosphere: the absolute atmospheric pressure (kPa) of the chambers' gas laws.
PlausibilityCheck CheckAtmosphere(double kpa);
// -structure_density: the film's density (kg/m^3) for its self-weight.
PlausibilityCheck CheckDensity(double density);
// A film temperature (deg C) given by `option`.
PlausibilityCheck CheckTemperature(const char *option, double celsius);

} // namespace etfe
