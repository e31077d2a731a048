#pragma once
// The tick's pulse stage (DESIGN.md "One tick": "+ pulse" after the ActuatorModel). For each
// finger: the arteries in range and their activation (PulseField), the pulse pressure it should
// feel, and, with lag compensation on, the command that makes the regulator deliver it on time
// (LagCompensator). The result is added to the finger's target before the hysteresis inverse
// and the safety stage, which still clamp everything. Runs on the loop thread: no allocation,
// no locks, no exceptions.
#include <array>

#include "models/channel_pressures.hpp"
#include "models/artery.hpp"
#include "models/finger_layout.hpp"
#include "models/pulse_renderer.hpp"

namespace palprig {

struct SafetyLimits;

// pressed: the pen is down (fingers valid); dt_s: time since the previous tick (0 on the first).
// Adds each finger's pulse command to target_kPa and reports the intended pulse in pulse_kPa.
void apply_pulse_stage(PulseTickState& state, const PulseRendering& rendering, const SafetyLimits& safety,
                       const PulseField& arteries, bool pressed, const std::array<Point2_mm, kFingerCount>& fingers,
                       double force_N, double t_s, double dt_s, ChannelPressures& target_kPa,
                       ChannelPressures& pulse_kPa) noexcept;

}  // namespace palprig
