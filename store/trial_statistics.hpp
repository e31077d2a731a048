#pragma once
// Everything the live statistics view shows of a trial store, computed in one pass of reads:
// the `stats trials` summaries per condition, per finger and per tumor (store/trial_summary),
// paper 002's response-time t-test between conditions, and paper 002's combined-interval
// comparison (eq. 10) of each measure between conditions. Pure: no Qt, so the GUI computes it
// on a worker thread and tests compute it directly.
#include <optional>
#include <string>
#include <vector>

#include "statistics/statistics_proportion.hpp"
#include "statistics/statistics_ttest.hpp"
#include "store/pulse_store.hpp"
#include "store/trial_summary.hpp"

namespace palprig {

// Response times of two conditions, Student's pooled-variance t-test as in paper 002. `test` is
// empty (with the reason in `why_not`) when a side has fewer than 2 answered trials or both sides
// are constant.
struct ResponseTimeComparison {
  std::string first, second;  // condition names, first < second
  std::optional<stats::TTestResult> test;
  std::string why_not;
};

// One measure (Se, Sp, PPV or ACC) of two conditions, paper 002 eq. 10. Only made when the
// measure is defined (has cases) in both conditions.
struct MeasureComparison {
  std::string measure;        // "Se", "Sp", "PPV", "ACC"
  std::string first, second;  // condition names, first < second
  stats::ProportionComparison comparison;
};

struct TrialStatistics {
  double confidence = 0.95;
  TrialSummary by_condition;  // exactly `palprig stats trials --by condition`
  TrialSummary by_finger;     // discrimination: finger 1..3 (localisation rows "-" left out)
  TrialSummary by_tumor;      // localisation: per-tumor sensitivity ("-" = false marks, left out)
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
