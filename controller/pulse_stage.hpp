#pragma once
// The tick's pulse stage (DESIGN.md "One tick": "+ pulse" after the ActuatorModel). For each
// finger: the arteries in range and their activation (PulseField), the pulse pressure it should
// feel, and, with lag compensation on, the command that makes the regulator deliver it on time
// (LagCompensator). The result is added to the finger's target before the hysteresis inverse
// and the safety stage, which still clamp everything. Runs on the loop thread: no allocation,
// no locks, no exceptions. Includes nothing of the tick (the tick includes this).
#include <array>

#include "models/artery.hpp"
#include "models/channel_pressures.hpp"
#include "models/finger_layout.hpp"
#include "models/pulse_renderer.hpp"

namespace palprig {

// What the stage renders with: the rig's regulator lags, the scene's arteries, and the two
// safety limits the lag compensation must keep within.
struct PulseStageSetting {
  const PulseRendering& rendering;
  const PulseField& arteries;
  double p_max_kPa;
  double slew_kPa_per_s;
};

// Where the fingers are this tick. centres are valid only while pressed.
struct FingersOnSkin {
  bool pressed = false;
  std::array<Point2_mm, kFingerCount> centres{};
  double force_N = 0;
  // Per finger (issue 26: tracked fingers each with their own load cell, a vented finger): its
  // force and whether it presses. The pen gives every finger force_N and pressed.
  std::array<double, kFingerCount> finger_force_N{};
  std::array<bool, kFingerCount> finger_pressed{};
};

// The tick's time and the time since the previous tick (0 on the first).
struct TickTime {
  double t_s = 0;
  double dt_s = 0;
};

// Adds each finger's pulse command to target_kPa and reports the intended pulse in pulse_kPa.
void apply_pulse_stage(PulseTickState& state, const PulseStageSetting& setting, const FingersOnSkin& fingers,
                       const TickTime& time, ChannelPressures& target_kPa, ChannelPressures& pulse_kPa) noexcept;

}  // namespace palprig
