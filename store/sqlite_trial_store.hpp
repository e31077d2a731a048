#pragma once
// SqliteTrialStore: the trial store in one SQLite file. WAL journal with full sync, one
// committed transaction per trial, so killing the process loses at most the trial in progress.
// Holds participants, sessions (protocol snapshot, seed, generated order, rig and calibration
// ids, simulated participant model) and trials (stimuli, answers, per-finger and per-tumor
// scores, times).
//
// Identification: PRAGMA application_id = 0x50616C50 ("PalP") marks a palprig database and
// PRAGMA user_version its schema version. Opening refuses a file that is not SQLite, a SQLite
// database of another program, and a palprig database from a newer version (InputError).
#include <cstdint>
#include <filesystem>
#include <memory>

#include "store/sqlite_db.hpp"
#include "store/trial_store.hpp"

namespace palprig {

inline constexpr std::int64_t kTrialStoreApplicationId = 0x50616C50;  // "PalP"
inline constexpr std::int64_t kTrialStoreSchemaVersion = 1;

class SqliteTrialStore final : public TrialStore {
 public:
  // Creates the schema in a new or empty file (read_write); refuses foreign or newer files.
  SqliteTrialStore(const std::filesystem::path& file, Access access);

  const std::string& location() const noexcept override { return db_.file(); }

  ParticipantRecord enrol(const std::string& code, bool simulated) override;
  std::optional<ParticipantRecord> find_participant(const std::string& code) override;

  std::optional<std::int64_t> find_unfinished_session(const ParticipantRecord& who,
                                                      const std::string& protocol_name) override;
  std::int64_t create_session(const ParticipantRecord& who, const Protocol& protocol, const SessionPlan& plan,
                              const SessionSetup& setup) override;
  StoredSession load_session(std::int64_t session_id) override;
  void complete_session(std::int64_t session_id) override;

  void commit_trial(std::int64_t session_id, const TrialRecord& trial) override;
  void commit_trials(std::int64_t session_id, std::span<const TrialRecord> trials) override;

  std::vector<SessionOverview> list_sessions() override;
  nlohmann::json protocol_snapshot(std::int64_t session_id) override;
  void scan_scored_trials(TrialFamily family, bool include_practice,
                          const std::function<void(const ScoredTrial&)>& visit) override;
  std::vector<StoredTrial> read_trials(bool include_practice) override;

  // The SQL connection, for tests and tools that check the file itself.
  Database& database() noexcept { return db_; }

 private:
  bool is_blank();  // a new file: no tables, no palprig marks
  void create_schema();
  void check_identity();
  void insert_trial(std::int64_t session_id, const TrialRecord& trial);

  Database db_;
  std::unique_ptr<Statement> insert_trial_;  // prepared once: trials are inserted one by one
};

}  // namespace palprig
