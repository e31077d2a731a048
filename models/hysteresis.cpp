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

double PrandtlIshlinskii::apply_exhausting(double x_kPa, double bottom_kPa) noexcept {
  double y = linear_weight * x_kPa;
  const double room = std::max(x_kPa - bottom_kPa, 0.0);
  for (std::size_t i = 0; i < operator_count; ++i) {
    const double r = thresholds_kPa[i];
    state_kPa[i] = std::max(x_kPa - r, std::min(x_kPa + std::min(r, room), state_kPa[i]));
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

PrandtlIshlinskii PrandtlIshlinskii::forward_of_inverse() const noexcept {
  // Kuhnen's relations solved for the forward parameters, in operator order:
  //   w0 = 1 / w0',  w_i = -w'_i S^2 / (1 + w'_i S),  r_i = (r'_i + sum_{j<i} w_j r_j) / S,
  // with S = w0 + sum_{j<i} w_j.
  PrandtlIshlinskii f;
  f.operator_count = operator_count;
  f.linear_weight = 1.0 / linear_weight;
  double sum_before = f.linear_weight, moment = 0;  // S, sum_{j<i} w_j r_j
  for (std::size_t i = 0; i < operator_count; ++i) {
    const double w = -weights[i] * sum_before * sum_before / (1.0 + weights[i] * sum_before);
    const double r = (thresholds_kPa[i] + moment) / sum_before;
    f.weights[i] = w;
    f.thresholds_kPa[i] = r;
    moment += w * r;
    sum_before += w;
  }
  return f;
}

double sync_inverse_to(const PrandtlIshlinskii& forward, double x_kPa, PrandtlIshlinskii& inverse) noexcept {
  double y = forward.linear_weight * x_kPa;
  for (std::size_t i = 0; i < forward.operator_count; ++i) y += forward.weights[i] * forward.state_kPa[i];
  double sum_before = forward.linear_weight, weighted = 0;  // S, sum_{j<i} w_j d_j
  for (std::size_t i = 0; i < forward.operator_count && i < inverse.operator_count; ++i) {
    const double d = x_kPa - forward.state_kPa[i];
    const double e = sum_before * d - weighted;
    inverse.state_kPa[i] = y - e;
    weighted += forward.weights[i] * d;
    sum_before += forward.weights[i];
  }
  return y;
}

}  // namespace palprig
