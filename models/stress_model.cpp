#include "models/stress_model.hpp"

#include <algorithm>
#include <cmath>

namespace palprig {

double StressModel::force_ratio(double force_N) const noexcept {
  if (!(force_N > 0) || !(reference_force_N > 0)) return 0.0;  // also catches NaN
  return std::min(force_N / reference_force_N, max_force_ratio);
}

double StressModel::target_stress_kPa(double stiffness, double force_N) const noexcept {
  const double s = std::clamp(stiffness, 0.0, 1.0);
  return force_ratio(force_N) * (soft_stress_kPa + s * (hard_stress_kPa - soft_stress_kPa));
}

double ActuatorModel::pressure_kPa(double stress_kPa, double force_ratio) const noexcept {
  const double p = (stress_kPa - force_ratio * intercept_kPa) / slope;
  return std::max(p, 0.0);  // NaN passes through so the safety stage sees it and faults
}

}  // namespace palprig
