#include "models/lag_compensator.hpp"

#include <algorithm>
#include <cmath>

namespace palprig {

namespace {

struct LagStep {
  double alpha;   // first-order step fraction this tick, in the direction being solved for
  double max_dy;  // regulator output slew allowance this tick
  double max_du;  // command slew allowance this tick (<= 0: unlimited)
  double lo, hi;  // command bounds
  // The step fractions filling (command above the output) and exhausting (below it): the same
  // for a regulator with one lag.
  double alpha_fill, alpha_exhaust;

  double advance(double y, double u) const noexcept {
    const double a = u >= y ? alpha_fill : alpha_exhaust;
    return y + std::clamp(a * (u - y), -max_dy, max_dy);
  }
};

constexpr int kBrakeHorizon = 400;  // ticks simulated to check a command (0.4 s at 1 kHz)
constexpr int kBisections = 10;

// Start with command u now, then move the command back to `want` as fast as its slew allows
// and hold it there: how far does the modelled output pass beyond want (in direction `sign`)?
// Once the command rests on want the first-order output only closes in, so the walk ends there.
double overshoot_walked(const LagStep& s, double y, double u, double want, double sign) noexcept {
  double worst = 0;
  for (int k = 0; k < kBrakeHorizon; ++k) {
    y = s.advance(y, u);
    worst = std::max(worst, sign * (y - want));
    if (u == want) break;
    if (s.max_du > 0)
      u = u > want ? std::max(u - s.max_du, want) : std::min(u + s.max_du, want);
    else
      u = want;
  }
  return worst;
}

// The same in closed form while the regulator's own output slew cannot bind (the walk's steps
// are then the linear recurrence Y' = a Y + (1 - a) U with U ramping down by D a tick): in the
// frame where want is 0 and the push is positive, Y_k = U_k + c + (Y_0 - U_0 - c) a^k with
// c = D / (1 - a), rising while a^k > D / ((U_0 - Y_0)(1 - a) + D), so its peak is at the first
// whole tick past that, or where the ramp ends. The tick runs this for every channel, often
// several times: a walk of tens of steps each time would not fit its budget.
double overshoot(const LagStep& s, double y, double u, double want, double sign) noexcept {
  const double Y0 = sign * (y - want), U0 = sign * (u - want), D = s.max_du, a = 1.0 - s.alpha;
  const bool linear = s.alpha * std::max(std::abs(U0 - Y0), std::abs(U0)) <= s.max_dy;
  if (!linear || !(U0 > Y0) || !(U0 > 0) || !(a > 0) || !(a < 1)) return overshoot_walked(s, y, u, want, sign);
  if (!(D > 0)) return std::max(0.0, a * Y0 + s.alpha * U0);  // the command is back on want next tick
  const double K = std::ceil(U0 / D);                         // ticks of the ramp down
  const double c = D / s.alpha;
  const double kappa = std::log(D / ((U0 - Y0) * s.alpha + D)) / std::log(a);
  const double k = std::clamp(std::ceil(kappa), 1.0, K);
  const double peak = (U0 - k * D) + c + (Y0 - U0 - c) * std::pow(a, k);
  return std::max(0.0, peak);
}

// The push (U_0 - Y_0 in overshoot's frame) whose ramp back lands the output on want + tolerance
// when the command slews continuously: v - c ln(1 + v / c) = tolerance - Y_0, convex in v, by
// Newton from the right. A starting point for the discrete search, not its answer.
double continuous_push(double Y0, double tolerance, double c) noexcept {
  const double E = tolerance - Y0;
  if (!(E > 0) || !(c > 0)) return 0.0;
  double v = E + std::sqrt(2 * c * E) + c * std::log1p(E / c);  // g(v) >= 0 here
  for (int i = 0; i < 6; ++i) {
    const double g = v - c * std::log1p(v / c) - E;
    const double dg = v / (v + c);
    if (!(dg > 0)) break;
    const double next = v - g / dg;
    if (!(next > 0) || std::abs(next - v) < 1e-9 * (1 + v)) {
      if (next > 0) v = next;
      break;
    }
    v = next;
  }
  return v;
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
  const double tau = lag.time_constant_s, tau_exhaust = lag.exhaust_tau_s();
  LagStep s;
  s.alpha_fill = tau > 0 ? -std::expm1(-dt_s / tau) : 1.0;
  s.alpha_exhaust = tau_exhaust > 0 ? -std::expm1(-dt_s / tau_exhaust) : 1.0;
  s.alpha = s.alpha_fill;
  s.max_dy = lag.slew_kPa_per_s > 0 ? lag.slew_kPa_per_s * dt_s : 1e300;
  s.max_du = max_step_kPa;
  s.lo = lo_kPa;
  s.hi = hi_kPa;
  const double want = std::clamp(want_ahead_kPa, lo_kPa, hi_kPa);
  const double y = predicted_kPa_;
  // A fall is pushed by the exhaust, a rise by the supply: the lag of the way the output goes.
  if (want < y) s.alpha = s.alpha_exhaust;

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
      // The continuous-slew answer narrows the search: it is within a slew step or so of the
      // discrete one, so a few halvings of a bracket around it find the push.
      if (s.max_du > 0 && s.alpha < 1) {
        const double v = continuous_push(sign * (y - want), tolerance, s.max_du / s.alpha);
        const double guess = y + sign * v;
        const double margin = s.max_du + 0.02 * v;
        const double lo_guess = guess - sign * margin, hi_guess = guess + sign * margin;
        if (sign * (lo_guess - weak) > 0 && sign * (strong - lo_guess) > 0 &&
            overshoot(s, y, lo_guess, want, sign) <= tolerance)
          weak = lo_guess;
        if (sign * (hi_guess - weak) > 0 && sign * (strong - hi_guess) > 0 &&
            overshoot(s, y, hi_guess, want, sign) > tolerance)
          strong = hi_guess;
      }
      for (int i = 0; i < kBisections && std::abs(strong - weak) > 1e-3 * (std::abs(want - y) + 1e-3); ++i) {
        const double mid = 0.5 * (weak + strong);
        if (overshoot(s, y, mid, want, sign) <= tolerance)
          weak = mid;
        else
          strong = mid;
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
