#include "models/lag_compensator.hpp"

#include <algorithm>
#include <cmath>

namespace palprig {

namespace {

struct LagStep {
  double alpha;   // first-order step fraction this tick
  double max_dy;  // regulator output slew allowance this tick
  double max_du;  // command slew allowance this tick (<= 0: unlimited)
  double lo, hi;  // command bounds

  double advance(double y, double u) const noexcept { return y + std::clamp(alpha * (u - y), -max_dy, max_dy); }
};

constexpr int kBrakeHorizon = 400;  // ticks simulated to check a command (0.4 s at 1 kHz)
constexpr int kBisections = 10;

// Start with command u now, then move the command back to `want` as fast as its slew allows
// and hold it there: how far does the modelled output pass beyond want (in direction `sign`)?
// Once the command rests on want the first-order output only closes in, so the walk ends there.
double overshoot(const LagStep& s, double y, double u, double want, double sign) noexcept {
  double worst = 0;
  for (int k = 0; k < kBrakeHorizon; ++k) {
    y = s.advance(y, u);
    worst = std::max(worst, sign * (y - want));
    if (u == want) break;
    if (s.max_du > 0) u = u > want ? std::max(u - s.max_du, want) : std::min(u + s.max_du, want);
    else u = want;
  }
  return worst;
}

}  // namespace

double LagCompensator::command(const RegulatorLag& lag, double want_ahead_kPa, double lo_kPa, double hi_kPa,
                               double max_step_kPa, double dt_s) noexcept {
  if (!std::isfinite(want_ahead_kPa)) return want_ahead_kPa;  // the safety stage faults on it
  if (hi_kPa < lo_kPa) hi_kPa = lo_kPa;
  if (!(dt_s > 0)) {
    const double u = std::clamp(want_ahead_kPa, lo_kPa, hi_kPa);
    last_command_kPa_ = u;
    return u;
  }
  const double tau = lag.time_constant_s;
  LagStep s;
  s.alpha = tau > 0 ? -std::expm1(-dt_s / tau) : 1.0;
  s.max_dy = lag.slew_kPa_per_s > 0 ? lag.slew_kPa_per_s * dt_s : 1e300;
  s.max_du = max_step_kPa;
  s.lo = lo_kPa;
  s.hi = hi_kPa;
  const double want = std::clamp(want_ahead_kPa, lo_kPa, hi_kPa);
  const double y = predicted_kPa_;

  // The reachable commands this tick, and the one that lands the model on `want` next tick.
  double u_min = lo_kPa, u_max = hi_kPa;
  if (max_step_kPa > 0) {
    u_min = std::clamp(last_command_kPa_ - max_step_kPa, lo_kPa, hi_kPa);
    u_max = std::clamp(last_command_kPa_ + max_step_kPa, lo_kPa, hi_kPa);
  }
  const double deadbeat = y + (want - y) / s.alpha;
  double u;
  if (want == y) {
    u = std::clamp(want, u_min, u_max);
  } else {
    // Push as hard as allowed toward `want`, but no harder than a command from which the
    // slew-limited way back still stops the output at `want` (no overshoot). Overshoot grows
    // with the push, so the largest safe push is found by bisection.
    const double sign = want > y ? 1.0 : -1.0;
    const double tolerance = 0.01 * std::abs(want - y) + 1e-6;
    double weak = std::clamp(sign > 0 ? std::max(want, u_min) : std::min(want, u_max), u_min, u_max);
    double strong = std::clamp(sign > 0 ? std::min(deadbeat, u_max) : std::max(deadbeat, u_min), u_min, u_max);
    if (sign * (strong - weak) <= 0 || overshoot(s, y, strong, want, sign) <= tolerance) {
      u = sign * (strong - weak) <= 0 ? weak : strong;
    } else if (overshoot(s, y, weak, want, sign) > tolerance) {
      u = sign > 0 ? u_min : u_max;  // already committed: brake as hard as the slew allows
    } else {
      for (int i = 0; i < kBisections; ++i) {
        const double mid = 0.5 * (weak + strong);
        if (overshoot(s, y, mid, want, sign) <= tolerance) weak = mid;
        else strong = mid;
      }
      u = weak;
    }
  }
  predicted_kPa_ = s.advance(y, u);
  last_command_kPa_ = u;
  measure_edges(want, dt_s);
  return u;
}

void LagCompensator::measure_edges(double want, double dt_s) noexcept {
  // A jump is a change of at least 0.5 kPa and a quarter of the level within one tick: the
  // edges of a rectangular pulse, not the slopes of a smooth waveform.
  const double jump = want - last_want_kPa_;
  const double level = std::max(std::abs(want), std::abs(last_want_kPa_));
  if (std::abs(jump) >= 0.5 && std::abs(jump) >= 0.25 * level) {
    timing_ = true;
    edge_mid_kPa_ = last_want_kPa_ + 0.5 * jump;
    edge_sign_ = jump > 0 ? 1.0 : -1.0;
    edge_elapsed_s_ = 0;
  }
  last_want_kPa_ = want;
  if (!timing_) return;
  edge_elapsed_s_ += dt_s;
  if (edge_sign_ * (predicted_kPa_ - edge_mid_kPa_) >= 0) {
    // Half-way: the model output follows the command, so this is when the felt edge is
    // half-way too; smooth over beats so one disturbed edge does not jerk the timing.
    double& a = edge_sign_ > 0 ? rise_anticipation_s_ : fall_anticipation_s_;
    a = a == 0 ? edge_elapsed_s_ : 0.5 * (a + edge_elapsed_s_);
    timing_ = false;
  } else if (edge_elapsed_s_ > 0.25) {
    timing_ = false;  // never got there (the finger moved off, or the limits forbid it)
  }
}

}  // namespace palprig
