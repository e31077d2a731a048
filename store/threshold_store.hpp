#pragma once
// Threshold sessions in the trial database. A threshold session is a row of `sessions`
// (task "threshold", the protocol snapshot, the seed) and one row of `threshold_trials` per
// trial, committed in its own transaction. A row has constant size: the tracks' state is not
// stored but replayed from the rows (study/threshold_record.hpp: replay_tracks), so a killed
// session resumes with exactly the staircases it had (schema 3; a schema-2 store's per-row
// state column is dropped when it is opened for writing). The table is created on first use
// (CREATE TABLE IF NOT EXISTS), and older readers ignore it.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "study/threshold_protocol.hpp"
#include "study/threshold_record.hpp"
#include "store/sqlite_trial_store.hpp"

namespace palprig {

struct StoredThresholdSession : StoredTaskSession {
  std::vector<ThresholdTrialRecord> trials;  // committed, in position order (replayed to resume)
};

// One stored trial, for statistics and plots.
struct ThresholdTrialRow {
  std::int64_t session_id = 0;
  std::string participant;
  ThresholdTrialRecord trial;
};

class ThresholdStore {
 public:
  // Adds the threshold table to a writable store if missing.
  explicit ThresholdStore(SqliteTrialStore& store, bool writable = true);

  std::int64_t create_session(const ParticipantRecord& who, const ThresholdProtocol& protocol, std::uint64_t seed,
                              const SessionSetup& setup);
  StoredThresholdSession load_session(std::int64_t session_id);
  void commit_trial(std::int64_t session_id, const ThresholdTrialRecord& trial);
  // Every threshold trial of the database (or of one session), in session and position order.
  std::vector<ThresholdTrialRow> trials(std::optional<std::int64_t> session_id = std::nullopt);
  bool has_table();

 private:
  SqliteTrialStore& store_;
};

}  // namespace palprig
