// Fabrication criteria of a drawn film (thesis L1682-1722): the drawing planner scores
// a stretch run by how far each element is from them. PETSc-free.
//
// Per element three violations, each zero when the criterion is met and growing linearly with the
// distance from it, in units that make one unit "as bad" for every criterion:
//   mises:  outside the band |S - T| <= band T   (in units of band T, the band's half-width);
//   minor:  the minor principal GL strain (or, for the tension-field test, the minor principal
//           stress) below minor_limit (in units of minor_unit);
//   eq:     the equivalent plastic strain at or above max_eq_strain (in units of strain_unit).
// A planner minimises the sum of their squares (a C1 function of the state) plus a small drawing
// term, so among schedules that meet the criteria it prefers the least drawing.
#pragma once

namespace etfe {

struct PlanCriteria {
  double mises_target = 13.28;  // the first yield stress S_y1 [MPa] (Table 4.2)
  double mises_band = 0.10;     // relative half-width of the band
  double minor_limit = 0.0;     // smallest allowed minor principal strain or stress (0: no wrinkle)
  double minor_unit = 1e-3;     // scale of the minor violation (a strain; MPa for the stress test)
  double max_eq_strain = 0.10;  // equivalent plastic strain must stay below (thesis: 10 %)
  double strain_unit = 1e-3;    // scale of the equivalent-strain violation
};

// The three violations v[0] (Mises band), v[1] (minor principal strain or stress), v[2]
// (equivalent strain) of one element. Returns 0, or KERNEL_NONFINITE for NaN/Inf input or criteria
// that make no sense (target, band or a unit <= 0).
int PlanElementViolations(const PlanCriteria &c, double mises, double minor, double eq_strain, double v[3]);

} // namespace etfe
