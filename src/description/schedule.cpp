// Piecewise-linear stage schedules (see schedule.h).
#include "etfe/description/schedule.h"

#include <algorithm>
#include <cmath>

namespace etfe {

double Schedule::At(double t) const {
  const int n = NumStages();
  if (n == 0) return initial;
  t = std::min(std::max(t, 0.0), (double)n);
  int s = std::min((int)std::floor(t), n - 1);
  const double start = s == 0 ? initial : values[s - 1];
  return start + (t - s) * (values[s] - start);
}

double ScheduledValue::At(const std::vector<Schedule> &schedules, double t) const {
  double v = 0.0;
  for (int k = 0; k < 2; ++k)
    if (schedule[k] >= 0) v += coef[k] * schedules[schedule[k]].At(t);
  return v;
}

} // namespace etfe
