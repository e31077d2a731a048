#pragma once
// Charts of `palprig stats psychometric --plot`: one group's data (point area ~ trials) with
// its fitted curve, threshold and bootstrap interval; and a threshold database's staircase
// tracks, one chart per session with every track's levels and its reversals.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "charts/chart_png.hpp"
#include "statistics/psychometric_fit.hpp"
#include "store/threshold_store.hpp"

namespace palprig::charts {

Chart psychometric_chart(const std::string& group, const stats::PsychometricFit& fit, const std::string& level_name);

// One chart per session: every track's levels by trial of the track, its reversals marked.
struct SessionTrackChart {
  std::int64_t session = 0;
  Chart chart;
};
std::vector<SessionTrackChart> track_charts(const std::vector<ThresholdTrialRow>& rows);

// Writes track_session<N>.png per session into `dir`; returns the paths written.
std::vector<std::string> write_track_charts(const std::vector<ThresholdTrialRow>& rows,
                                            const std::filesystem::path& dir);

}  // namespace palprig::charts
