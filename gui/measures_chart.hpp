#pragma once
// Paper 002 fig. 15 as a chart: Se, Sp, PPV and ACC per row of a trial summary (one bar series
// per condition) with their Wilson intervals, on a proportion axis from 0 to 1. A measure with
// no denominator (Sp and ACC of localisation, which has no true negatives) is a gap, not a 0.
#include "gui/chart_png.hpp"
#include "store/trial_summary.hpp"

namespace palprig::gui {

Chart measures_chart(const TrialSummary& summary);

}  // namespace palprig::gui
