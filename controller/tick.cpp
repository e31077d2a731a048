#include "controller/tick.hpp"

#include <algorithm>
#include <cmath>

#include "controller/pulse_stage.hpp"
#include "models/finger_placement.hpp"

namespace palprig {

TickState make_tick_state(const TickConfig& config) noexcept {
  TickState s;
  s.hysteresis_inverse = config.hysteresis_inverse;
  for (auto& inverse : s.hysteresis_inverse) inverse.reset(0.0);
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

ChannelPressures hysteresis_inverse_stage(TickState& state, const ChannelPressures& target_kPa) noexcept {
  ChannelPressures command = target_kPa;
  if (state.fault != FaultCode::none) return command;  // venting: the inverses keep their state
  for (std::size_t i = 0; i < kFingerCount; ++i)
    if (std::isfinite(target_kPa[i]) && !state.hysteresis_inverse[i].is_identity())
      command[i] = state.hysteresis_inverse[i].apply(target_kPa[i]);
  return command;
}

void safety_stage(TickState& state, const TickConfig& config, const ChannelPressures& command_kPa, double t_s,
                  TickResult& out) noexcept {
  TelemetryRecord& rec = out.record;
  const SafetyLimits& lim = config.safety;
  for (double p : command_kPa)
    if (!std::isfinite(p)) state.enter_fault(FaultCode::non_finite_target);  // a broken inverse, too

  if (state.fault != FaultCode::none) {
    // Vent: every channel to 0 kPa at once (no slew limit on the way down to safety).
    out.setpoint_kPa = {};
    rec.flags |= kVented;
  } else {
    // The first tick has no previous time: one nominal period. From the vented state (the
    // state's last setpoint is 0 kPa at the start and after restart_from_vented) the
    // setpoint therefore rises by at most one slew step, whatever the pen pressed on.
    const double dt = state.started ? std::max(t_s - state.last_t_s, 0.0) : config.period_s;
    const double max_step = lim.slew_kPa_per_s * dt;
    for (std::size_t i = 0; i < kFingerCount; ++i) {
      double p = command_kPa[i];
      if (p > lim.p_max_kPa) { p = lim.p_max_kPa; rec.flags |= kClamped; }
      if (p < 0) p = 0;
      const double prev = state.last_setpoint_kPa[i];
      if (p > prev + max_step) { p = prev + max_step; rec.flags |= kSlewLimited; }
      else if (p < prev - max_step) { p = prev - max_step; rec.flags |= kSlewLimited; }
      out.setpoint_kPa[i] = p;
    }
  }
  for (std::size_t i = 0; i < kFingerCount; ++i) rec.setpoint_kPa[i] = static_cast<float>(out.setpoint_kPa[i]);
  rec.fault = state.fault;
  rec.t_s = t_s;
  rec.tick = state.ticks++;
  state.last_setpoint_kPa = out.setpoint_kPa;
  state.last_t_s = t_s;
  state.started = true;
}

TickResult tick(TickState& state, const TickConfig& config, const Scene& scene, const TouchSample& sample,
                double t_s) noexcept {
  TickResult out;
  TelemetryRecord& rec = out.record;
  rec.x_mm = static_cast<float>(sample.x_mm);
  rec.y_mm = static_cast<float>(sample.y_mm);
  rec.force_N = static_cast<float>(sample.force_N);

  ChannelPressures target{};
  FingersOnSkin fingers;
  // Each bad reading is named for what is wrong with it (a NaN position is not a bad force).
  if (!std::isfinite(sample.x_mm) || !std::isfinite(sample.y_mm) || !finger_positions_finite(sample)) {
    state.enter_fault(FaultCode::bad_position);
  } else if (!std::isfinite(sample.t_s)) {
    state.enter_fault(FaultCode::bad_time);
  } else if (!std::isfinite(sample.force_N) || sample.force_N < 0 || !finger_forces_valid(sample)) {
    state.enter_fault(FaultCode::bad_sample);
  } else if (t_s - sample.t_s > config.safety.max_input_age_s) {
    state.enter_fault(FaultCode::input_stale);
  } else {
    // The triangle around the pen, or each finger at its own tracked position (issue 26); a
    // finger whose tool is out of view is vented (target 0 kPa) and says why in the record.
    const PlacedFingers placed = place_fingers(config.layout, sample, config.contact_force_N);
    fingers.centres = placed.centres;
    fingers.finger_force_N = placed.force_N;
    fingers.finger_pressed = placed.pressed;
    if (sample.own_positions) rec.flags |= kOwnPositions;
    for (std::size_t i = 0; i < kFingerCount; ++i) {
      rec.finger_x_mm[i] = static_cast<float>(placed.centres[i].x_mm);
      rec.finger_y_mm[i] = static_cast<float>(placed.centres[i].y_mm);
      rec.finger_force_N[i] = static_cast<float>(placed.force_N[i]);
      rec.finger_vent[i] = sample.fingers[i].vent;
    }
    if (sample.in_contact && sample.force_N >= config.contact_force_N) {
      rec.flags |= kInContact;
      fingers.pressed = true;
      fingers.force_N = sample.force_N;
      for (std::size_t i = 0; i < kFingerCount; ++i) {
        if (!placed.pressed[i]) continue;
        const double force_N = placed.force_N[i];
        const TissueSample felt = scene.sample(fingers.centres[i], force_N, t_s);
        rec.stiffness[i] = static_cast<float>(felt.stiffness);
        const double stress_kPa = config.stress.target_stress_kPa(felt.stiffness, force_N);
        target[i] = config.actuators[i].pressure_kPa(stress_kPa, config.stress.force_ratio(force_N));
      }
    }
  }
  if (!fingers.pressed) fingers.force_N = sample.force_N;
  // Scenes without arteries (maps) skip this entirely.
  if (const PulseField* arteries = scene.pulse()) {
    const PulseStageSetting setting{config.pulse, *arteries, config.safety.p_max_kPa, config.safety.slew_kPa_per_s};
    const TickTime time{t_s, state.started ? t_s - state.last_t_s : 0.0};
    apply_pulse_stage(state.pulse, setting, fingers, time, target, out.pulse_kPa);
  }
  check_targets(state, target, t_s, rec);
  safety_stage(state, config, hysteresis_inverse_stage(state, target), t_s, out);
  return out;
}

TickResult tick_direct(TickState& state, const TickConfig& config, const ChannelPressures& target_kPa,
                       double t_s) noexcept {
  TickResult out;
  out.record.flags |= kInContact;
  check_targets(state, target_kPa, t_s, out.record);
  safety_stage(state, config, hysteresis_inverse_stage(state, target_kPa), t_s, out);
  return out;
}

}  // namespace palprig
