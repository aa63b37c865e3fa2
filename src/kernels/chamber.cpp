// Gas chamber kernels (see chamber.h).
#include "etfe/kernels/chamber.h"

#include <cmath>

namespace etfe {

double ChamberTetVolume(const double x[9], const double o[3]) {
  double a[3], b[3], c[3];
  for (int i = 0; i < 3; ++i) a[i] = x[i] - o[i], b[i] = x[3 + i] - o[i], c[i] = x[6 + i] - o[i];
  return (a[0] * (b[1] * c[2] - b[2] * c[1]) + a[1] * (b[2] * c[0] - b[0] * c[2]) + a[2] * (b[0] * c[1] - b[1] * c[0])) /
         6.0;
}

double SealedAmount(double gauge, double atmosphere, double volume, double kappa) {
  return (gauge + atmosphere) * std::pow(volume, kappa);
}

double SealedGauge(double amount, double atmosphere, double volume, double kappa) {
  return amount * std::pow(volume, -kappa) - atmosphere;
}

double SealedStiffness(double amount, double volume, double kappa) {
  return kappa * amount * std::pow(volume, -kappa) / volume;
}

} // namespace etfe
