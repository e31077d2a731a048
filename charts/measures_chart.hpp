#pragma once
// Proportions with their Wilson intervals as charts: paper 002 fig. 15 (Se, Sp, PPV, ACC per row
// of a trial summary: a condition, a finger value), per-tumor sensitivity (localisation) and the
// pulse-localisation hit rate per condition. Each proportion is a point with its interval as a
// whisker (points rather than bars: the axis is zoomed to where the proportions are, often 0.85
// to 1, and a bar cut off at the axis' foot would misstate its length), its value and n above
// it; the series of several rows sit side by side within each measure. A proportion with no
// denominator (Sp and ACC of localisation, which has no true negatives) is "n/a" at the axis'
// foot, never a 0.
#include <string>
#include <vector>

#include "charts/chart_png.hpp"
#include "store/pulse_store.hpp"
#include "store/trial_summary.hpp"

namespace palprig::charts {

Chart measures_chart(const TrialSummary& summary);
// One proportion as a point with its interval and "value\nn=N" above it ("n/a" when undefined).
void add_measure_point(ChartSeries& points, const Measure& m);
// The same with another title, and `series_prefix` before each row's key in the legend
// ("finger " -> "finger 1").
Chart measures_chart(const TrialSummary& summary, const std::string& title, const std::string& series_prefix);

// Localisation: sensitivity per tumor (one point per tumor, Wilson interval, value and n).
Chart tumor_sensitivity_chart(const TrialSummary& by_tumor);

// Pulse localisation: the hit rate per condition with its Wilson interval, value and n.
Chart pulse_hit_rate_chart(const std::vector<PulseConditionSummary>& rows, double confidence);
// Pulse localisation: the distance from the mark to the artery, median with quartiles per
// condition (answered trials), n above each.
Chart pulse_distance_chart(const std::vector<PulseConditionSummary>& rows);

}  // namespace palprig::charts
