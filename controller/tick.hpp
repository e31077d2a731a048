#pragma once
// The tick: one pass from pen sample to three setpoints (docs/architecture.md, "The tick"). A
// plain function of (state, configuration, scene, sample, the operator's inputs, time): no
// threads, clocks, allocation or exceptions, so tests and replays run it directly. Each stage is
// a named function, called in this order:
//
//   finger_placement_stage   the sample checked, the three fingers placed (the pen's triangle, or
//                            each tracked finger at its own position with its own force)
//   tissue_drag_stage        what lies under a sticking finger moves with it (scenes whose
//                            layers drag; models/tissue_drag.hpp)
//   stiffness_target_stage   Scene::sample -> StressModel -> ActuatorModel, per finger
//   look_ahead_stage         with the regulators' dynamics identified: the targets where the
//                            fingers will be (controller/lag_compensation_stage.hpp plans it)
//   apply_pulse_stage        the pulse each finger should feel now and ahead (scenes with
//                            arteries only; controller/pulse_stage.hpp)
//   lag_compensation_stage   the inverse of the regulators' lag, bounded
//   hysteresis_inverse_stage the command that lands the actuator on the target on both branches
//   safety_stage             clamp to [0, p_max], slew limit, vent on fault -> setpoints + record
//
// Experiments that present fixed per-finger pressures, and calibration, use tick_direct(),
// which enters at the hysteresis inverse stage and passes the same safety stage. What happens
// around the tick (backend write, monitors, faults, venting) is controller/rig_step.hpp's.
#include <array>

#include "controller/fault.hpp"
#include "controller/lag_compensation_stage.hpp"
#include "controller/pulse_stage.hpp"
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

// What the operator sets while a run goes on, as it stands this tick: the tick's inputs beside
// the pen sample (the loop reads them once per tick from controller/operator_switches.hpp). The
// defaults are the configuration's own behaviour.
struct TickInputs {
  bool compensate_lag = true;  // the window's lag compensation switch (with the configuration's)
  PulseSettings pulse;         // each artery's rate and amplitude (NaN: the scene's)
};

struct TickConfig {
  FingerLayout layout;
  StressModel stress;
  std::array<ActuatorModel, kFingerCount> actuators{};
  // Per channel, the forward hysteresis model calibration fitted (identity: no compensation),
  // symmetric or asymmetric. The hysteresis inverse stage inverts it exactly
  // (TickState::hysteresis_model, its copy driven by the setpoints sent) at each point of the
  // actuator's history, on either branch.
  std::array<PrandtlIshlinskii, kFingerCount> hysteresis_model{};
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
  // Per channel, the hysteresis model of TickConfig::hysteresis_model (identity: none),
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

TickResult tick(TickState& state, const TickConfig& config, const Scene& scene, const TouchSample& sample, double t_s,
                const TickInputs& inputs = {}) noexcept;

// Direct per-finger pressures (experiments, calibration): hysteresis inverse and safety only.
TickResult tick_direct(TickState& state, const TickConfig& config, const ChannelPressures& target_kPa,
                       double t_s) noexcept;

// The stages, in the order tick() calls them (see the top of this file). Each fills its part of
// the record. Exposed so that a test can run one stage alone.

// The sample checked (a bad position, time, force or a stale sample latches a fault named for
// what is wrong with it) and the fingers placed.
FingersOnSkin finger_placement_stage(TickState& state, const TickConfig& config, const TouchSample& sample, double t_s,
                                     TelemetryRecord& rec) noexcept;
// Each pressing finger feels the tissue now under it, which a sticking finger has carried along.
void tissue_drag_stage(TickState& state, const Scene& scene, FingersOnSkin& fingers, double dt_s,
                       TelemetryRecord& rec) noexcept;
// Per pressing finger: the scene's stiffness, the stress model and the channel's actuator line.
ChannelPressures stiffness_target_stage(TickState& state, const TickConfig& config, const Scene& scene,
                                        const FingersOnSkin& fingers, double t_s, TelemetryRecord& rec) noexcept;
// Channels that compensate their whole target: the target where the fingers will be, from the
// pen's past samples only (the plan says which channels and how far ahead).
void look_ahead_stage(TickState& state, const TickConfig& config, const Scene& scene, const LagPlan& plan,
                      const ChannelPressures& target_now_kPa, double t_s, LagTargets& targets,
                      TelemetryRecord& rec) noexcept;
// The hysteresis inverse stage turns targets into commands that land the actuator on the target on
// both branches (the model's input for the target at the actuator's present state,
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
// After the safety stage: the hysteresis models follow the setpoints actually sent.
void hysteresis_follow_setpoints(TickState& state, const TickResult& out) noexcept;

}  // namespace palprig
