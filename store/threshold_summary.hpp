#pragma once
// What `palprig stats trials` prints for threshold sessions: one row per session and adaptive
// track, with the track's own threshold estimate (a staircase's mean of its last reversals, or
// QUEST's posterior mean) and the proportion correct it refers to (1-up 3-down: 79.4 %), the
// trials, the share answered correctly and the reversals. The tracks are replayed from the
// stored trials with the session's stored protocol (store/threshold_export), as an export and a
// resume do. Psychometric fits of the same trials: `palprig stats psychometric DB`.
#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "store/sqlite_trial_store.hpp"
#include "study/adaptive_track.hpp"

namespace palprig {

struct ThresholdTrackSummary {
  std::string participant;
  std::int64_t session = 0;
  std::string track, fingers, procedure, method;  // procedure: staircase / quest; method: 2afc / yes-no
  int trials = 0, answered = 0, correct = 0;
  bool finished = false;  // the track reached its stopping rule
  TrackEstimate estimate;
};

// Every threshold track of the store, by participant number, session and track order. Empty
// when the store holds no threshold trial.
std::vector<ThresholdTrackSummary> summarise_threshold_tracks(SqliteTrialStore& store);

std::string threshold_summary_table(const std::vector<ThresholdTrackSummary>& rows);
nlohmann::ordered_json threshold_summary_json(const std::vector<ThresholdTrackSummary>& rows);

}  // namespace palprig
