#pragma once
// The calibration file (JSON, versioned) holds the per-channel models the tick uses: the
// stress model, each actuator's stress-vs-pressure line and, once identified, its hysteresis
// model (the tick applies the inverse). `palprig calibrate fit` writes it; without one, the
// paper 002 defaults apply (data/calibration/paper002.json holds the same numbers).
#include <array>
#include <filesystem>
#include <optional>
#include <string>

#include "models/calibration_models.hpp"

namespace palprig {

inline constexpr int kCalibrationFileVersion = 1;
// Bounds of an actuator line (stress = slope * p + intercept_kPa) beyond the stress model's own:
// README, "Hardening notes".
inline constexpr double kMaxActuatorSlope = 1000;  // kPa of stress per kPa of air
inline constexpr double kMinActuatorIntercept_kPa = -1000;

// Throws InputError naming the field: wrong version, channel count, degenerate fits (a slope of
// 0 or a hysteresis model without an inverse) are refused.
CalibrationModels load_calibration_file(const std::filesystem::path& path);
// Refuses a calibration made for another rig.
void check_calibration_matches(const CalibrationModels& cal, const std::string& rig_id, const std::string& rig_source);

}  // namespace palprig
