#pragma once
// What `palprig calibrate fit` and `evaluate` print and save: the fit tables (paper 002
// fig. 8 layout), the evaluation comparison, their JSON forms and the evaluation trace CSV.
#include <filesystem>
#include <iosfwd>

#include <nlohmann/json.hpp>

#include "calibration/calibration_fit.hpp"
#include "calibration/compensation_evaluation.hpp"

namespace palprig {

void print_fit_report(std::ostream& out, const CalibrationResult& result, const std::string& written_to);

nlohmann::json evaluation_json(const EvaluationResult& result, const std::array<bool, kFingerCount>& channels);
void print_evaluation_report(std::ostream& out, const EvaluationResult& result,
                             const std::array<bool, kFingerCount>& channels);
// t_s,compensation,target_kPa,setpoint_1..3_kPa,monitor_1..3_kPa (both runs). Throws
// OutputError when the file cannot be written.
void write_evaluation_trace_csv(const std::filesystem::path& path, const EvaluationResult& result);

// Now as ISO 8601 UTC ("2026-11-22T12:00:00Z"), for the calibration file's date.
std::string utc_timestamp_now();

}  // namespace palprig
