#pragma once
// Paper 002 fig. 15 as a chart: Se, Sp, PPV and ACC per row of a trial summary (one bar series
// per row: a condition, a finger value) with their Wilson intervals, on a proportion axis from 0
// to 1, and n above each bar. A measure with no denominator (Sp and ACC of localisation, which
// has no true negatives) is a gap labelled "n/a", not a 0.
#include <string>

#include "charts/chart_png.hpp"
#include "store/trial_summary.hpp"

namespace palprig::charts {

Chart measures_chart(const TrialSummary& summary);
// One proportion as a bar with its interval and "n=N" above it ("n/a" when undefined).
void add_measure_bar(ChartSeries& bars, const Measure& m);
// The same with another title, and `series_prefix` before each row's key in the legend
// ("finger " -> "finger 1").
Chart measures_chart(const TrialSummary& summary, const std::string& title, const std::string& series_prefix);

// Localisation: sensitivity per tumor (one bar per tumor, Wilson interval, n above each bar).
Chart tumor_sensitivity_chart(const TrialSummary& by_tumor);

}  // namespace palprig::charts
