#pragma once
// Writes the calibration file the controller reads (controller/calibration_file.hpp): the
// models the tick uses, their fit quality, and under "fits" the full tables (paper 002 fig. 8
// per channel and pooled, the regulator check, the hysteresis identification) for people and
// later tools. The file is written beside its destination and renamed into place only after
// the controller's own reader has accepted it, so a half-written or refused file never
// replaces a good one.
#include <filesystem>

#include <nlohmann/json.hpp>

#include "calibration/calibration_fit.hpp"

namespace palprig {

nlohmann::json calibration_json(const CalibrationResult& result);
nlohmann::json branch_fits_json(const BranchFits& fits);

// Returns the models as the controller loaded them back. Throws OutputError when the
// file cannot be written.
CalibrationModels write_calibration_file(const std::filesystem::path& path, const nlohmann::json& document);

}  // namespace palprig
