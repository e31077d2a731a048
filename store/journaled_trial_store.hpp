#pragma once
// JournaledTrialStore: what a session uses when its store is the lab's PostgreSQL server.
// Offline first: the bench never stops a participant's session because the server is down.
//
//   - Opening needs the server (participants are numbered across every rig, the order depends
//     on the number): an unreachable server is refused before anything moves on the rig. It
//     first pushes whatever an earlier run left in the journal (a crash, an outage), so a
//     --resume sees every trial.
//   - Participants and sessions are created on the server and mirrored into the journal (a
//     local SQLite trial file, lab_store_sessions linking the two).
//   - Each trial is committed to the journal (its own transaction, fsync'd) and pushed by the
//     JournalPusher thread; when the server is unreachable the session goes on and the pending
//     trials follow when it returns, or with `palprig store sync --from JOURNAL --to URI`.
//     Pushes are idempotent on (session, position).
//   - One process per session: claimed on the server (advisory lock, every bench) and in the
//     journal (session_locks, this bench); see claim_session.
//   - Reads (stats, export) go to the server.
#include <chrono>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <string>

#include "store/journal_pusher.hpp"
#include "store/postgres_trial_store.hpp"
#include "store/sqlite_trial_store.hpp"

namespace palprig {

// $PALPRIG_JOURNAL, else $XDG_STATE_HOME/palprig/journal.sqlite, else
// ~/.local/state/palprig/journal.sqlite.
std::filesystem::path default_journal_file();

class JournaledTrialStore final : public TrialStore {
 public:
  // `say` gets the pusher's lines (server lost / back); default: standard error.
  JournaledTrialStore(const PgTarget& target, const std::filesystem::path& journal_file,
                      std::function<void(const std::string&)> say = {});
  ~JournaledTrialStore() override;

  const std::string& location() const noexcept override { return server_.location(); }

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

  std::vector<SessionOverview> list_sessions() override { return server_.list_sessions(); }
  nlohmann::json protocol_snapshot(std::int64_t session_id) override { return server_.protocol_snapshot(session_id); }
  void scan_scored_trials(TrialFamily family, bool include_practice,
                          const std::function<void(const ScoredTrial&)>& visit) override {
    server_.scan_scored_trials(family, include_practice, visit);
  }
  std::vector<StoredTrial> read_trials(bool include_practice) override { return server_.read_trials(include_practice); }
  std::vector<StoredTrial> read_session_trials(std::int64_t session_id) override {
    return server_.read_session_trials(session_id);
  }
  int next_participant_number() override { return server_.next_participant_number(); }

  // Training: enrolments and history are read from and reserved on the server (every rig sees
  // them; the server refuses a case given on another rig), and mirrored into the journal; a
  // session's completion goes through the journal and is pushed with it.
  void enrol_trainee(const std::string& code, const std::string& curriculum) override {
    server_.enrol_trainee(code, curriculum);
  }
  std::vector<TraineeRecord> trainees() override { return server_.trainees(); }
  std::vector<TrainingSessionRecord> training_sessions(const std::string& trainee) override {
    return server_.training_sessions(trainee);
  }
  void begin_training_session(const TrainingSessionRecord& record) override;
  void complete_training_session(std::int64_t session_id, const nlohmann::json& scores, bool met_benchmark) override;

  // Waits up to `timeout` for the pushes; returns the journal commits still pending.
  std::int64_t flush(std::chrono::milliseconds timeout) { return pusher_->flush(timeout); }
  const std::filesystem::path& journal_file() const noexcept { return journal_file_; }
  int pushed_at_open() const noexcept { return pushed_at_open_; }

 private:
  // The journal's copy of a server session, made when this journal does not have it yet (a
  // session resumed on another bench).
  std::int64_t journal_session(std::int64_t server_session_id);

  PostgresTrialStore server_;
  std::filesystem::path journal_file_;
  SqliteTrialStore journal_;
  std::map<std::int64_t, std::int64_t> journal_id_of_;  // server session id -> journal session id
  std::string server_identity_;                         // pg_store_identity: the store, not its address
  int pushed_at_open_ = 0;
  std::unique_ptr<JournalPusher> pusher_;
};

}  // namespace palprig
