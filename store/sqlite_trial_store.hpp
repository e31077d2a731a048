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
#include <vector>

#include "store/sqlite_db.hpp"
#include "store/trial_store.hpp"

namespace palprig {

// The `sessions` row of a session; discrimination sessions add their planned order, threshold
// and pulse sessions keep their trials in tables of their own (store/threshold_store,
// store/pulse_store).
struct TaskSessionRow {
  std::string task, protocol_name, bids_task;
  nlohmann::json protocol_snapshot;
  std::uint64_t seed = 0;
  nlohmann::json condition_order = nlohmann::json::array();
};

// A threshold or pulse session as stored, with the count of its trials committed in order.
struct StoredTaskSession {
  std::int64_t id = 0;
  ParticipantRecord participant;
  nlohmann::json protocol_snapshot;
  std::string protocol_dir, status;
  std::uint64_t seed = 0;
  int completed_trials = 0;
};

inline constexpr std::int64_t kTrialStoreApplicationId = 0x50616C50;  // "PalP"
// 2: trials.confidence and trials.stimulus_end_s. A version-1 file opened for writing is
// migrated in one transaction (every trial kept, the new columns NULL); opened for reading it
// is read as it is (the new columns read as NULL).
// 3: threshold_trials without the per-trial copy of every track's state (the tracks are
// replayed from the trial rows, so a row has constant size); migrated the same way.
// 4: trials.stimulus_reached_s (when the stimulus reached the fingers); migrated the same way,
// NULL for the trials stored before.
// 5: the localisation case of each trial (trials.case_name, case_seed, case_difficulty,
// case_tumors; NULL for the trials stored before) and the training tables (trainees,
// training_sessions, training_cases); migrated the same way.
inline constexpr std::int64_t kTrialStoreSchemaVersion = 5;

class SqliteTrialStore final : public TrialStore {
 public:
  // Creates the schema in a new or empty file (read_write); refuses foreign or newer files.
  // Every open runs PRAGMA quick_check and refuses a damaged file (InputError naming it).
  SqliteTrialStore(const std::filesystem::path& file, Access access);
  ~SqliteTrialStore() override;  // releases the sessions this process holds

  const std::string& location() const noexcept override { return db_.file(); }

  ParticipantRecord enrol(const std::string& code, bool simulated) override;
  std::optional<ParticipantRecord> find_participant(const std::string& code) override;

  std::optional<std::int64_t> find_unfinished_session(const ParticipantRecord& who,
                                                      const std::string& protocol_name) override;
  std::int64_t create_session(const ParticipantRecord& who, const Protocol& protocol, const SessionPlan& plan,
                              const SessionSetup& setup) override;
  // A threshold or pulse session: the same refusal as create_session when this participant
  // already runs one with this protocol; inserted and claimed in one transaction.
  std::int64_t create_task_session(const ParticipantRecord& who, const TaskSessionRow& row, const SessionSetup& setup);
  // Refuses (InputError) a missing session, one of another task, or trials not at positions
  // 0..n-1 in `trial_table` (one of the store's own table names).
  StoredTaskSession load_task_session(std::int64_t session_id, const std::string& task, const std::string& trial_table);
  // session_locks rows name the holder (pid, host, process start time).
  void claim_session(std::int64_t session_id) override;
  void refuse_if_running_elsewhere(std::int64_t session_id) override;
  void release_session(std::int64_t session_id) override;
  StoredSession load_session(std::int64_t session_id) override;
  void complete_session(std::int64_t session_id) override;

  void commit_trial(std::int64_t session_id, const TrialRecord& trial) override;
  void commit_trials(std::int64_t session_id, std::span<const TrialRecord> trials) override;

  std::vector<SessionOverview> list_sessions() override;
  nlohmann::json protocol_snapshot(std::int64_t session_id) override;
  void scan_scored_trials(TrialFamily family, bool include_practice,
                          const std::function<void(const ScoredTrial&)>& visit) override;
  std::vector<StoredTrial> read_trials(bool include_practice) override;
  std::vector<StoredTrial> read_session_trials(std::int64_t session_id) override;
  int next_participant_number() override;

  // Training (store/sqlite_training.cpp).
  void enrol_trainee(const std::string& code, const std::string& curriculum) override;
  std::vector<TraineeRecord> trainees() override;
  std::vector<TrainingSessionRecord> training_sessions(const std::string& trainee) override;
  void begin_training_session(const TrainingSessionRecord& record) override;
  void complete_training_session(std::int64_t session_id, const nlohmann::json& scores, bool met_benchmark) override;

  // The SQL connection, for tests and tools that check the file itself.
  Database& database() noexcept { return db_; }
  const std::string& file() const noexcept { return db_.file(); }

 private:
  std::vector<StoredTrial> read_trials_where(const std::string& where);  // " WHERE ..." or ""
  bool is_blank();                                                       // a new file: no tables, no palprig marks
  void create_schema_if_blank();
  bool has_lock_table();
  void create_lock_table();
  void refuse_if_held_elsewhere(std::int64_t session_id, const std::string& who);
  void write_lock_row(std::int64_t session_id);  // inside a transaction
  // Inside a transaction: refuses a running session of this participant and protocol, inserts.
  std::int64_t insert_session_row(const ParticipantRecord& who, const TaskSessionRow& row, const SessionSetup& setup);
  void check_identity();
  void migrate_if_older();
  // The trial columns later schemas appended, for the scans: "confidence, stimulus_end_s,
  // stimulus_reached_s" with NULL for those an older file opened for reading lacks.
  std::string later_columns(const char* prefix) const;
  void insert_trial(std::int64_t session_id, const TrialRecord& trial);

  Database db_;
  std::unique_ptr<Statement> insert_trial_;  // prepared once: trials are inserted one by one
  std::vector<std::int64_t> held_;           // sessions whose lock row this process wrote
  std::size_t trial_columns_ = 0;            // of kTrialColumns this file has (fewer: an older file read as it is)
};

// Open an existing SQLite trial database for reading; refuses a missing, foreign or newer file.
// For code that reads SQLite-only tables (threshold_trials, pulse_trials) besides the interface.
SqliteTrialStore open_sqlite_trial_store_for_reading(const std::filesystem::path& file);

}  // namespace palprig
