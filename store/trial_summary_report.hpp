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

}  // namespace palprig
