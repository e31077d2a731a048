#pragma once
// The statistics view's two tables, filled from one TrialStatistics: the measures (per
// condition, per finger value, per tumor) and the comparisons between conditions (response-time
// t-test, paper 002 eq. 10 per measure). Cells say "n/a" where a measure has no cases.
#include <QString>

#include "store/trial_statistics.hpp"

class QTableWidget;

namespace palprig::gui {

// "0.857 [0.720, 0.933] n=42", or "n/a" when the measure has no cases.
QString measure_text(const Measure& m);

enum MeasureColumn {
  group_column = 0,
  trials_column,
  tp_column,
  fn_column,
  tn_column,
  fp_column,
  se_column,
  sp_column,
  ppv_column,
  acc_column,
  rt_column,
  rt_after_column,
  rt_reached_column,
  confidence_column,
  measure_column_count
};

void fill_measures_table(QTableWidget& table, const TrialStatistics& statistics);
void fill_comparisons_table(QTableWidget& table, const TrialStatistics& statistics);

}  // namespace palprig::gui
