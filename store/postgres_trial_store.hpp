#pragma once
// PostgresTrialStore: the lab's shared trial store on a PostgreSQL server (libpq). Same tables
// and promises as the SQLite store (store/trial_store.hpp): one transaction per trial, the
// order stored before trial 1, trials in position order. On top: every session carries a global
// session_uid, the host it ran on and the rig id, so an analyst tells rigs and sites apart, and
// a trial is unique per (session, position): committing it twice stores it once, which makes
// pushes from a bench's journal safe to repeat.
//
// Several rigs write one study at once: enrolment numbers are handed out one at a time (a table
// lock for the few milliseconds of an enrolment); trials of different sessions never conflict.
//
// One process per session: claim_session takes a PostgreSQL advisory lock on this store's
// connection (pg_try_advisory_lock, session level) and writes a session_locks row naming the
// holder (pid, host, since) for the refusal line. The lock, not the row, says whether the holder
// lives: the server drops it with the connection (kill -9, a crashed bench, a lost network), on
// any host, so a stale row is simply overwritten by the next claim.
//
// Opening connects and creates or migrates the schema (read_write) or checks it (read_only).
// An unreachable server or a refused login is InputError naming host, port, database and
// libpq's reason; a lost connection later is PgError (connection_lost).
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "store/pg_connection.hpp"
#include "store/pg_target.hpp"
#include "store/session_rows.hpp"
#include "store/trial_store.hpp"

namespace palprig {

class PostgresTrialStore final : public TrialStore {
 public:
  PostgresTrialStore(const PgTarget& target, Access access, int connect_timeout_s = 10);
  ~PostgresTrialStore() override;  // releases the sessions this process holds

  const std::string& location() const noexcept override { return location_; }

  ParticipantRecord enrol(const std::string& code, bool simulated) override;
  std::optional<ParticipantRecord> find_participant(const std::string& code) override;

  std::optional<std::int64_t> find_unfinished_session(const ParticipantRecord& who,
                                                      const std::string& protocol_name) override;
  std::int64_t create_session(const ParticipantRecord& who, const Protocol& protocol, const SessionPlan& plan,
                              const SessionSetup& setup) override;
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

  // Training (store/postgres_training.cpp).
  void enrol_trainee(const std::string& code, const std::string& curriculum) override;
  std::vector<TraineeRecord> trainees() override;
  std::vector<TrainingSessionRecord> training_sessions(const std::string& trainee) override;
  void begin_training_session(const TrainingSessionRecord& record) override;
  void complete_training_session(std::int64_t session_id, const nlohmann::json& scores, bool met_benchmark) override;

  // The session's global identity (what the journal and copies key on).
  std::string session_uid(std::int64_t session_id);
  PgConnection& connection() noexcept { return db_; }
  const PgTarget& target() const noexcept { return db_.target(); }

 private:
  std::vector<StoredTrial> read_trials_where(const std::string& where);  // " WHERE ..." or ""
  // Session locks (postgres_session_lock.cpp).
  void refuse_if_held_elsewhere(std::int64_t session_id, const std::string& who);
  void take_lock(std::int64_t session_id, const std::string& who);  // inside a transaction
  void drop_lock(std::int64_t session_id);
  // "t.confidence, t.stimulus_end_s, t.stimulus_reached_s", NULL for those an older server lacks.
  std::string later_columns() const;

  PgConnection db_;
  std::string location_;
  std::vector<std::int64_t> held_;  // sessions whose advisory lock this connection holds
  std::size_t trial_columns_ = 0;   // of kTrialColumns the server has (fewer: an older one opened for reading)
};

// A new session's global identity: host, UTC time and 64 random bits.
std::string new_session_uid();

// The trial's rows as the SQLite store writes them (columns of store/session_rows.hpp).
TrialRows trial_rows_of(const TrialRecord& trial);

}  // namespace palprig
