#include "models/hysteresis.hpp"

#include <algorithm>
#include <cmath>

namespace palprig {

void PrandtlIshlinskii::reset(double x_kPa) noexcept {
  for (std::size_t i = 0; i < operator_count; ++i) state_kPa[i] = x_kPa;
}

double PrandtlIshlinskii::apply(double x_kPa) noexcept {
  double y = linear_weight * x_kPa;
  for (std::size_t i = 0; i < operator_count; ++i) {
    const double r = thresholds_kPa[i];
    state_kPa[i] = std::max(x_kPa - r, std::min(x_kPa + r, state_kPa[i]));
    y += weights[i] * state_kPa[i];
  }
  return y;
}

bool PrandtlIshlinskii::valid() const noexcept {
  if (!(linear_weight > 0) || !std::isfinite(linear_weight) || operator_count > kMaxPlayOperators) return false;
  double prev = 0.0;
  for (std::size_t i = 0; i < operator_count; ++i) {
    if (!std::isfinite(thresholds_kPa[i]) || !(thresholds_kPa[i] > prev)) return false;
    if (!std::isfinite(weights[i]) || weights[i] < 0) return false;
    prev = thresholds_kPa[i];
  }
  return true;
}

PrandtlIshlinskii PrandtlIshlinskii::inverse() const noexcept {
  PrandtlIshlinskii inv;
  inv.operator_count = operator_count;
  inv.linear_weight = 1.0 / linear_weight;
  double sum_before = linear_weight;  // w0 + sum_{j<i} w_j
  for (std::size_t i = 0; i < operator_count; ++i) {
    const double r = thresholds_kPa[i];
    double r_inv = linear_weight * r;
    for (std::size_t j = 0; j < i; ++j) r_inv += weights[j] * (r - thresholds_kPa[j]);
    const double sum_through = sum_before + weights[i];
    inv.thresholds_kPa[i] = r_inv;
    inv.weights[i] = -weights[i] / (sum_through * sum_before);
    sum_before = sum_through;
  }
  return inv;
}

}  // namespace palprig
