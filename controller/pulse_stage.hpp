#pragma once
// The tick's pulse stage (docs/architecture.md, "The tick": after the ActuatorModel). For each
// finger: the arteries in range and their activation (PulseField) and the pulse pressure it
// should feel now and, for the lag compensation stage (controller/lag_compensation_stage.hpp,
// which compensates the regulators' lag for the pulse and the stiffness target alike), the pulse
// it should feel a lead ahead, its rectangular edges asked for earlier by the compensator's
// measured half-way times. Runs on the loop thread: no allocation, no locks, no exceptions.
// Includes nothing of the tick (the tick includes this).
#include <array>

#include "models/artery.hpp"
#include "models/channel_pressures.hpp"
#include "models/finger_layout.hpp"
#include "models/pulse_renderer.hpp"

namespace palprig {

// What the stage renders with: the rig's calibrated force window, the scene's arteries and the
// operator's rates and amplitudes this tick.
struct PulseStageSetting {
  const PulseRendering& rendering;
  const PulseField& arteries;
  const PulseSettings& settings;
};

// Where the fingers are this tick. centres are valid only while pressed.
struct FingersOnSkin {
  bool pressed = false;
  std::array<Point2_mm, kFingerCount> centres{};
  double force_N = 0;
  // Per finger (tracked fingers each with their own load cell, a vented finger): its
  // force and whether it presses. The pen gives every finger force_N and pressed.
  std::array<double, kFingerCount> finger_force_N{};
  std::array<bool, kFingerCount> finger_pressed{};
};

// The tick's time and the time since the previous tick (0 on the first).
struct TickTime {
  double t_s = 0;
  double dt_s = 0;
};

// The pulse each finger should feel now, and ahead (by each finger's PulseLookahead: lead_s 0
// gives the pulse now).
struct PulseOutput {
  ChannelPressures now_kPa{};
  ChannelPressures ahead_kPa{};
};

void apply_pulse_stage(PulseTickState& state, const PulseStageSetting& setting, const FingersOnSkin& fingers,
                       const TickTime& time, const std::array<PulseLookahead, kFingerCount>& ahead,
                       PulseOutput& out) noexcept;

}  // namespace palprig
