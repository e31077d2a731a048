#pragma once
// The calibration workflow's charts: per channel the staircase readings with their fitted branch
// lines (paper 002 fig. 8), the hysteresis model driven through a major and nested minor loops
// over the recorded holds, and the evaluation's tracking error and output-against-target loops
// with and without compensation. The charts are made as data on any thread (the window fits on
// a worker) and written (PNG, and SVG with `svg`) on the application's thread.
#include <array>
#include <filesystem>
#include <string>
#include <vector>

#include "calibration/calibration_fit.hpp"
#include "calibration/compensation_evaluation.hpp"
#include "calibration/sweep_csv.hpp"
#include "charts/chart.hpp"

namespace palprig::charts {

struct NamedChart {
  std::string stem;  // file name without extension: "channel_1_regulator"
  Chart chart;
};

std::vector<NamedChart> fit_charts(const SweepData& data, const CalibrationResult& r);
std::vector<NamedChart> evaluation_charts(const EvaluationResult& r, const std::array<bool, kFingerCount>& channels);

// Writes STEM.png (and STEM.svg) for each chart into `dir` (created when missing); returns the
// files in order.
std::vector<std::filesystem::path> write_charts(const std::filesystem::path& dir, const std::vector<NamedChart>& charts,
                                                bool svg = false);

// Both in one call, for the command line.
std::vector<std::filesystem::path> plot_fit(const std::filesystem::path& dir, const SweepData& data,
                                            const CalibrationResult& r, bool svg = false);
std::vector<std::filesystem::path> plot_evaluation(const std::filesystem::path& dir, const EvaluationResult& r,
                                                   const std::array<bool, kFingerCount>& channels, bool svg = false);

}  // namespace palprig::charts
