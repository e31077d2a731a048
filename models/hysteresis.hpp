#pragma once
// Prandtl-Ishlinskii (PI) hysteresis: y = w0 * x + sum_i w_i * play_{r_i}[x], with play
// operators z_i = max(x - r_i, min(x + r_i, z_i_prev)). With w0 > 0 and w_i >= 0 the model has
// an analytic inverse that is itself a PI model (Kuhnen 2003):
//   r'_i = sum_{j<i} w_j (r_i - r_j)   (r_0 = 0, w_0 the linear weight)
//   w'_0 = 1 / w0,  w'_i = -w_i / ((w0 + sum_{j<=i} w_j) (w0 + sum_{j<i} w_j))
// The tick runs the inverse per channel so that the actuator lands on the target on both the
// inflation and the deflation branch. Fixed-size storage: no allocation on the hot path.
//
// Asymmetric regulators (a pneumatic regulator fills through its supply valve and empties
// through its exhaust, so its dead band rising is not its dead band falling): the generalised
// Prandtl-Ishlinskii model with separate rising and falling envelopes (Al Janaideh, Rakheja and
// Su, IEEE/ASME Trans. Mechatronics 16(4), 2011), with linear envelopes, i.e. play operators
// whose lower edge is x - r+_i and upper edge x + r-_i:
//   z_i = max(x - r+_i, min(x + r-_i, z_i_prev)),   y = w0 * x + sum_i w_i * z_i.
// Chosen over Kuhnen's modified PI model (one-sided dead-zone operators on the output) because
// what differs in a regulator is the width of its dead band by direction, not the output's
// shape by level, which is what dead zones bend; and over a discrete Preisach model because that
// needs a weight per cell (tens to hundreds) where a sweep of a few hundred holds supports about
// ten parameters. It keeps what the tick relies on: with w0 > 0 and w_i >= 0 the output is
// piecewise linear and strictly increasing in the input, so input_for inverts it exactly at the
// actuator's present state on either branch; and r+ = r- is the symmetric model, so a calibration
// file without falling thresholds is that model, unchanged. Its inverse is no longer a PI model
// (inverse() and forward_of_inverse() are for symmetric models only); the tick needs none.
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
  // Asymmetric plays: thresholds_kPa are then the rising ones (the output lags a rising input by
  // them) and these the falling ones (above a falling input); unused when !asymmetric.
  bool asymmetric = false;
  std::array<double, kMaxPlayOperators> falling_thresholds_kPa{};

  double rising_threshold_kPa(std::size_t i) const noexcept { return thresholds_kPa[i]; }
  double falling_threshold_kPa(std::size_t i) const noexcept {
    return asymmetric ? falling_thresholds_kPa[i] : thresholds_kPa[i];
  }

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
  // Valid when w0 > 0, weights >= 0, thresholds positive, finite and strictly increasing (for an
  // asymmetric model: rising and falling thresholds positive and finite, in any order).
  bool valid() const noexcept;
  // The analytic inverse (requires valid() and !asymmetric).
  PrandtlIshlinskii inverse() const noexcept;
  // The forward model an analytic inverse came from (the inverse of inverse(); for a model made
  // by inverse() only), play states reset to 0.
  PrandtlIshlinskii forward_of_inverse() const noexcept;
};

}  // namespace palprig
