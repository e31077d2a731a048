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
  double linear_weight = 1.0;                              // w0
  std::size_t operator_count = 0;                          // n <= kMaxPlayOperators
  std::array<double, kMaxPlayOperators> thresholds_kPa{};  // r_1 < r_2 < ... (strictly increasing, > 0)
  std::array<double, kMaxPlayOperators> weights{};         // w_i
  std::array<double, kMaxPlayOperators> state_kPa{};       // play outputs

  // Sets every play state to x (a relaxed start at input x).
  void reset(double x_kPa) noexcept;
  double apply(double x_kPa) noexcept;
  // As apply, for an actuator whose regulator exhausts at the bottom of its range: below
  // bottom + r_i a play's band above the input narrows to the input's distance from the bottom
  // (a regulator commanded 0 kPa opens its exhaust valve and empties the actuator; the simulated
  // plant of models/pneumatic_plant.hpp does the same). A plain PI model cannot describe that;
  // the tick's forward copy, driven by the setpoints sent, uses this so that its inverse
  // continues from an emptied actuator after a command near 0.
  double apply_exhausting(double x_kPa, double bottom_kPa = 0.0) noexcept;
  // The input, at least bottom_kPa, that apply_exhausting would turn into y_kPa from the present
  // play states (the states are not changed): the exact inverse of the exhausting model at this
  // point of its history. The model is piecewise linear and strictly increasing in its input
  // (linear_weight > 0), so it is solved exactly between its kinks. bottom_kPa when even that
  // gives more than y_kPa. For a valid() model.
  double input_for(double y_kPa, double bottom_kPa = 0.0) const noexcept;
  bool is_identity() const noexcept { return operator_count == 0 && linear_weight == 1.0; }
  // Valid when w0 > 0, weights >= 0, thresholds positive, finite and strictly increasing.
  bool valid() const noexcept;
  // The analytic inverse (requires valid()).
  PrandtlIshlinskii inverse() const noexcept;
  // The forward model an analytic inverse came from (the inverse of inverse(); for a model made
  // by inverse() only), play states reset to 0.
  PrandtlIshlinskii forward_of_inverse() const noexcept;
};

}  // namespace palprig
