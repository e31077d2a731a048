#pragma once
// Charts of `palprig stats psychometric --plot`: one group's data (point area ~ trials) with
// its fitted curve, threshold and bootstrap interval; and a threshold database's staircase
// tracks, one chart per session with every track's levels and its reversals.
#include <filesystem>
#include <string>
#include <vector>

#include "charts/chart_png.hpp"
#include "statistics/psychometric_fit.hpp"
#include "store/threshold_store.hpp"

namespace palprig::charts {

Chart psychometric_chart(const std::string& group, const stats::PsychometricFit& fit, const std::string& level_name);

// Writes track_session<N>.png per session into `dir`; returns the paths written.
std::vector<std::string> write_track_charts(const std::vector<ThresholdTrialRow>& rows, const std::filesystem::path& dir);

}  // namespace palprig::charts
