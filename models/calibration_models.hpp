#pragma once
// What a rig's calibration holds, as model data: the stress model, each channel's actuator
// line and forward hysteresis model, and the measured pulse force window. Read from and
// written to the calibration file by formats/ and calibration/; turned into the tick's
// configuration by controller/tick_setup.hpp.
#include <array>
#include <cstddef>
#include <optional>
#include <string>

#include "models/finger_layout.hpp"
#include "models/hysteresis.hpp"
#include "models/stress_model.hpp"

namespace palprig {

// Paper 003's pulse force window as measured by calibration: the pressing forces read at the
// diastolic (60 mmHg) and systolic (120 mmHg) reference presses; the pulse amplitude scales as
// (F - f_min_N) / (f_max_N - f_min_N) while f_min_N <= F <= f_max_N.
struct MeasuredForceWindow {
  double f_min_N = 0, f_max_N = 0;
  double diastolic_mmHg = 60, systolic_mmHg = 120;
};

// A regulator channel's dynamics as calibration identified them from a step and a chirp
// (calibration/dynamics_fit.hpp): a first-order lag with dead time between the command (through
// the channel's hysteresis model) and the monitor, with how well it fits.
struct RegulatorDynamics {
  double dead_time_s = 0;
  double time_constant_s = 0;
  double r_squared = 0;  // of the monitor over the step and chirp samples
  double rms_residual_kPa = 0;
  double max_residual_kPa = 0;
  std::size_t samples = 0;
  double rate_hz = 0;  // the rate the samples were taken at
  // A lag of its own while exhausting (time_constant_s is then the filling one); 0: one lag.
  double exhaust_time_constant_s = 0;
};

// Below this R^2 a channel's identified dynamics are not trusted: its lag compensation stays off
// (a wrong model must never push a fingertip harder than the uncompensated rig would).
inline constexpr double kDefaultMinDynamicsRSquared = 0.98;
inline constexpr double kLowestMinDynamicsRSquared = 0.9;

// The calibration file's `lag_compensation` section: whether the tick compensates the whole
// target with the identified dynamics (off until identified and switched on), and its bounds.
struct LagCompensationChoice {
  bool enabled = false;
  double max_lead_kPa = 10.0;  // the command at most this far above the target
  double min_r_squared = kDefaultMinDynamicsRSquared;
  bool anticipate_edges = true;
};

struct CalibrationModels {
  std::string source = "(built-in paper 002 defaults)";
  std::string rig_id = "*";  // "*" fits any rig
  StressModel stress;
  std::array<ActuatorModel, kFingerCount> actuators{};
  std::array<PrandtlIshlinskii, kFingerCount> hysteresis{};               // forward models; identity when absent
  std::optional<MeasuredForceWindow> force_window;                        // absent until calibrated
  std::array<std::optional<RegulatorDynamics>, kFingerCount> dynamics{};  // absent until identified
  LagCompensationChoice lag_compensation;
};

}  // namespace palprig
