#include "controller/pulse_stage.hpp"

#include <algorithm>
#include <cmath>

namespace palprig {

void apply_pulse_stage(PulseTickState& state, const PulseStageSetting& setting, const FingersOnSkin& fingers,
                       const TickTime& time, ChannelPressures& target_kPa, ChannelPressures& pulse_kPa) noexcept {
  const double t_s = time.t_s, dt_s = time.dt_s;
  if (!std::isfinite(t_s)) return;  // the safety stage faults on the bad time
  const PulseRendering& rendering = setting.rendering;
  setting.arteries.update_clocks(state.clocks, t_s);
  const bool stepped = dt_s > 0 && std::isfinite(dt_s);
  // The command issued now reaches the actuator one tick and one dead time later.
  const double period_s = stepped ? dt_s : state.last_dt_s;
  const bool compensate = rendering.lag_compensation_on();
  for (std::size_t i = 0; i < kFingerCount; ++i) {
    const RegulatorLag& lag = rendering.lag[i];
    LagCompensator& compensator = state.lag_compensator[i];
    PulseLookahead ahead;
    if (compensate) {
      ahead.lead_s = lag.dead_time_s + period_s;
      ahead.rise_advance_s = compensator.rise_anticipation_s();
      ahead.fall_advance_s = compensator.fall_anticipation_s();
    }
    const FingerContact contact{fingers.centres[i], fingers.finger_force_N[i], fingers.pressed && fingers.finger_pressed[i]};
    const PulseFelt felt = setting.arteries.felt(contact, state.clocks, state.activation[i], t_s, ahead,
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
    const double hi = std::max(setting.p_max_kPa - base, 0.0);
    const double max_step = stepped ? setting.slew_kPa_per_s * dt_s : 0.0;
    target_kPa[i] = base + compensator.command(lag, felt.ahead_kPa, lo, hi, max_step, stepped ? dt_s : 0.0);
  }
  if (stepped) state.last_dt_s = dt_s;
}

}  // namespace palprig
