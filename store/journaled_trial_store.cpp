#include "store/journaled_trial_store.hpp"

#include <cstdlib>
#include <iostream>

#include "core/input_error.hpp"
#include "store/lab_sync.hpp"
#include "store/postgres_schema.hpp"
#include "store/postgres_session_rows.hpp"
#include "store/sqlite_session_rows.hpp"

namespace palprig {

namespace {

std::filesystem::path journal_parent_created(const std::filesystem::path& file) {
  std::error_code ec;
  if (file.has_parent_path()) std::filesystem::create_directories(file.parent_path(), ec);
  return file;
}

}  // namespace

std::filesystem::path default_journal_file() {
  if (const char* env = std::getenv("PALPRIG_JOURNAL"); env && *env) return env;
  if (const char* state = std::getenv("XDG_STATE_HOME"); state && *state) {
    return std::filesystem::path(state) / "palprig" / "journal.sqlite";
  }
  const char* home = std::getenv("HOME");
  return std::filesystem::path(home && *home ? home : "/tmp") / ".local" / "state" / "palprig" / "journal.sqlite";
}

JournaledTrialStore::JournaledTrialStore(const PgTarget& target, const std::filesystem::path& journal_file,
                                         std::function<void(const std::string&)> say)
    : server_(target, Access::read_write),
      journal_file_(journal_parent_created(journal_file)),
      journal_(journal_file_, Access::read_write) {
  ensure_lab_sessions_table(journal_.database());
  try {
    server_identity_ = pg_store_identity(server_.connection());
  } catch (const PgError& e) {
    throw InputError(target.describe(), "connection", "a reachable PostgreSQL server (libpq: " + e.reason() + ")");
  }
  {
    // Journals written before the store had an identity name the server by host, port and
    // database. Their sessions not yet on a server go to this one (pushes are idempotent on the
    // session's uid), with no server id: an id of that old server says nothing here. Pushed
    // ones keep the old name, which matches no store, so a fresh server at the same address
    // never finds them (it was taken for the old one, and its session 1 refused as running).
    auto adopt = journal_.database().prepare(
        "UPDATE lab_store_sessions SET server = ?1, server_session_id = NULL WHERE server = ?2 AND synced = 0");
    adopt.bind(1, server_identity_).bind(2, target.describe()).run();
  }
  // What an earlier run could not push (killed, or the server was down) goes first, so that
  // --resume continues after the last trial the bench ran.
  PushOptions options;
  options.journal_only = true;
  options.mark_synced = true;
  try {
    pushed_at_open_ = push_file_to_server(journal_.database(), server_.connection(), options).trials_added;
  } catch (const PgError& e) {
    throw InputError(target.describe(), "connection", "a reachable PostgreSQL server (libpq: " + e.reason() + ")");
  }
  if (!say) say = [](const std::string& line) { std::cerr << "palprig: " << line << "\n" << std::flush; };
  pusher_ = std::make_unique<JournalPusher>(target, journal_file_, std::move(say));
}

JournaledTrialStore::~JournaledTrialStore() = default;

ParticipantRecord JournaledTrialStore::enrol(const std::string& code, bool simulated) {
  return server_.enrol(code, simulated);
}

std::optional<ParticipantRecord> JournaledTrialStore::find_participant(const std::string& code) {
  return server_.find_participant(code);
}

std::optional<std::int64_t> JournaledTrialStore::find_unfinished_session(const ParticipantRecord& who,
                                                                         const std::string& protocol_name) {
  return server_.find_unfinished_session(who, protocol_name);
}

std::int64_t JournaledTrialStore::create_session(const ParticipantRecord& who, const Protocol& protocol,
                                                 const SessionPlan& plan, const SessionSetup& setup) {
  const std::int64_t server_id = server_.create_session(who, protocol, plan, setup);  // claimed on the server
  journal_.claim_session(journal_session(server_id));
  return server_id;
}

// Two locks: the server's (advisory lock of server_'s connection: no other bench runs the
// session) and the journal's (session_locks row: no other process on this bench writes its
// journal copy). The server's lapses while the server is down (the connection ends); the
// journal's holds throughout, and this bench pushes its trials when the server returns.
void JournaledTrialStore::claim_session(std::int64_t session_id) {
  server_.claim_session(session_id);
  try {
    journal_.claim_session(journal_session(session_id));
  } catch (...) {
    server_.release_session(session_id);
    throw;
  }
}

void JournaledTrialStore::refuse_if_running_elsewhere(std::int64_t session_id) {
  server_.refuse_if_running_elsewhere(session_id);
  if (const auto it = journal_id_of_.find(session_id); it != journal_id_of_.end()) {
    journal_.refuse_if_running_elsewhere(it->second);
  }
}

void JournaledTrialStore::release_session(std::int64_t session_id) {
  if (const auto it = journal_id_of_.find(session_id); it != journal_id_of_.end()) journal_.release_session(it->second);
  server_.release_session(session_id);
}

std::int64_t JournaledTrialStore::journal_session(std::int64_t server_session_id) {
  if (const auto it = journal_id_of_.find(server_session_id); it != journal_id_of_.end()) return it->second;
  Database& db = journal_.database();
  const std::string& server_key = server_identity_;
  std::int64_t local = 0;
  auto known = db.prepare("SELECT session_id FROM lab_store_sessions WHERE server = ?1 AND server_session_id = ?2");
  known.bind(1, server_key).bind(2, server_session_id);
  if (known.step()) {
    local = known.integer(0);
  } else {
    // The server's session (order, protocol, rig) becomes the journal's, linked by its uid.
    auto rows = pg_read_session(server_.connection(), server_session_id);
    if (!rows) throw InputError(location(), "session " + std::to_string(server_session_id), "an existing session");
    local = write_sqlite_session(db, rows->rows).session_id;
    auto link = db.prepare(
        "UPDATE lab_store_sessions SET server = ?2, server_uri = ?3, server_session_id = ?4 WHERE session_id = ?1");
    link.bind(1, local).bind(2, server_key).bind(3, server_.target().conninfo).bind(4, server_session_id).run();
  }
  journal_id_of_[server_session_id] = local;
  return local;
}

StoredSession JournaledTrialStore::load_session(std::int64_t session_id) {
  StoredSession s = server_.load_session(session_id);
  journal_session(session_id);
  return s;
}

void JournaledTrialStore::complete_session(std::int64_t session_id) {
  journal_.complete_session(journal_session(session_id));  // releases the journal's lock
  pusher_->committed();
  // The server's lock is kept until this store closes: by then the pusher has stopped (members
  // end in reverse order) and the server has every trial it could be given, so no other bench
  // resumes a session whose last trials are still on their way. It ends with the connection
  // at the latest.
}

void JournaledTrialStore::commit_trial(std::int64_t session_id, const TrialRecord& trial) {
  journal_.commit_trial(journal_session(session_id), trial);
  pusher_->committed();
}

void JournaledTrialStore::commit_trials(std::int64_t session_id, std::span<const TrialRecord> trials) {
  journal_.commit_trials(journal_session(session_id), trials);
  pusher_->committed();
}

void JournaledTrialStore::begin_training_session(const TrainingSessionRecord& record) {
  server_.begin_training_session(record);
  TrainingSessionRecord local = record;
  local.session_id = journal_session(record.session_id);
  journal_.begin_training_session(local);
}

void JournaledTrialStore::complete_training_session(std::int64_t session_id, const nlohmann::json& scores,
                                                    bool met_benchmark) {
  const std::int64_t local = journal_session(session_id);
  journal_.complete_training_session(local, scores, met_benchmark);
  // The session may be marked synced already (it completed a moment ago): pushed once more, for
  // its training row (the trials are there; pushes are idempotent).
  auto again = journal_.database().prepare("UPDATE lab_store_sessions SET synced = 0 WHERE session_id = ?1");
  again.bind(1, local).run();
  pusher_->committed();
}

}  // namespace palprig
