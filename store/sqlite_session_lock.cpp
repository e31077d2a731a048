#include "store/sqlite_trial_store.hpp"

// One process per session in an SQLite store: a lock row names the process (pid, host, start
// time) that runs the session; a holder that died is recognised and taken over (the PostgreSQL
// side's is store/postgres_session_lock.cpp, with advisory locks).
#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <fstream>
#include <iterator>
#include <string>

#include "core/input_error.hpp"
#include "store/host_identity.hpp"
#include "store/utc_time.hpp"

namespace palprig {

namespace {

// Which process runs a session (docs/architecture.md, "Data": one process per session). Created on every
// open for writing, so databases written before the table existed get it too.
constexpr const char* kLockSchema = R"sql(
CREATE TABLE IF NOT EXISTS session_locks (
  session_id    INTEGER PRIMARY KEY REFERENCES sessions(id),
  pid           INTEGER NOT NULL,
  host          TEXT NOT NULL,
  process_start TEXT NOT NULL,                 -- /proc/<pid>/stat start time: a reused pid is not the holder
  since_utc     TEXT NOT NULL
);
)sql";

// Field 22 of /proc/<pid>/stat (start time in clock ticks since boot); "" when there is no
// such process. The command name (field 2) may hold spaces and ')', so fields count from the
// last ')'.
std::string process_start(pid_t pid) {
  std::ifstream in("/proc/" + std::to_string(pid) + "/stat");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const auto close = text.rfind(')');
  if (close == std::string::npos) return "";
  std::size_t pos = close + 2;  // field 3
  for (int field = 3; field < 22 && pos != std::string::npos; ++field) {
    pos = text.find(' ', pos);
    if (pos != std::string::npos) ++pos;
  }
  if (pos == std::string::npos) return "";
  return text.substr(pos, text.find(' ', pos) - pos);
}

bool process_alive(pid_t pid, const std::string& start) {
  if (pid <= 0) return false;
  const std::string now = process_start(pid);
  if (!now.empty()) return start.empty() || now == start;
  return ::kill(pid, 0) == 0 || errno == EPERM;  // no /proc: trust the pid alone
}

}  // namespace

bool SqliteTrialStore::has_lock_table() {
  auto exists = db_.prepare("SELECT count(*) FROM sqlite_master WHERE type = 'table' AND name = 'session_locks'");
  exists.step();
  return exists.integer(0) != 0;
}

void SqliteTrialStore::create_lock_table() {
  // The look-up's statement must be finished before the write lock is asked for: a read left
  // open would keep a shared lock that deadlocks against another process's commit.
  if (has_lock_table()) return;
  Transaction tx(db_);
  if (has_lock_table()) return;
  db_.exec(kLockSchema);
  tx.commit();
}

void SqliteTrialStore::refuse_if_held_elsewhere(std::int64_t session_id, const std::string& who) {
  auto q = db_.prepare("SELECT pid, host, process_start, since_utc FROM session_locks WHERE session_id = ?1");
  q.bind(1, session_id);
  if (!q.step()) return;
  const auto pid = static_cast<pid_t>(q.integer(0));
  const std::string host = q.text(1), start = q.text(2), since = q.text(3);
  const bool same_host = host == this_host_name();
  if (same_host && pid == ::getpid() && start == process_start(::getpid())) return;  // ours
  if (same_host && !process_alive(pid, start)) return;  // its process died (kill -9, power loss): stale
  std::string expected = "no other palprig process running session " + std::to_string(session_id) + " of " + who +
                         " (process " + std::to_string(pid) + " on " + host + " has run it since " + since +
                         "; wait for it to finish, or stop it and continue with --resume";
  if (!same_host) {
    expected += "; if that process is gone, run: sqlite3 " + db_.file() +
                " \"DELETE FROM session_locks WHERE session_id = " + std::to_string(session_id) + "\"";
  }
  throw InputError(db_.file(), "session " + std::to_string(session_id), expected + ")");
}

void SqliteTrialStore::write_lock_row(std::int64_t session_id) {
  auto ins = db_.prepare(
      "INSERT OR REPLACE INTO session_locks (session_id, pid, host, process_start, since_utc) VALUES (?1, ?2, ?3, ?4, "
      "?5)");
  ins.bind(1, session_id)
      .bind(2, static_cast<std::int64_t>(::getpid()))
      .bind(3, this_host_name())
      .bind(4, process_start(::getpid()))
      .bind(5, utc_now_text())
      .run();
  if (std::find(held_.begin(), held_.end(), session_id) == held_.end()) held_.push_back(session_id);
}

void SqliteTrialStore::claim_session(std::int64_t session_id) {
  Transaction tx(db_);
  auto q = db_.prepare(
      "SELECT s.status, p.code FROM sessions s JOIN participants p ON p.id = s.participant_id WHERE s.id = ?1");
  q.bind(1, session_id);
  if (!q.step()) throw InputError(db_.file(), "session " + std::to_string(session_id), "an existing session");
  const std::string status = q.text(0), who = "participant '" + q.text(1) + "'";
  if (status != "running") {
    throw InputError(db_.file(), "session " + std::to_string(session_id),
                     "an unfinished session of " + who + " (another palprig process has just completed it)");
  }
  refuse_if_held_elsewhere(session_id, who);
  write_lock_row(session_id);
  tx.commit();
}

void SqliteTrialStore::refuse_if_running_elsewhere(std::int64_t session_id) {
  auto q = db_.prepare("SELECT p.code FROM sessions s JOIN participants p ON p.id = s.participant_id WHERE s.id = ?1");
  q.bind(1, session_id);
  if (!q.step()) return;
  refuse_if_held_elsewhere(session_id, "participant '" + q.text(0) + "'");
}

void SqliteTrialStore::release_session(std::int64_t session_id) {
  Transaction tx(db_);
  auto del = db_.prepare("DELETE FROM session_locks WHERE session_id = ?1 AND pid = ?2 AND host = ?3");
  del.bind(1, session_id).bind(2, static_cast<std::int64_t>(::getpid())).bind(3, this_host_name()).run();
  tx.commit();
  held_.erase(std::remove(held_.begin(), held_.end(), session_id), held_.end());
}

}  // namespace palprig
