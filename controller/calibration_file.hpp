#pragma once
// The calibration file (JSON, versioned) holds the per-channel models the tick uses: the
// stress model, each actuator's stress-vs-pressure line and, once identified, its hysteresis
// model (the tick applies the inverse). `palprig calibrate fit` writes it; without one, the
// paper 002 defaults apply (data/calibration/paper002.json holds the same numbers).
#include <array>
#include <filesystem>
#include <optional>
#include <string>

#include "controller/tick.hpp"

namespace palprig {

inline constexpr int kCalibrationFileVersion = 1;

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

// Throws InputError naming the field: wrong version, channel count, degenerate fits (a slope of
// 0 or a hysteresis model without an inverse) are refused.
CalibrationModels load_calibration_file(const std::filesystem::path& path);
// Refuses a calibration made for another rig.
void check_calibration_matches(const CalibrationModels& cal, const std::string& rig_id, const std::string& rig_source);
// Fill a tick configuration from a rig and its calibration.
struct RigConfig;
TickConfig make_tick_config(const RigConfig& rig, const CalibrationModels& cal);

}  // namespace palprig
