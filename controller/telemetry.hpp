#pragma once
// One fixed-size record per tick: what the pen did, what each finger read and was commanded,
// and what the regulators reported. Trivially copyable so it moves through a lock-free queue
// and is written to the binary telemetry file as is.
#include <cstdint>
#include <type_traits>

#include "controller/fault.hpp"
#include "models/finger_layout.hpp"
#include "models/touch_sample.hpp"

namespace palprig {

struct TelemetryRecord {
  std::uint64_t tick = 0;
  double t_s = 0;
  float x_mm = 0, y_mm = 0, force_N = 0;
  float stiffness[kFingerCount] = {};
  float target_kPa[kFingerCount] = {};    // pressure the models ask for (before safety)
  float setpoint_kPa[kFingerCount] = {};  // what was sent to the backend
  float monitor_kPa[kFingerCount] = {};   // what the regulators reported
  float wake_latency_us = 0;              // real-time mode: wake-up minus deadline
  float io_us = 0;                        // time spent in the backend this tick
  FaultCode fault = FaultCode::none;
  std::uint8_t flags = 0;  // TelemetryFlag bits
  // Where the compiler would otherwise pad: the binary file holds each record's bytes as they
  // are, so every byte is a field and none is left undefined. Always 0.
  std::uint8_t reserved_after_flags[2] = {};
  // Where each finger was and how hard it pressed (the pen's triangle, or each tracked
  // fingertip with its own load cell), and why a tracked finger was vented.
  float finger_x_mm[kFingerCount] = {};
  float finger_y_mm[kFingerCount] = {};
  float finger_force_N[kFingerCount] = {};
  FingerVent finger_vent[kFingerCount] = {};
  std::uint8_t reserved_after_vents = 0;  // as reserved_after_flags
  // How far the tissue under each finger is carried by tissue dragging (paper 000's stick/slip;
  // 0 where the scene does not drag): the finger feels the tissue at its centre minus this.
  float drag_x_mm[kFingerCount] = {};
  float drag_y_mm[kFingerCount] = {};
};

enum TelemetryFlag : std::uint8_t {
  kInContact = 1 << 0,
  kClamped = 1 << 1,  // a target was above p_max and clamped
  kSlewLimited = 1 << 2,
  kVented = 1 << 3,
  kOverrun = 1 << 4,         // this tick finished after the next deadline
  kDisarmed = 1 << 5,        // the backend was not armed: vented, monitors still read
  kOwnPositions = 1 << 6,    // each finger at its own tracked position (finger_x_mm, finger_y_mm), no triangle
  kLagCompensated = 1 << 7,  // a channel's whole target was lag-compensated (calibration's identified regulators)
};

static_assert(std::is_trivially_copyable_v<TelemetryRecord>);

}  // namespace palprig
