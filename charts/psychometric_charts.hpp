#pragma once
// Charts of `palprig stats psychometric --plot` and `export --plot`: one group's data (the
// proportion at each level, point area ~ trials) with its fitted curve and its threshold (a
// marker on the curve with the bootstrap interval as a horizontal whisker, its value and where it
// is taken printed beside it); and a threshold database's tracks, one chart per session, each
// track's levels trial by trial with its reversals marked and its own threshold estimate as a
// dashed line, labelled with the proportion correct it refers to.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "charts/chart_png.hpp"
#include "statistics/psychometric_fit.hpp"
#include "store/threshold_store.hpp"
#include "store/threshold_summary.hpp"

namespace palprig::charts {

// `level_name` is the level column; level_kPa is drawn as "pressure increment (kPa)".
// `response_name`: "correct" (2AFC) or a yes/no column, for the y axis.
Chart psychometric_chart(const std::string& group, const stats::PsychometricFit& fit, const std::string& level_name,
                         const std::string& response_name = "correct");

// One chart per session: every track's levels by trial of the track, its reversals marked, and
// (when `estimates` has the track) its threshold estimate.
struct SessionTrackChart {
  std::int64_t session = 0;
  Chart chart;
};
std::vector<SessionTrackChart> track_charts(const std::vector<ThresholdTrialRow>& rows,
                                            const std::vector<ThresholdTrackSummary>& estimates);

}  // namespace palprig::charts
