#pragma once
// The statistics view's pulse-localisation table: the rows PulseStore::summarise computes (the
// numbers `palprig stats trials` prints for pulse trials). Hit rate per condition with its Wilson
// interval and n; the mark's distance to the artery centreline, mean, median and IQR. Its charts
// are charts/measures_chart's (pulse_hit_rate_chart, pulse_distance_chart), as `export --plot`
// draws them.
#include <vector>

#include "store/pulse_store.hpp"

class QTableWidget;

namespace palprig::gui {

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
