#pragma once
// What a rig's calibration holds, as model data: the stress model, each channel's actuator
// line and forward hysteresis model, and the measured pulse force window. Read from and
// written to the calibration file by formats/ and calibration/; turned into the tick's
// configuration by controller/tick_setup.hpp.
#include <array>
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

struct CalibrationModels {
  std::string source = "(built-in paper 002 defaults)";
  std::string rig_id = "*";  // "*" fits any rig
  StressModel stress;
  std::array<ActuatorModel, kFingerCount> actuators{};
  std::array<PrandtlIshlinskii, kFingerCount> hysteresis{};  // forward models; identity when absent
  std::optional<MeasuredForceWindow> force_window;            // absent until calibrated
};

}  // namespace palprig
