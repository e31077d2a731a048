#pragma once
// Pulse-localisation trials as analysts read them: one row per trial with the mark, the artery
// it was scored against, its distance to the centreline and the hit (the protocol's hit radius
// beside it). Written as pulse_trials.csv (long CSV) and as BIDS beh runs with their sidecar.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "store/sqlite_trial_store.hpp"
#include "study/pulse_record.hpp"

namespace palprig {

struct PulseExportRow {
  std::int64_t session = 0;
  ParticipantRecord participant;
  std::string protocol;
  double hit_radius_mm = 0;
  PulseTrialRecord trial;
};

std::vector<PulseExportRow> pulse_export_rows(SqliteTrialStore& store, const std::vector<SessionOverview>& sessions);
void write_pulse_csv(const std::vector<PulseExportRow>& rows, const std::filesystem::path& file);
void write_pulse_bids_run(const std::vector<const PulseExportRow*>& rows, const std::string& task,
                          const std::filesystem::path& dir, const std::string& stem,
                          std::vector<std::filesystem::path>& written);

}  // namespace palprig
