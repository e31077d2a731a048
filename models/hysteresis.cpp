#include "models/hysteresis.hpp"

#include <algorithm>
#include <array>
#include <cstddef>
#include <cmath>

namespace palprig {

void PrandtlIshlinskii::reset(double x_kPa) noexcept {
  for (std::size_t i = 0; i < operator_count; ++i) state_kPa[i] = x_kPa;
}

double PrandtlIshlinskii::apply(double x_kPa) noexcept {
  double y = linear_weight * x_kPa;
  for (std::size_t i = 0; i < operator_count; ++i) {
    state_kPa[i] = std::max(x_kPa - thresholds_kPa[i], std::min(x_kPa + falling_threshold_kPa(i), state_kPa[i]));
    y += weights[i] * state_kPa[i];
  }
  return y;
}

double PrandtlIshlinskii::apply_exhausting(double x_kPa, double bottom_kPa) noexcept {
  double y = linear_weight * x_kPa;
  const double room = std::max(x_kPa - bottom_kPa, 0.0);
  for (std::size_t i = 0; i < operator_count; ++i) {
    state_kPa[i] =
        std::max(x_kPa - thresholds_kPa[i], std::min(x_kPa + std::min(falling_threshold_kPa(i), room), state_kPa[i]));
    y += weights[i] * state_kPa[i];
  }
  return y;
}

bool PrandtlIshlinskii::valid() const noexcept {
  if (!(linear_weight > 0) || !std::isfinite(linear_weight) || operator_count > kMaxPlayOperators) return false;
  double prev = 0.0;
  for (std::size_t i = 0; i < operator_count; ++i) {
    if (asymmetric) {
      if (!std::isfinite(thresholds_kPa[i]) || !(thresholds_kPa[i] > 0)) return false;
      if (!std::isfinite(falling_thresholds_kPa[i]) || !(falling_thresholds_kPa[i] > 0)) return false;
    } else if (!std::isfinite(thresholds_kPa[i]) || !(thresholds_kPa[i] > prev)) {
      return false;
    }
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

double PrandtlIshlinskii::input_for(double y_kPa, double bottom_kPa) const noexcept {
  if (!std::isfinite(y_kPa)) return y_kPa;
  // The output for an input x from the present states, as apply_exhausting computes it.
  auto output = [&](double x) {
    double y = linear_weight * x;
    const double room = std::max(x - bottom_kPa, 0.0);
    for (std::size_t i = 0; i < operator_count; ++i)
      y += weights[i] *
           std::max(x - thresholds_kPa[i], std::min(x + std::min(falling_threshold_kPa(i), room), state_kPa[i]));
    return y;
  };
  // The kinks: where a play's lower edge (x - r+) or upper edge (x + r-, or 2x - bottom near the
  // bottom) meets its state, and where the upper edge's slope changes (x = bottom + r-).
  std::array<double, 3 * kMaxPlayOperators + 1> kink{};
  std::size_t n = 0;
  kink[n++] = bottom_kPa;
  for (std::size_t i = 0; i < operator_count; ++i) {
    const double r_up = thresholds_kPa[i], r_down = falling_threshold_kPa(i), z = state_kPa[i];
    kink[n++] = z + r_up;
    kink[n++] = bottom_kPa + r_down;
    kink[n++] = z - r_down >= bottom_kPa + r_down ? z - r_down : 0.5 * (z + bottom_kPa);
  }
  std::sort(kink.begin(), kink.begin() + std::ptrdiff_t(n));
  double x0 = bottom_kPa, y0 = output(bottom_kPa);
  if (!(y_kPa > y0)) return bottom_kPa;
  for (std::size_t k = 0; k < n; ++k) {
    if (!(kink[k] > x0)) continue;
    const double y1 = output(kink[k]);
    if (y1 >= y_kPa) return y1 > y0 ? x0 + (kink[k] - x0) * (y_kPa - y0) / (y1 - y0) : kink[k];
    x0 = kink[k];
    y0 = y1;
  }
  // Past every kink every play follows its lower edge: slope w0 + sum of the weights.
  double slope = linear_weight;
  for (std::size_t i = 0; i < operator_count; ++i) slope += weights[i];
  return x0 + (y_kPa - y0) / slope;
}

}  // namespace palprig
