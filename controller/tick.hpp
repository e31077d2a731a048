#pragma once
// The tick: one pass from pen sample to three setpoints (docs/architecture.md, "The tick"). A plain
// function of (state, configuration, scene, sample, time): no threads, clocks, allocation or
// exceptions, so tests and replays run it directly.
//
//   sample -> FingerLayout [-> tissue drag (scenes whose layers drag; models/tissue_drag.hpp)]
//          -> Scene::sample -> StressModel -> ActuatorModel
//          [-> pulse stage (scenes with arteries only; controller/pulse_stage.hpp)]
//          -> lag compensation stage (controller/lag_compensation_stage.hpp: the pulse part, or
//             with identified regulators the whole target, sampled where the fingers will be)
//          -> hysteresis inverse stage -> safety stage (clamp, slew, vent) -> setpoints + telemetry
//
// Experiments that present fixed per-finger pressures, and calibration, use tick_direct(),
// which enters at the hysteresis inverse stage and passes the same safety stage. What happens
// around the tick (backend write, monitors, faults, venting) is controller/rig_step.hpp's.
#include <array>

#include "controller/fault.hpp"
#include "controller/lag_compensation_stage.hpp"
#include "controller/telemetry.hpp"
#include "models/touch_sample.hpp"
#include "models/channel_pressures.hpp"
#include "models/finger_layout.hpp"
#include "models/hysteresis.hpp"
#include "models/pulse_renderer.hpp"
#include "models/safety_limits.hpp"
#include "models/scene.hpp"
#include "models/stress_model.hpp"
#include "models/tissue_drag.hpp"

namespace palprig {

struct TickConfig {
  FingerLayout layout;
  StressModel stress;
  std::array<ActuatorModel, kFingerCount> actuators{};
  // Per channel, the inverse of the hysteresis model calibration fitted (identity: no
  // compensation). The hysteresis inverse stage inverts the model it came from
  // (TickState::hysteresis_model) at each point of the actuator's history.
  std::array<PrandtlIshlinskii, kFingerCount> hysteresis_inverse{};
  SafetyLimits safety;
  double contact_force_N = 0.05;  // below this the pen is lifted: targets go to 0 kPa
  // Nominal time between ticks (1 / loop rate). The first tick of a run has no previous time,
  // so its slew allowance from the vented state is one nominal period's.
  double period_s = 0.001;
  // Pulse rendering (scenes with arteries): regulator-lag pre-compensation from the rig's plant.
  PulseRendering pulse;
  // The regulators' identified dynamics and whether the whole target is lag-compensated
  // (calibration's `lag_compensation`; off unless identified and switched on).
  LagCompensationSetting lag_compensation;
};

struct TickState {
  // Where the safety stage's slew limiter starts from: the last setpoint sent, or 0 kPa (the
  // vented state) after a (re)start.
  ChannelPressures last_setpoint_kPa{};
  double last_t_s = 0;
  bool started = false;               // a tick has run: last_t_s is a time
  FaultCode fault = FaultCode::none;  // latched: once set, every later tick vents
  std::uint64_t ticks = 0;
  // Per channel, the hysteresis model TickConfig::hysteresis_inverse inverts (identity: none),
  // its play states driven by the setpoints actually sent, with the regulator's exhaust near
  // 0 kPa: the actuator's state as the inverse stage needs it.
  std::array<PrandtlIshlinskii, kFingerCount> hysteresis_model{};
  PulseTickState pulse;      // pulse clocks and per-finger activation (fixed size)
  LagCompensationState lag;  // per-channel lag compensators and the pen's recent samples
  // Per finger: how the tissue under it is dragged, and the layer it pressed into last tick
  // (whose stick/slip parameters apply).
  std::array<FingerDrag, kFingerCount> drag{};
  std::array<int, kFingerCount> drag_layer{-1, -1, -1};

  // Latch a fault (the first reason wins) so the next ticks vent.
  void enter_fault(FaultCode why) noexcept {
    if (fault == FaultCode::none) fault = why;
  }
  // The channels were vented without a fault (a link outage, a disarm): the next tick rises
  // from 0 kPa under the slew limit again, as on the first tick. Time and the pulse clocks go on.
  void restart_from_vented() noexcept {
    last_setpoint_kPa = {};
    lag.restart_from_vented();
  }
};

struct TickResult {
  ChannelPressures setpoint_kPa{};
  ChannelPressures pulse_kPa{};  // the pulse each finger should feel now (before compensation); 0 without arteries
  // What the lag compensation stage commanded (before the hysteresis inverse and the safety
  // stage); equal to the target where nothing is compensated.
  ChannelPressures compensated_kPa{};
  TelemetryRecord record;
};

// Prepare a state for a run: the hysteresis models of the configuration's inverses, relaxed at 0.
TickState make_tick_state(const TickConfig& config) noexcept;

TickResult tick(TickState& state, const TickConfig& config, const Scene& scene, const TouchSample& sample,
                double t_s) noexcept;

// Direct per-finger pressures (experiments, calibration): hysteresis inverse and safety only.
TickResult tick_direct(TickState& state, const TickConfig& config, const ChannelPressures& target_kPa,
                       double t_s) noexcept;

// The last two stages, named as in the design diagram (tick and tick_direct call them in this
// order). The hysteresis inverse stage turns targets into commands that land the actuator on the
// target on both branches (the model's input for the target at the actuator's present state,
// PrandtlIshlinskii::input_for, which equals the analytic inverse above the regulator's exhaust
// and handles it below); it leaves non-finite targets for the safety stage and does nothing
// once a fault is latched. The states then follow what the safety stage sent
// (hysteresis_follow_setpoints, called by tick and tick_direct after it).
ChannelPressures hysteresis_inverse_stage(TickState& state, const ChannelPressures& target_kPa) noexcept;
// The safety stage: vent on a latched fault or a non-finite command; otherwise clamp to
// [0, p_max] and limit each change to the slew rate (from 0 kPa after a (re)start). Fills the
// setpoints and the record's setpoint, flag, fault, time and tick fields, and advances the state.
void safety_stage(TickState& state, const TickConfig& config, const ChannelPressures& command_kPa, double t_s,
                  TickResult& out) noexcept;

}  // namespace palprig
