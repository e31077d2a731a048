#pragma once
// The outputs of `palprig stats trials`: an aligned table for people, CSV for spreadsheets and
// R, JSON for programs. Measures with a zero denominator print as NA (null in JSON).
#include <string>

#include <nlohmann/json.hpp>

#include "store/trial_summary.hpp"

namespace palprig {

std::string summary_table(const TrialSummary& summary);
std::string summary_csv(const TrialSummary& summary);
nlohmann::ordered_json summary_json(const TrialSummary& summary, double confidence);

// Everything `palprig stats trials` prints for a store in `format` ("table", "csv" or "json"):
// first the pulse-localisation summary when a SQLite store has pulse trials (store/pulse_store;
// printed as its table for table and csv), then the summary of the discrimination and
// localisation trials, left out when the store holds pulse trials only. The GUI's
// statistics.json export writes the same text.
std::string stats_trials_text(TrialStore& store, const SummaryOptions& options, const std::string& format);

}  // namespace palprig
