#pragma once
// The calibration workflow's charts, drawn with chart_png: per channel the staircase readings
// with their fitted branch lines (paper 002 fig. 8), the hysteresis model driven through a
// major and nested minor loops, and the evaluation's tracking error and output-against-target
// loops with and without compensation. Each function writes PNG files into `dir` (created
// when missing) and returns them in order.
#include <array>
#include <filesystem>
#include <vector>

#include "calibration/calibration_fit.hpp"
#include "calibration/compensation_evaluation.hpp"
#include "calibration/sweep_csv.hpp"

namespace palprig::charts {

std::vector<std::filesystem::path> plot_fit(const std::filesystem::path& dir, const SweepData& data,
                                            const CalibrationResult& r);
std::vector<std::filesystem::path> plot_evaluation(const std::filesystem::path& dir, const EvaluationResult& r,
                                                   const std::array<bool, kFingerCount>& channels);

}  // namespace palprig::charts
