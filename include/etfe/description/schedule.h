// Piecewise-linear load schedules over the stages of an analysis. PETSc-free.
//
// Load time t runs from 0 to the number of stages; stage s covers t in [s, s+1]. A schedule
// holds one value per stage end and starts from `initial` at t = 0, so "draw a = 10, 20, 30,
// 40 mm in four experimental steps" or "pressure 0.5, 0, 1, 0 kPa" are one schedule each.
#pragma once
#include <string>
#include <utility>
#include <vector>

namespace etfe {

struct Schedule {
  Schedule() = default;
  Schedule(std::string name_, double initial_, std::vector<double> values_, std::string unit_ = "",
           double display_scale_ = 1.0)
      : name(std::move(name_)), initial(initial_), values(std::move(values_)), unit(std::move(unit_)),
        display_scale(display_scale_) {}

  std::string name;
  double initial = 0.0;
  std::vector<double> values;  // value at the end of each stage
  // How progress lines show it: value x display_scale, then unit ("" for a load factor).
  std::string unit;
  double display_scale = 1.0;

  int NumStages() const { return (int)values.size(); }
  // Value at load time t (clamped to [0, NumStages()]).
  double At(double t) const;
};

// A prescribed value built from up to two schedules: value(t) = c0 S[i0](t) + c1 S[i1](t)
// (index -1 drops a term, so a fixed support is {0, -1, 0, -1}). Drawing values interpolated
// linearly along an edge between two drawing positions use both terms.
struct ScheduledValue {
  double coef[2] = {0.0, 0.0};
  int schedule[2] = {-1, -1};
  double At(const std::vector<Schedule> &schedules, double t) const;
};

} // namespace etfe
