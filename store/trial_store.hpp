#pragma once
// TrialStore: the SQLite trial database (DESIGN.md "Data"). WAL journal with full sync, one
// committed transaction per trial, so killing the process loses at most the trial in
// progress. Holds participants, sessions (protocol snapshot, seed, generated order, rig and
// calibration ids, simulated participant model) and trials (stimuli, answers, per-finger and
// per-tumor scores, times).
//
// Identification: PRAGMA application_id = 0x50616C50 ("PalP") marks a palprig database and
// PRAGMA user_version its schema version. Opening refuses a file that is not SQLite, a SQLite
// database of another program, and a palprig database from a newer version (InputError).
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "experiments/protocol.hpp"
#include "experiments/session_plan.hpp"
#include "store/sqlite_db.hpp"
#include "experiments/trial_record.hpp"

namespace palprig {

inline constexpr std::int64_t kTrialStoreApplicationId = 0x50616C50;  // "PalP"
inline constexpr std::int64_t kTrialStoreSchemaVersion = 1;

struct ParticipantRecord {
  std::int64_t id = 0;
  std::string code;
  int number = 0;  // 1-based enrolment order
  bool simulated = false;
};

struct SessionSetup {
  std::string rig_id, rig_backend, calibration;
  nlohmann::json participant_model;  // the simulated participant's parameters; null for people
  std::string protocol_dir;          // folder of the protocol file (resolves a scene path)
};

struct StoredSession {
  std::int64_t id = 0;
  ParticipantRecord participant;
  nlohmann::json protocol_snapshot;
  std::string protocol_dir;
  std::string status;  // "running" or "completed"
  SessionPlan plan;
  int completed_trials = 0;  // trials committed; the next position to run
};

class TrialStore {
 public:
  enum class Access { read_only, read_write };
  // Creates the schema in a new or empty file (read_write); refuses foreign or newer files.
  // Every open runs PRAGMA quick_check and refuses a damaged file (InputError naming it).
  TrialStore(const std::filesystem::path& file, Access access);
  ~TrialStore();  // releases the sessions this process holds
  TrialStore(const TrialStore&) = delete;
  TrialStore& operator=(const TrialStore&) = delete;

  ParticipantRecord enrol(const std::string& code, bool simulated);
  std::optional<ParticipantRecord> find_participant(const std::string& code);

  // The session of this participant and protocol that was started but not completed.
  std::optional<std::int64_t> find_unfinished_session(const ParticipantRecord& who, const std::string& protocol_name);
  // Refuses (InputError) when this participant has an unfinished session with this protocol,
  // e.g. one another process created a moment ago. The new session is held by this process.
  std::int64_t create_session(const ParticipantRecord& who, const Protocol& protocol, const SessionPlan& plan,
                              const SessionSetup& setup);
  // One process per session: a row in session_locks names the holder (pid, host, process start
  // time). Claiming refuses (InputError) a session a live process holds or that was completed;
  // a row of a dead process on this host is stale and taken over. Released by
  // complete_session, release_session and the destructor.
  void claim_session(std::int64_t session_id);
  // The refusal claim_session would give, without claiming (InputError when a live process holds it).
  void refuse_if_running_elsewhere(std::int64_t session_id);
  void release_session(std::int64_t session_id);
  StoredSession load_session(std::int64_t session_id);
  void complete_session(std::int64_t session_id);

  // One transaction per trial (the crash-safety promise).
  void commit_trial(std::int64_t session_id, const TrialRecord& trial);
  // Many trials in one transaction (imports, benchmarks, tests).
  void commit_trials(std::int64_t session_id, std::span<const TrialRecord> trials);

  Database& database() noexcept { return db_; }
  const std::string& file() const noexcept { return db_.file(); }

 private:
  bool is_blank();  // a new file: no tables, no palprig marks
  void create_schema_if_blank();
  bool has_lock_table();
  void create_lock_table();
  void refuse_if_held_elsewhere(std::int64_t session_id, const std::string& who);
  void write_lock_row(std::int64_t session_id);  // inside a transaction
  void check_identity();
  void insert_trial(std::int64_t session_id, const TrialRecord& trial);

  Database db_;
  std::unique_ptr<Statement> insert_trial_;  // prepared once: trials are inserted one by one
  std::vector<std::int64_t> held_;            // sessions whose lock row this process wrote
};

// Open a database for reading (stats, export): refuses a missing, foreign or newer file.
TrialStore open_trial_store_for_reading(const std::filesystem::path& file);

}  // namespace palprig
