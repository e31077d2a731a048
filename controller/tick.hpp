#pragma once
// The tick: one pass from pen sample to three setpoints (DESIGN.md "One tick"). A plain
// function of (state, configuration, scene, sample, time): no threads, clocks, allocation or
// exceptions, so tests and replays run it directly.
//
//   sample -> FingerLayout -> Scene::sample -> StressModel -> ActuatorModel
//          [-> + pulse (scenes with arteries only; controller/pulse_stage.hpp)]
//          -> HysteresisInverse -> Safety (clamp, slew, vent) -> setpoints + telemetry
//
// Experiments that present fixed per-finger pressures use tick_direct(), which enters at the
// hysteresis stage and passes the same safety stage.
#include <array>

#include "controller/fault.hpp"
#include "controller/telemetry.hpp"
#include "models/touch_sample.hpp"
#include "models/channel_pressures.hpp"
#include "models/finger_layout.hpp"
#include "models/hysteresis.hpp"
#include "models/pulse_renderer.hpp"
#include "models/safety_limits.hpp"
#include "models/scene.hpp"
#include "models/stress_model.hpp"

namespace palprig {

struct TickConfig {
  FingerLayout layout;
  StressModel stress;
  std::array<ActuatorModel, kFingerCount> actuators{};
  // Per-channel hysteresis model fitted by calibration; the tick applies its inverse.
  std::array<PrandtlIshlinskii, kFingerCount> hysteresis_inverse{};
  SafetyLimits safety;
  double contact_force_N = 0.05;    // below this the pen is lifted: targets go to 0 kPa
  // Pulse rendering (scenes with arteries): regulator-lag pre-compensation from the rig's plant.
  PulseRendering pulse;
};

struct TickState {
  ChannelPressures last_setpoint_kPa{};
  double last_t_s = 0;
  bool started = false;
  FaultCode fault = FaultCode::none;  // latched: once set, every later tick vents
  std::uint64_t ticks = 0;
  std::array<PrandtlIshlinskii, kFingerCount> compensator{};  // running inverse models
  PulseTickState pulse;  // pulse clocks, per-finger activation and lag compensators (fixed size)

  // Latch a fault (the first reason wins) so the next ticks vent.
  void enter_fault(FaultCode why) noexcept {
    if (fault == FaultCode::none) fault = why;
  }
};

struct TickResult {
  ChannelPressures setpoint_kPa{};
  ChannelPressures pulse_kPa{};  // the pulse each finger should feel now (before compensation); 0 without arteries
  TelemetryRecord record;
};

// Prepare a state for a run: copies the compensators from the configuration and resets them.
TickState make_tick_state(const TickConfig& config) noexcept;

TickResult tick(TickState& state, const TickConfig& config, const Scene& scene,
                const TouchSample& sample, double t_s) noexcept;

// Direct per-finger pressures (experiments): hysteresis compensation and safety only.
TickResult tick_direct(TickState& state, const TickConfig& config, const ChannelPressures& target_kPa,
                       double t_s) noexcept;

}  // namespace palprig
