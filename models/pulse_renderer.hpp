#pragma once
// Rendering the pulse on pneumatic actuators. The pulse is a pressure modulation added to a
// finger's stiffness pressure. A proportional regulator answers in about 50 ms (paper 002), so a
// 0.2-duty pulse at 160 BPM (75 ms) would come out late and rounded: the rig file's plant model
// (dead time + first-order lag + slew) is pre-compensated.
//
// The compensator works on the pulse part alone (the lag is linear, so the stiffness part is
// left exactly as the tick computes it). It keeps a model y of the pulse part of the regulator's
// output one dead time ahead, and each tick chooses the command u that brings y toward the
// wanted pulse one tick and one dead time from now (the waveform is known ahead, so the dead
// time is met by reading it early). The fastest move is
//     u = y + (want - y) / alpha,     alpha = 1 - exp(-dt / tau),
// but u is limited to what the rig can do: the total (stiffness + pulse) within 0..p_max, the
// command's slew limit (the safety stage's) and the regulator's own output slew. Because the
// command can only come back down at its slew rate, the push is the largest one from which the
// slew-limited return still stops y at the wanted level (checked by simulating the model,
// found by bisection): a boost that lands without overshoot, the fastest a first-order
// regulator allows under those limits.
//
// Even so an edge of a rectangular pulse takes time (about 10 ms for 8 kPa on the default rig).
// So that the felt transition is half-way at the true edge, the compensator measures how long
// its model takes to get half-way after a jump in what it is asked for, separately for rises
// and falls, and the pulse stage asks for rectangular edges that much earlier (anticipation).
// The pulse repeats every beat, so what one beat measures serves the next.
#include <array>
#include <atomic>

#include "models/artery.hpp"
#include "models/finger_layout.hpp"

namespace palprig {

// One channel's regulator as the rig file's plant section describes it.
struct RegulatorLag {
  double dead_time_s = 0.005;
  double time_constant_s = 0.050;
  double slew_kPa_per_s = 2000.0;
};

struct PulseRendering {
  bool compensate_lag = true;
  // Optional run-time switch (the GUI's lag compensation check box), read each tick with a
  // relaxed load: compensation is on when compensate_lag and the switch (if any) are both on.
  const std::atomic<bool>* compensate_lag_switch = nullptr;
  bool lag_compensation_on() const noexcept {
    return compensate_lag && (!compensate_lag_switch || compensate_lag_switch->load(std::memory_order_relaxed));
  }
  std::array<RegulatorLag, kFingerCount> lag{};
  // 003's force window as calibration measured it on this rig (60 and 120 mmHg), for arteries
  // whose scene gives none.
  bool has_measured_window = false;
  ForceWindow measured_window;
};

class LagCompensator {
 public:
  // Command for the pulse part. lo..hi bounds the pulse part so that the total stays in
  // 0..p_max; max_step_kPa is the command's slew allowance this tick. dt_s <= 0 (the first
  // tick) passes the wanted value through without advancing the model.
  double command(const RegulatorLag& lag, double want_ahead_kPa, double lo_kPa, double hi_kPa, double max_step_kPa,
                 double dt_s) noexcept;
  double predicted_kPa() const noexcept { return predicted_kPa_; }
  // How early rectangular edges should be asked for (s), as last measured.
  double rise_anticipation_s() const noexcept { return rise_anticipation_s_; }
  double fall_anticipation_s() const noexcept { return fall_anticipation_s_; }

 private:
  void measure_edges(double want, double dt_s) noexcept;

  double predicted_kPa_ = 0;
  double last_command_kPa_ = 0;
  double last_want_kPa_ = 0;
  // An edge being timed: where half-way is, which way, and for how long it has run.
  bool timing_ = false;
  double edge_mid_kPa_ = 0, edge_sign_ = 0, edge_elapsed_s_ = 0;
  double rise_anticipation_s_ = 0, fall_anticipation_s_ = 0;
};

// Everything the pulse stage keeps between ticks: fixed size, lives in the tick state.
struct PulseTickState {
  PulseClocks clocks;
  std::array<PulseActivation, kFingerCount> activation{};
  std::array<LagCompensator, kFingerCount> compensator{};
  double last_dt_s = 0.001;  // the loop's period as last seen (the first tick assumes 1 kHz)
};

}  // namespace palprig
