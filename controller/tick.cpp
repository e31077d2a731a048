#include "controller/tick.hpp"

#include <cmath>

namespace palprig {

TickState make_tick_state(const TickConfig& config) noexcept {
  TickState s;
  for (std::size_t i = 0; i < kFingerCount; ++i) {
    s.hysteresis_model[i] = config.hysteresis_model[i];
    s.hysteresis_model[i].reset(0.0);
  }
  return s;
}

namespace {

// Record the targets and latch a fault for a non-finite target or time, before the last stages.
void check_targets(TickState& state, const ChannelPressures& target_kPa, double t_s, TelemetryRecord& rec) noexcept {
  for (std::size_t i = 0; i < kFingerCount; ++i) {
    rec.target_kPa[i] = static_cast<float>(target_kPa[i]);
    if (!std::isfinite(target_kPa[i])) state.enter_fault(FaultCode::non_finite_target);
  }
  if (state.fault == FaultCode::none && !std::isfinite(t_s)) state.enter_fault(FaultCode::bad_time);
}

}  // namespace

TickResult tick(TickState& state, const TickConfig& config, const Scene& scene, const TouchSample& sample, double t_s,
                const TickInputs& inputs) noexcept {
  TickResult out;
  TelemetryRecord& rec = out.record;
  rec.x_mm = static_cast<float>(sample.x_mm);
  rec.y_mm = static_cast<float>(sample.y_mm);
  rec.force_N = static_cast<float>(sample.force_N);
  const double dt_s = state.started ? t_s - state.last_t_s : 0.0;

  FingersOnSkin fingers = finger_placement_stage(state, config, sample, t_s, rec);
  tissue_drag_stage(state, scene, fingers, dt_s, rec);
  ChannelPressures target = stiffness_target_stage(state, config, scene, fingers, t_s, rec);

  // What each channel compensates this tick, and the targets it compensates toward: the scene
  // where the fingers will be (channels compensating the whole target), the pulse now and ahead.
  const PulseField* arteries = scene.pulse();
  const double period_s = dt_s > 0 && std::isfinite(dt_s) ? dt_s : state.pulse.last_dt_s;
  const LagPlan plan =
      plan_lag_compensation(state.lag, config.lag_compensation, config.pulse.lag, config.pulse.compensate_lag,
                            inputs.compensate_lag, arteries != nullptr, period_s);
  LagTargets lag_targets;
  lag_targets.base_now_kPa = target;
  lag_targets.base_ahead_kPa = target;
  if (state.fault == FaultCode::none) state.lag.pen.observe(sample, config.lag_compensation.prediction);
  ++state.lag.ticks;
  // A lifted pen, or a run that restarts: the window's cached targets are stale. A finger that
  // is not pressing (a tracked one vented, or lifted by its own load cell) too.
  for (std::size_t i = 0; i < kFingerCount; ++i)
    if (!fingers.pressed || !fingers.finger_pressed[i]) state.lag.window_sampled[i] = false;
  look_ahead_stage(state, config, scene, plan, target, t_s, lag_targets, rec);

  // Scenes without arteries (maps) skip the pulse stage entirely.
  if (arteries) {
    std::array<PulseLookahead, kFingerCount> ahead{};
    for (std::size_t i = 0; i < kFingerCount; ++i)
      ahead[i] = {plan.lead_s[i], plan.rise_advance_s[i], plan.fall_advance_s[i]};
    PulseOutput pulse;
    apply_pulse_stage(state.pulse, PulseStageSetting{config.pulse, *arteries, inputs.pulse}, fingers,
                      TickTime{t_s, dt_s}, ahead, pulse);
    out.pulse_kPa = pulse.now_kPa;
    lag_targets.pulse_now_kPa = pulse.now_kPa;
    lag_targets.pulse_ahead_kPa = pulse.ahead_kPa;
    for (std::size_t i = 0; i < kFingerCount; ++i) target[i] += pulse.now_kPa[i];
  }
  check_targets(state, target, t_s, rec);
  const LagLimits limits{config.safety.p_max_kPa, config.safety.slew_kPa_per_s, config.lag_compensation.max_lead_kPa};
  out.compensated_kPa = lag_compensation_stage(state.lag, plan, lag_targets, limits, dt_s);
  safety_stage(state, config, hysteresis_inverse_stage(state, out.compensated_kPa), t_s, out);
  hysteresis_follow_setpoints(state, out);
  return out;
}

TickResult tick_direct(TickState& state, const TickConfig& config, const ChannelPressures& target_kPa,
                       double t_s) noexcept {
  TickResult out;
  out.record.flags |= kInContact;
  check_targets(state, target_kPa, t_s, out.record);
  out.compensated_kPa = target_kPa;
  safety_stage(state, config, hysteresis_inverse_stage(state, target_kPa), t_s, out);
  hysteresis_follow_setpoints(state, out);
  return out;
}

}  // namespace palprig
