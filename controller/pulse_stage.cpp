#include "controller/pulse_stage.hpp"

#include <cmath>

namespace palprig {

void apply_pulse_stage(PulseTickState& state, const PulseStageSetting& setting, const FingersOnSkin& fingers,
                       const TickTime& time, const std::array<PulseLookahead, kFingerCount>& ahead,
                       PulseOutput& out) noexcept {
  const double t_s = time.t_s, dt_s = time.dt_s;
  if (!std::isfinite(t_s)) return;  // the safety stage faults on the bad time
  const PulseRendering& rendering = setting.rendering;
  setting.arteries.update_clocks(state.clocks, t_s, setting.settings);
  for (std::size_t i = 0; i < kFingerCount; ++i) {
    const FingerContact contact{fingers.centres[i], fingers.finger_force_N[i],
                                fingers.pressed && fingers.finger_pressed[i]};
    const PulseFelt felt =
        setting.arteries.felt(contact, state.clocks, state.activation[i], t_s, ahead[i],
                              rendering.has_measured_window ? &rendering.measured_window : nullptr, setting.settings);
    out.now_kPa[i] = felt.now_kPa;
    out.ahead_kPa[i] = ahead[i].lead_s > 0 ? felt.ahead_kPa : felt.now_kPa;
  }
  if (dt_s > 0 && std::isfinite(dt_s)) state.last_dt_s = dt_s;
}

}  // namespace palprig
