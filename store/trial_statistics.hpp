#pragma once
// Everything the live statistics view shows of a trial store, computed in one pass of reads:
// the `stats trials` summaries per condition, per finger and per tumor (store/trial_summary),
// paper 002's response-time t-test between conditions, and paper 002's combined-interval
// comparison (eq. 10) of each measure between conditions (store/condition_comparisons, as
// `palprig stats trials` computes them). Pure: no Qt, so the GUI computes it
// on a worker thread and tests compute it directly.
#include <optional>
#include <string>
#include <vector>

#include "store/condition_comparisons.hpp"
#include "store/pulse_store.hpp"
#include "store/trial_summary.hpp"

namespace palprig {

struct TrialStatistics {
  double confidence = 0.95;
  TrialSummary by_condition;  // exactly `palprig stats trials --by condition`
  TrialSummary by_finger;     // discrimination: finger 1..3 (localisation rows "-" left out)
  TrialSummary by_tumor;      // localisation: per-tumor sensitivity ("-" = false marks, left out)
  // Between conditions (store/condition_comparisons: the same call and numbers as `palprig stats
  // trials --by condition`): Student's t-test of response times, paper 002 eq. 10 per measure.
  std::vector<ResponseTimeComparison> response_times;  // every pair of conditions
  std::vector<MeasureComparison> measures;             // every pair of conditions x measure
  // Pulse-localisation trials per condition: exactly what `palprig stats trials` prints for them
  // (PulseStore::summarise; SQLite stores only, as there). Empty without pulse trials.
  std::vector<PulseConditionSummary> pulse;
};

// Reads `store` (a read-only connection is enough). `options.by` is ignored: each part has its
// own grouping; `include_practice` and `confidence` apply to all of them.
TrialStatistics compute_trial_statistics(TrialStore& store, const SummaryOptions& options);

}  // namespace palprig
