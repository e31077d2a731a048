#pragma once
// Rendering the pulse on pneumatic actuators. The pulse is a pressure modulation added to a
// finger's stiffness pressure. A proportional regulator answers in about 50 ms (paper 002), so a
// 0.2-duty pulse at 160 BPM (75 ms) would come out late and rounded: the regulator's dynamics
// (dead time + first-order lag + slew; calibration's identified model, else the rig file's plant
// section) are pre-compensated by the tick's lag compensation stage with the LagCompensator of
// models/lag_compensator.hpp, the same mechanism that compensates the stiffness target.
//
// Without whole-target compensation the compensator works on the pulse part alone (the lag is
// linear, so the stiffness part is left exactly as the tick computes it): the waveform is known
// ahead, so the dead time is met by reading it early, and rectangular edges are asked for
// earlier by the compensator's measured half-way times (anticipation). The pulse repeats every
// beat, so what one beat measures serves the next.
#include <array>

#include "models/artery.hpp"
#include "models/lag_compensator.hpp"
#include "models/finger_layout.hpp"

namespace palprig {

struct PulseRendering {
  // Compensation is on when this and the operator's switch of the tick (TickInputs) are both on.
  bool compensate_lag = true;
  std::array<RegulatorLag, kFingerCount> lag{};
  // 003's force window as calibration measured it on this rig (60 and 120 mmHg), for arteries
  // whose scene gives none.
  bool has_measured_window = false;
  ForceWindow measured_window;
};

// Everything the pulse stage keeps between ticks: fixed size, lives in the tick state.
struct PulseTickState {
  PulseClocks clocks;
  std::array<PulseActivation, kFingerCount> activation{};
  double last_dt_s = 0.001;  // the loop's period as last seen (the first tick assumes 1 kHz)
};

}  // namespace palprig
