#pragma once
// The outputs of `palprig stats trials`: an aligned table for people, CSV for spreadsheets and
// R, JSON for programs. Measures with a zero denominator print as NA (null in JSON).
#include <string>

#include <nlohmann/json.hpp>

#include "store/condition_comparisons.hpp"
#include "store/trial_summary.hpp"

namespace palprig {

std::string summary_table(const TrialSummary& summary);
std::string summary_csv(const TrialSummary& summary);
// With "comparisons" (store/condition_comparisons) when the grouping has `condition`.
nlohmann::ordered_json summary_json(const TrialSummary& summary, double confidence,
                                    ResponseTimeTest test = ResponseTimeTest::student);

// Everything `palprig stats trials` prints for a store in `format` ("table", "csv" or "json"),
// one part per task kind the store holds: pulse localisation (store/pulse_store), thresholds
// (store/threshold_summary; both printed as their tables for table and csv), then the
// discrimination and localisation summary with the comparisons between conditions (table and
// JSON). JSON is one object: the kind's own when the store holds one kind, else {"tasks": [...]}
// with one object per kind. A store without any trial is refused (InputError naming it). The
// GUI's statistics.json export writes the same text.
std::string stats_trials_text(TrialStore& store, const SummaryOptions& options, const std::string& format,
                              ResponseTimeTest test = ResponseTimeTest::student);

}  // namespace palprig
