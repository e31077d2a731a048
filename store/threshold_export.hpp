#pragma once
// Threshold trials (staircase and QUEST tracks) as analysts read them: one row per trial with
// its track, level, answer, reversal and the track's estimate after that trial, which no row
// stores (the tracks are replayed from the trials with the session's stored protocol, as a
// resume does: study/threshold_record.hpp). Written as threshold_trials.csv (long CSV) and as
// BIDS beh runs with their sidecar (store/trial_export.hpp runs both).
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "store/sqlite_trial_store.hpp"
#include "study/threshold_record.hpp"

namespace palprig {

struct ThresholdExportRow {
  std::int64_t session = 0;
  ParticipantRecord participant;
  std::string protocol, method, procedure;  // method: 2afc or yes-no; procedure: staircase or quest
  ThresholdTrialRecord trial;
  double estimate_kPa = 0;      // the trial's track's threshold estimate after this trial
  TrackEstimate estimate;       // the whole estimate after this trial (reversals, target proportion, sd)
  bool track_finished = false;  // the track had reached its stopping rule after this trial
};

// Every threshold trial of the store, by session and position. InputError naming the store and
// session when a session's stored protocol or trials no longer replay (a damaged or edited file).
std::vector<ThresholdExportRow> threshold_export_rows(SqliteTrialStore& store,
                                                      const std::vector<SessionOverview>& sessions);

// threshold_trials.csv: the header and one line per row.
void write_threshold_csv(const std::vector<ThresholdExportRow>& rows, const std::filesystem::path& file);

// One BIDS run (the rows of one session): STEM_beh.tsv and STEM_beh.json in `dir`.
void write_threshold_bids_run(const std::vector<const ThresholdExportRow*>& rows, const std::string& task,
                              const std::filesystem::path& dir, const std::string& stem,
                              std::vector<std::filesystem::path>& written);

}  // namespace palprig
