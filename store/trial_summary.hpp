#pragma once
// `palprig stats trials`: per-group confusion counts of a trial database with paper 002's
// measures (Se, Sp, PPV, ACC, each with its Wilson interval) and response times.
//
// Units scored: every finger value of a discrimination trial (3 per trial, as in the paper);
// every tumor of a localisation trial's case (TP detected / FN missed; grouped by tumor, keyed
// "case/tumor": tumors of different cases are never pooled), one FP per false mark, and one TN
// per normal case (no tumor) answered without a mark; Sp = TN / normal cases. False marks and a
// normal case's answer are the row "case/elsewhere" when grouping by tumor. Unanswered (timed-out) trials are counted,
// not scored. Practice trials are left out unless asked for. Response times: mean and sd over answered trials, each
// trial counted once per group it contributes to, from onset (paper 002's measure) and from the stimulus end; the mean
// confidence rating and the count rated when any trial has one.
#include <cstdint>
#include <string>
#include <vector>

#include "statistics/diagnostic_measures.hpp"
#include "store/trial_store.hpp"

namespace palprig {

// The tumor key of a case's marks away from every tumor and of a normal case's answer.
inline constexpr const char* kElsewhereKey = "elsewhere";

enum class SummaryKey { condition, participant, finger, tumor, combination, session };

const char* to_string(SummaryKey key) noexcept;
// "condition,participant" -> keys; throws InputError naming the unknown word.
std::vector<SummaryKey> parse_summary_keys(const std::string& list);

struct SummaryOptions {
  std::vector<SummaryKey> by;
  bool include_practice = false;
  double confidence = 0.95;
};

struct SummaryRow {
  std::vector<std::string> key;  // one value per SummaryOptions::by, in that order
  ConfusionCounts counts;
  DiagnosticMeasures measures;
  std::int64_t trials = 0;            // trials that contributed (answered or not)
  std::int64_t unanswered = 0;        // of which timed out
  double mean_rt_s = 0, sd_rt_s = 0;  // from onset (paper 002); NaN when fewer than 1 (mean) or 2 (sd) answered trials
  std::int64_t rt_count = 0;          // the response times behind them: answered trials with a stored time
  // From the end of the stimulus (0 for an answer during it); NaN likewise, and for trials
  // stored before the stimulus end was.
  double mean_rt_after_stimulus_s = 0, sd_rt_after_stimulus_s = 0;
  // From when the stimulus reached the fingers (half the commanded level on the monitor); NaN
  // likewise, and for trials without that time (0/0/0, scenes, stored before the column).
  double mean_rt_from_reached_s = 0, sd_rt_from_reached_s = 0;
  std::int64_t rated = 0;      // answered trials with a confidence rating
  double mean_confidence = 0;  // NaN when none was rated
  // Localisation: true negatives are normal cases left unmarked (a tumor-free spot of an
  // abnormal case is none); without normal cases TN and Sp have no denominator and are n/a,
  // never 0; ACC is always n/a (it would add tumors to cases).
  bool negatives_counted = true;
  std::int64_t normal_cases = 0;  // localisation: answered normal cases (Sp's denominator)
};

struct TrialSummary {
  std::vector<SummaryKey> by;
  std::vector<SummaryRow> rows;  // sorted by key
  bool any_rated = false;        // some trial has a confidence rating: reports show the columns
};

TrialSummary summarise_trials(TrialStore& store, const SummaryOptions& options);

}  // namespace palprig
