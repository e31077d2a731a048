#include "controller/pulse_stage.hpp"

#include <algorithm>
#include <cmath>

#include "controller/tick.hpp"

namespace palprig {

void apply_pulse_stage(PulseTickState& state, const PulseRendering& rendering, const SafetyLimits& safety,
                       const PulseField& arteries, bool pressed, const std::array<Point2_mm, kFingerCount>& fingers,
                       double force_N, double t_s, double dt_s, ChannelPressures& target_kPa,
                       ChannelPressures& pulse_kPa) noexcept {
  if (!std::isfinite(t_s)) return;  // the safety stage faults on the bad time
  arteries.update_clocks(state.clocks, t_s);
  const bool stepped = dt_s > 0 && std::isfinite(dt_s);
  // The command issued now reaches the actuator one tick and one dead time later.
  const double period_s = stepped ? dt_s : state.last_dt_s;
  const bool compensate = rendering.lag_compensation_on();
  for (std::size_t i = 0; i < kFingerCount; ++i) {
    const RegulatorLag& lag = rendering.lag[i];
    const double lead_s = compensate ? lag.dead_time_s + period_s : 0.0;
    const LagCompensator& comp = state.compensator[i];
    const double rise_s = compensate ? comp.rise_anticipation_s() : 0.0;
    const double fall_s = compensate ? comp.fall_anticipation_s() : 0.0;
    const PulseFelt felt =
        arteries.felt(fingers[i], force_N, pressed, state.clocks, state.activation[i], t_s, lead_s, rise_s, fall_s,
                      rendering.has_measured_window ? &rendering.measured_window : nullptr);
    pulse_kPa[i] = felt.now_kPa;
    const double base = target_kPa[i];
    if (!std::isfinite(base)) continue;  // left for the safety stage to fault on
    if (!compensate) {
      target_kPa[i] = base + felt.now_kPa;
      continue;
    }
    // The pulse part may dip below zero (to speed a fall) but never takes the total below 0 kPa
    // or above p_max.
    const double lo = -std::max(base, 0.0);
    const double hi = std::max(safety.p_max_kPa - base, 0.0);
    const double max_step = stepped ? safety.slew_kPa_per_s * dt_s : 0.0;
    target_kPa[i] = base + state.compensator[i].command(lag, felt.ahead_kPa, lo, hi, max_step, stepped ? dt_s : 0.0);
  }
  if (stepped) state.last_dt_s = dt_s;
}

}  // namespace palprig
