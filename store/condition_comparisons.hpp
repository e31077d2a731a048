#pragma once
// The tests paper 002 reports between conditions, on a trial summary (store/trial_summary):
// the response times' t-test (Student's pooled-variance test, as the paper; or Welch's) and the
// combined-interval comparison of Se, Sp, PPV and ACC (eq. 10). `palprig stats trials` prints
// them under its table and in its JSON, and the window's statistics view shows them: both call
// compare_conditions, so the numbers are the same.
//
// Per the grouping asked: conditions are compared within each stratum of the other keys of
// `--by` (--by condition,participant compares the conditions of each participant; without
// `condition` in the grouping there is nothing to compare). Response times: one value per
// trial, answered trials with a stored time, practice left out unless asked for, as the summary
// counted them (its rows keep each group's n, mean and sd, from which both t-tests follow
// exactly).
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "statistics/statistics_proportion.hpp"
#include "statistics/statistics_ttest.hpp"
#include "store/trial_summary.hpp"

namespace palprig {

enum class ResponseTimeTest { student, welch };
const char* to_string(ResponseTimeTest test) noexcept;

// Response times of two conditions. `test` is empty (with the reason in `why_not`) when a side
// has fewer than 2 answered trials or both sides are constant.
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

// The comparisons within one stratum: `key` holds the values of the grouping's other keys, in the
// order of ConditionComparisons::strata_by (empty for --by condition).
struct ComparisonStratum {
  std::vector<std::string> key;
  std::vector<ResponseTimeComparison> response_times;  // every pair of conditions
  std::vector<MeasureComparison> measures;             // every pair of conditions x defined measure
};

struct ConditionComparisons {
  ResponseTimeTest test = ResponseTimeTest::student;
  double confidence = 0.95;
  bool by_condition = false;              // `condition` was in the grouping: comparisons were made
  std::vector<SummaryKey> strata_by;      // the grouping without `condition`
  std::vector<ComparisonStratum> strata;  // strata with at least two conditions, by key
};

ConditionComparisons compare_conditions(const TrialSummary& summary, double confidence,
                                        ResponseTimeTest test = ResponseTimeTest::student);

// The comparisons as `palprig stats trials` prints them under its table: a heading line and an
// aligned table, one row per pair of conditions and measure (empty when nothing was compared).
std::string comparisons_table(const ConditionComparisons& c);
// As a JSON array, one object per pair of conditions and measure ("RT" or Se, Sp, PPV, ACC), the
// stratum's keys first: what `stats trials --json` puts under "comparisons".
nlohmann::ordered_json comparisons_json(const ConditionComparisons& c);

}  // namespace palprig
