// One process per session on the lab server (PostgresTrialStore's claim_session and friends).
//
// Why an advisory lock and not only a row: a row can only be judged stale by asking whether its
// process still lives, which a bench can do for its own processes only (the SQLite store's
// session_locks). The server knows better: a session-level advisory lock belongs to the holder's
// connection and is dropped the moment that connection ends, whichever bench it came from. The
// session_locks row is kept beside it only to name the holder (pid, host, since) in a refusal.
#include <unistd.h>

#include <algorithm>

#include "core/input_error.hpp"
#include "store/postgres_trial_store.hpp"
#include "store/host_identity.hpp"
#include "store/utc_time.hpp"

namespace palprig {

namespace {

// pg_try_advisory_lock(int4, int4): the first key marks palprig session locks ("PalS"), the
// second is the session id. The two-key form lives apart from the one-key schema lock.
constexpr std::int32_t kSessionLockClass = 0x50616C53;

std::string key_params(std::int64_t session_id) {
  return std::to_string(kSessionLockClass) + ", " + std::to_string(static_cast<std::int32_t>(session_id));
}

std::string participant_of(PgConnection& db, std::int64_t session_id, std::string* status = nullptr) {
  const PgResult q =
      db.exec("SELECT s.status, p.code FROM sessions s JOIN participants p ON p.id = s.participant_id WHERE s.id = $1",
              {pg_text(session_id)});
  if (q.rows() == 0) return {};
  if (status) *status = q.text(0, 0);
  return "participant '" + q.text(0, 1) + "'";
}

}  // namespace

PostgresTrialStore::~PostgresTrialStore() {
  const std::vector<std::int64_t> held = held_;  // drop_lock edits held_
  for (std::int64_t session_id : held) {
    try {
      release_session(session_id);
    } catch (...) {
      // The connection is gone: so is the advisory lock; the row left behind is stale and the
      // next claim overwrites it.
    }
  }
}

void PostgresTrialStore::refuse_if_held_elsewhere(std::int64_t session_id, const std::string& who) {
  if (std::find(held_.begin(), held_.end(), session_id) != held_.end()) return;  // ours
  // The holder's server connection (pg_locks), then its bench (session_locks).
  const PgResult lock = db_.exec(
      "SELECT l.pid FROM pg_locks l WHERE l.locktype = 'advisory' AND l.granted AND l.objsubid = 2 "
      "AND l.database = (SELECT oid FROM pg_database WHERE datname = current_database()) "
      "AND l.classid = $1::bigint::oid AND l.objid = $2::bigint::oid AND l.pid <> pg_backend_pid()",
      {std::to_string(kSessionLockClass), std::to_string(static_cast<std::int32_t>(session_id))});
  if (lock.rows() == 0) return;  // nobody holds it: a row left by a dead holder is stale
  const std::string backend = lock.text(0, 0);
  const PgResult row =
      db_.exec("SELECT pid, host, since_utc FROM session_locks WHERE session_id = $1", {pg_text(session_id)});
  const std::string holder =
      row.rows() > 0 ? "process " + row.text(0, 0) + " on " + row.text(0, 1) + " has run it since " + row.text(0, 2)
                     : std::string("a process is starting it");
  // Kept short (a refusal part is cut at a few hundred characters): the holder, and the way out
  // when its bench is gone but the server has not noticed yet (no TCP keepalive reply).
  throw InputError(location_, "session " + std::to_string(session_id),
                   "no other palprig process running session " + std::to_string(session_id) + " of " + who + " (" +
                       holder +
                       "; wait for it to finish, or stop it and continue with --resume; if that bench is "
                       "gone, run on the server: SELECT pg_terminate_backend(" +
                       backend + "))");
}

void PostgresTrialStore::take_lock(std::int64_t session_id, const std::string& who) {
  if (std::find(held_.begin(), held_.end(), session_id) != held_.end()) return;
  refuse_if_held_elsewhere(session_id, who);
  // Session level: the lock outlives this transaction (and is not undone by its rollback, hence
  // drop_lock on the way out of a failure), and ends with the connection.
  if (db_.exec("SELECT pg_try_advisory_lock(" + key_params(session_id) + ")").text_view(0, 0) != "t") {
    refuse_if_held_elsewhere(session_id, who);  // taken between the look and the try
    throw InputError(location_, "session " + std::to_string(session_id),
                     "no other palprig process running session " + std::to_string(session_id) + " of " + who);
  }
  held_.push_back(session_id);
  try {
    db_.exec(
        "INSERT INTO session_locks (session_id, pid, host, since_utc) VALUES ($1, $2, $3, $4) "
        "ON CONFLICT (session_id) DO UPDATE SET pid = EXCLUDED.pid, host = EXCLUDED.host, since_utc = "
        "EXCLUDED.since_utc",
        {pg_text(session_id), std::to_string(::getpid()), this_host_name(), utc_now_text()});
  } catch (...) {
    drop_lock(session_id);
    throw;
  }
}

void PostgresTrialStore::drop_lock(std::int64_t session_id) {
  const auto it = std::find(held_.begin(), held_.end(), session_id);
  if (it == held_.end()) return;
  held_.erase(it);
  if (db_.ok()) db_.exec("SELECT pg_advisory_unlock(" + key_params(session_id) + ")");
}

void PostgresTrialStore::claim_session(std::int64_t session_id) {
  PgTransaction tx(db_);
  std::string status;
  const std::string who = participant_of(db_, session_id, &status);
  if (who.empty()) throw InputError(location_, "session " + std::to_string(session_id), "an existing session");
  if (status != "running") {
    throw InputError(location_, "session " + std::to_string(session_id),
                     "an unfinished session of " + who + " (another palprig process has just completed it)");
  }
  const bool had = std::find(held_.begin(), held_.end(), session_id) != held_.end();
  take_lock(session_id, who);
  try {
    tx.commit();
  } catch (...) {
    if (!had) drop_lock(session_id);
    throw;
  }
}

void PostgresTrialStore::refuse_if_running_elsewhere(std::int64_t session_id) {
  const std::string who = participant_of(db_, session_id);
  if (!who.empty()) refuse_if_held_elsewhere(session_id, who);
}

void PostgresTrialStore::release_session(std::int64_t session_id) {
  if (std::find(held_.begin(), held_.end(), session_id) == held_.end()) return;
  db_.exec("DELETE FROM session_locks WHERE session_id = $1 AND pid = $2 AND host = $3",
           {pg_text(session_id), std::to_string(::getpid()), this_host_name()});
  drop_lock(session_id);
}

}  // namespace palprig
