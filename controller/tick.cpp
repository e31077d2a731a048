#include "controller/tick.hpp"

#include <algorithm>
#include <cmath>

#include "controller/pulse_stage.hpp"

namespace palprig {

TickState make_tick_state(const TickConfig& config) noexcept {
  TickState s;
  s.compensator = config.hysteresis_inverse;
  for (auto& c : s.compensator) c.reset(0.0);
  return s;
}

namespace {

// Hysteresis compensation, then the safety stage; fills setpoints and the record's outputs.
void finish(TickState& state, const TickConfig& config, const ChannelPressures& target_kPa, double t_s,
            TickResult& out) noexcept {
  TelemetryRecord& rec = out.record;
  const SafetyLimits& lim = config.safety;
  for (std::size_t i = 0; i < kFingerCount; ++i) {
    rec.target_kPa[i] = static_cast<float>(target_kPa[i]);
    if (!std::isfinite(target_kPa[i])) state.enter_fault(FaultCode::non_finite_target);
  }
  if (state.fault == FaultCode::none && !std::isfinite(t_s)) state.enter_fault(FaultCode::bad_time);

  if (state.fault != FaultCode::none) {
    // Vent: every channel to 0 kPa at once (no slew limit on the way down to safety).
    out.setpoint_kPa = {};
    rec.flags |= kVented;
  } else {
    const double dt = state.started ? std::max(t_s - state.last_t_s, 0.0) : 0.0;
    const double max_step = lim.slew_kPa_per_s * dt;
    for (std::size_t i = 0; i < kFingerCount; ++i) {
      double p = target_kPa[i];
      if (!state.compensator[i].is_identity()) p = state.compensator[i].apply(p);
      if (!std::isfinite(p)) {  // a broken compensator must not reach the rig either
        state.enter_fault(FaultCode::non_finite_target);
        p = 0;
      }
      if (p > lim.p_max_kPa) { p = lim.p_max_kPa; rec.flags |= kClamped; }
      if (p < 0) p = 0;
      if (state.started) {
        const double prev = state.last_setpoint_kPa[i];
        if (p > prev + max_step) { p = prev + max_step; rec.flags |= kSlewLimited; }
        else if (p < prev - max_step) { p = prev - max_step; rec.flags |= kSlewLimited; }
      }
      out.setpoint_kPa[i] = p;
    }
    if (state.fault != FaultCode::none) { out.setpoint_kPa = {}; rec.flags |= kVented; }
  }
  for (std::size_t i = 0; i < kFingerCount; ++i) rec.setpoint_kPa[i] = static_cast<float>(out.setpoint_kPa[i]);
  rec.fault = state.fault;
  rec.t_s = t_s;
  rec.tick = state.ticks++;
  state.last_setpoint_kPa = out.setpoint_kPa;
  state.last_t_s = t_s;
  state.started = true;
}

}  // namespace

TickResult tick(TickState& state, const TickConfig& config, const Scene& scene, const TouchSample& sample,
                double t_s) noexcept {
  TickResult out;
  TelemetryRecord& rec = out.record;
  rec.x_mm = static_cast<float>(sample.x_mm);
  rec.y_mm = static_cast<float>(sample.y_mm);
  rec.force_N = static_cast<float>(sample.force_N);

  ChannelPressures target{};
  std::array<Point2_mm, kFingerCount> fingers{};
  bool pressed = false;
  // Each bad reading is named for what is wrong with it (a NaN position is not a bad force).
  if (!std::isfinite(sample.x_mm) || !std::isfinite(sample.y_mm)) {
    state.enter_fault(FaultCode::bad_position);
  } else if (!std::isfinite(sample.t_s)) {
    state.enter_fault(FaultCode::bad_time);
  } else if (!std::isfinite(sample.force_N) || sample.force_N < 0) {
    state.enter_fault(FaultCode::bad_sample);
  } else if (t_s - sample.t_s > config.safety.max_input_age_s) {
    state.enter_fault(FaultCode::input_stale);
  } else if (sample.in_contact && sample.force_N >= config.contact_force_N) {
    rec.flags |= kInContact;
    pressed = true;
    fingers = config.layout.centres(sample.x_mm, sample.y_mm);
    const double ratio = config.stress.force_ratio(sample.force_N);
    for (std::size_t i = 0; i < kFingerCount; ++i) {
      const TissueSample felt = scene.sample(fingers[i], sample.force_N, t_s);
      rec.stiffness[i] = static_cast<float>(felt.stiffness);
      const double stress_kPa = config.stress.target_stress_kPa(felt.stiffness, sample.force_N);
      target[i] = config.actuators[i].pressure_kPa(stress_kPa, ratio);
    }
  }
  // Scenes without arteries (maps) skip this entirely.
  if (const PulseField* arteries = scene.pulse()) {
    const double dt_s = state.started ? t_s - state.last_t_s : 0.0;
    apply_pulse_stage(state.pulse, config.pulse, config.safety, *arteries, pressed, fingers, sample.force_N, t_s, dt_s,
                      target, out.pulse_kPa);
  }
  finish(state, config, target, t_s, out);
  return out;
}

TickResult tick_direct(TickState& state, const TickConfig& config, const ChannelPressures& target_kPa,
                       double t_s) noexcept {
  TickResult out;
  out.record.flags |= kInContact;
  finish(state, config, target_kPa, t_s, out);
  return out;
}

}  // namespace palprig
