#pragma once
// Prandtl-Ishlinskii (PI) hysteresis: y = w0 * x + sum_i w_i * play_{r_i}[x], with play
// operators z_i = max(x - r_i, min(x + r_i, z_i_prev)). With w0 > 0 and w_i >= 0 the model has
// an analytic inverse that is itself a PI model (Kuhnen 2003):
//   r'_i = sum_{j<i} w_j (r_i - r_j)   (r_0 = 0, w_0 the linear weight)
//   w'_0 = 1 / w0,  w'_i = -w_i / ((w0 + sum_{j<=i} w_j) (w0 + sum_{j<i} w_j))
// The tick runs the inverse per channel so that the actuator lands on the target on both the
// inflation and the deflation branch. Fixed-size storage: no allocation on the hot path.
#include <array>
#include <cstddef>

namespace palprig {

inline constexpr std::size_t kMaxPlayOperators = 16;

struct PrandtlIshlinskii {
  double linear_weight = 1.0;                      // w0
  std::size_t operator_count = 0;                  // n <= kMaxPlayOperators
  std::array<double, kMaxPlayOperators> thresholds_kPa{};  // r_1 < r_2 < ... (strictly increasing, > 0)
  std::array<double, kMaxPlayOperators> weights{};         // w_i
  std::array<double, kMaxPlayOperators> state_kPa{};       // play outputs

  // Sets every play state to x (a relaxed start at input x).
  void reset(double x_kPa) noexcept;
  double apply(double x_kPa) noexcept;
  bool is_identity() const noexcept { return operator_count == 0 && linear_weight == 1.0; }
  // Valid when w0 > 0, weights >= 0, thresholds positive, finite and strictly increasing.
  bool valid() const noexcept;
  // The analytic inverse (requires valid()).
  PrandtlIshlinskii inverse() const noexcept;
};

}  // namespace palprig
