// Plausibility of inputs: a value off by a unit or a scale (metres for mm, Pa for MPa, percent
// for a fraction) is stated before the run, not found in its results. PETSc-free: each check
// returns its verdict and the message; input_plausibility.h prints a warning or stops the run.
//
// The thresholds, all in the project's units (mm, MPa, fractions), for an ETFE foil:
//   quantity                         warning outside      error                         why the error
//   mesh extent (bounding-box diag.) 100 mm .. 1 km       -                             a mesh may be anything
//   -membrane_thickness              0.05 .. 0.5 mm       < 0.001 mm or > 10 mm         no foil: 1 um, 1 cm
//   -material_young                  100 .. 5000 MPa      > 1e6 MPa                     stiffer than any solid
//   -material_yield (each)           1 .. 100 MPa         above -material_young         yield strain > 100 %
//   -cutpattern_compensation_md/td   |c| > 0.05 (5 %)     |c| >= 0.5 (50 %)             the strips cut at 2/3 or less
//   -cutpattern_prestress (larger    above 30 MPa         -                             (the stress compensation
//     principal stress)                                                                  refuses what no stretch reaches)
//   a scene's pressure (largest |p|  above 0.05 MPa       above 10 MPa                  bursts a foil even over 1 cm
//     over its stages)               (50 kPa)
// A warning names the option, the unit and, when the value times a power of 1000 (or 0.01 for a
// fraction) falls in the range, the likely intent ("did you mean 0.25?"). An error is reserved
// for values no film can have, so a study outside ETFE's range (another foil, a thick test
// specimen) still runs, with the warning.
#pragma once
#include <string>

#include "etfe/mesh/mesh_data.h"

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
} // namespace plausible

enum class Plausibility { Fine, Warning, Error };

struct PlausibilityCheck {
  Plausibility level = Plausibility::Fine;
  std::string message;  // empty when Fine; names the option (or file), the unit and the intent
};

// A mesh read from `file` (coordinates in mm): its bounding-box diagonal against the extent range.
PlausibilityCheck CheckMeshExtent(const MeshData &mesh, const std::string &file);
// -membrane_thickness (mm).
PlausibilityCheck CheckThickness(double thickness);
// -material_young (MPa).
PlausibilityCheck CheckYoung(double young);
// -material_yield: the n yield stresses (MPa) of a law with Young's modulus `young` (MPa).
PlausibilityCheck CheckYield(const double *yield, int n, double young);
// A uniform cutting-pattern compensation given by `option` (a fraction: 0.01 = 1 %).
PlausibilityCheck CheckCompensation(const char *option, double compensation);
// A design prestress given by `option`: its larger principal stress (MPa).
PlausibilityCheck CheckPrestress(const char *option, double stress);
// The largest |pressure| (MPa) over the stages of a load; `what` names it and its options.
PlausibilityCheck CheckPressure(const std::string &what, double pressure);

} // namespace etfe
