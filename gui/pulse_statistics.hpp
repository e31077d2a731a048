#pragma once
// The statistics view's pulse-localisation part: the rows PulseStore::summarise computes (the
// numbers `palprig stats trials` prints for pulse trials) as charts and a table. Hit rate per
// condition with its Wilson interval and n; the mark's distance to the artery centreline, mean
// and median (bars: median with the quartiles as its range).
#include <vector>

#include "charts/chart_png.hpp"
#include "store/pulse_store.hpp"

class QTableWidget;

namespace palprig::gui {

charts::Chart pulse_hit_rate_chart(const std::vector<PulseConditionSummary>& rows, double confidence);
charts::Chart pulse_distance_chart(const std::vector<PulseConditionSummary>& rows);

enum PulseStatisticsColumn {
  pulse_condition_column = 0,
  pulse_trials_column,
  pulse_answered_column,
  pulse_hits_column,
  pulse_hit_rate_column,
  pulse_mean_column,
  pulse_median_column,
  pulse_iqr_column,
  pulse_column_count
};

void fill_pulse_table(QTableWidget& table, const std::vector<PulseConditionSummary>& rows, double confidence);

}  // namespace palprig::gui
