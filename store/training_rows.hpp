#pragma once
// A training session's record (store/trial_store.hpp: TrainingSessionRecord) as the row both
// stores keep in training_sessions (kTrainingColumns, store/session_rows.hpp), and back. The row
// travels with its session (store copy, journal pushes), so a trainee's history is wherever their
// sessions are.
#include <cstdint>
#include <string>
#include <variant>

#include <nlohmann/json.hpp>

#include "store/session_rows.hpp"
#include "store/trial_store.hpp"

namespace palprig {

inline SqlRow training_row_of(const TrainingSessionRecord& r) {
  SqlRow row(kTrainingColumns.size(), std::monostate{});
  row[0] = r.trainee;
  row[1] = r.curriculum;
  row[2] = std::int64_t{r.level};
  row[3] = r.level_name;
  row[4] = nlohmann::json(r.cases).dump();
  row[5] = r.status;
  if (!r.scores.is_null()) row[6] = r.scores.dump();
  if (r.met_benchmark) row[7] = std::int64_t{*r.met_benchmark ? 1 : 0};
  row[8] = r.started_utc;
  if (!r.finished_utc.empty()) row[9] = r.finished_utc;
  return row;
}

inline TrainingSessionRecord training_record_of(std::int64_t session_id, const SqlRow& row) {
  const auto text = [&](std::size_t i) {
    const auto* t = std::get_if<std::string>(&row.at(i));
    return t ? *t : std::string();
  };
  TrainingSessionRecord r;
  r.session_id = session_id;
  r.trainee = text(0);
  r.curriculum = text(1);
  if (const auto* level = std::get_if<std::int64_t>(&row.at(2))) r.level = static_cast<int>(*level);
  r.level_name = text(3);
  const nlohmann::json cases = nlohmann::json::parse(text(4), nullptr, false);
  if (cases.is_array()) {
    for (const auto& c : cases) {
      if (c.is_string()) r.cases.push_back(c.get<std::string>());
    }
  }
  r.status = text(5);
  if (!text(6).empty()) r.scores = nlohmann::json::parse(text(6), nullptr, false);
  if (r.scores.is_discarded()) r.scores = nullptr;
  if (const auto* met = std::get_if<std::int64_t>(&row.at(7))) r.met_benchmark = *met != 0;
  r.started_utc = text(8);
  r.finished_utc = text(9);
  return r;
}

// The case keys of a training row (its `cases` JSON), for training_cases.
inline std::vector<std::string> training_row_cases(const SqlRow& row) { return training_record_of(0, row).cases; }

// What both stores expected when they refuse a case given to the trainee before (in the session
// given_in_session): the third part of their InputError on training_cases.
inline std::string case_not_given_before(const std::string& trainee, const std::string& key,
                                         std::int64_t given_in_session) {
  std::string expected = "a case trainee '";
  expected.append(trainee).append("' was not given before (").append(key).append(" was given in session ");
  expected.append(std::to_string(given_in_session)).append(")");
  return expected;
}

}  // namespace palprig
