#include "store/sqlite_trial_store.hpp"

#include <signal.h>
#include <sqlite3.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <fstream>
#include <cmath>
#include <limits>
#include <map>

#include "experiments/scoring.hpp"
#include "models/parse_error.hpp"
#include "store/sqlite_session_rows.hpp"
#include "store/utc_time.hpp"

namespace palprig {

namespace {

constexpr const char* kSchema = R"sql(
CREATE TABLE participants (
  id          INTEGER PRIMARY KEY,
  code        TEXT NOT NULL UNIQUE,
  number      INTEGER NOT NULL UNIQUE,         -- 1-based enrolment order (counterbalancing)
  simulated   INTEGER NOT NULL CHECK (simulated IN (0, 1)),
  created_utc TEXT NOT NULL
);
CREATE TABLE sessions (
  id                INTEGER PRIMARY KEY,
  participant_id    INTEGER NOT NULL REFERENCES participants(id),
  protocol_name     TEXT NOT NULL,
  task              TEXT NOT NULL,
  bids_task         TEXT NOT NULL,
  protocol_json     TEXT NOT NULL,             -- the protocol file as read
  protocol_dir      TEXT NOT NULL,
  seed              INTEGER NOT NULL,
  condition_order   TEXT NOT NULL,             -- JSON array of condition indices
  rig_id            TEXT NOT NULL,
  rig_backend       TEXT NOT NULL,
  calibration       TEXT NOT NULL,
  participant_model TEXT,                      -- simulated participant parameters (JSON)
  status            TEXT NOT NULL CHECK (status IN ('running', 'completed')),
  started_utc       TEXT NOT NULL,
  finished_utc      TEXT
);
CREATE TABLE planned_trials (                  -- the generated order, stored before trial 1
  session_id      INTEGER NOT NULL REFERENCES sessions(id),
  position        INTEGER NOT NULL,
  block           INTEGER NOT NULL,
  condition_index INTEGER NOT NULL,
  condition       TEXT NOT NULL,
  practice        INTEGER NOT NULL,
  combination     INTEGER NOT NULL,            -- -1 for localisation
  break_after     INTEGER NOT NULL,
  PRIMARY KEY (session_id, position)
) WITHOUT ROWID;
CREATE TABLE trials (
  id                INTEGER PRIMARY KEY,
  session_id        INTEGER NOT NULL REFERENCES sessions(id),
  position          INTEGER NOT NULL,
  block             INTEGER NOT NULL,
  condition         TEXT NOT NULL,
  mode              TEXT NOT NULL,
  practice          INTEGER NOT NULL,
  combination       INTEGER NOT NULL,
  combination_label TEXT,
  stimulus1_kPa     REAL, stimulus2_kPa REAL, stimulus3_kPa REAL,
  truth             TEXT,                      -- per finger 1/0, e.g. "010"
  answered          INTEGER NOT NULL,          -- 0: the response timed out
  answer            TEXT,                      -- per finger 1/0; NULL when not answered
  response_time_s   REAL,
  onset_s           REAL NOT NULL,
  felt1_kPa         REAL, felt2_kPa REAL, felt3_kPa REAL,
  outcome1          TEXT CHECK (outcome1 IN ('TP', 'FN', 'TN', 'FP')),
  outcome2          TEXT CHECK (outcome2 IN ('TP', 'FN', 'TN', 'FP')),
  outcome3          TEXT CHECK (outcome3 IN ('TP', 'FN', 'TN', 'FP')),
  false_marks       INTEGER,
  completed_utc     TEXT NOT NULL,
  confidence        INTEGER CHECK (confidence BETWEEN 1 AND 9),  -- NULL: not asked or not answered
  stimulus_end_s    REAL,                      -- when the stimulus ended (onset_s's clock)
  UNIQUE (session_id, position)
);
CREATE TABLE tumor_scores (
  trial_id        INTEGER NOT NULL REFERENCES trials(id),
  tumor           TEXT NOT NULL,
  outcome         TEXT NOT NULL CHECK (outcome IN ('TP', 'FN')),
  nearest_mark_mm REAL,
  PRIMARY KEY (trial_id, tumor)
) WITHOUT ROWID;
CREATE TABLE marks (
  trial_id INTEGER NOT NULL REFERENCES trials(id),
  mark     INTEGER NOT NULL,
  x_mm     REAL NOT NULL,
  y_mm     REAL NOT NULL,
  tumor    TEXT,                               -- the tumor it hit; NULL for a false mark
  PRIMARY KEY (trial_id, mark)
) WITHOUT ROWID;
)sql";

// Schema 1 -> 2: the confidence rating and the stimulus end (appended, as in kSchema).
constexpr const char* kMigrationTo2 = R"sql(
ALTER TABLE trials ADD COLUMN confidence INTEGER CHECK (confidence BETWEEN 1 AND 9);
ALTER TABLE trials ADD COLUMN stimulus_end_s REAL;
PRAGMA user_version = 2;
)sql";

// Which process runs a session (DESIGN.md "Data": one process per session). Created on every
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

std::string this_host() {
  char name[256] = {};
  if (::gethostname(name, sizeof name - 1) != 0) return "unknown";
  return name;
}

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

std::string flags_text(const FingerFlags& f) {
  std::string s;
  for (bool b : f) s += b ? '1' : '0';
  return s;
}

std::optional<double> finite_or_null(double x) {
  if (std::isfinite(x)) return x;
  return std::nullopt;
}

std::optional<double> real_or_null(const Statement& s, int column) {
  if (s.is_null(column)) return std::nullopt;
  return s.real(column);
}

double real_or_nan(const Statement& s, int column) {
  return s.is_null(column) ? std::numeric_limits<double>::quiet_NaN() : s.real(column);
}

std::string practice_filter(bool include_practice, const char* keyword) {
  return include_practice ? std::string() : std::string(" ") + keyword + " t.practice = 0";
}

}  // namespace

SqliteTrialStore::SqliteTrialStore(const std::filesystem::path& file, Access access) try
    : db_(file, access == Access::read_only ? Database::Mode::read_only : Database::Mode::read_write_create) {
  if (access == Access::read_write) create_schema_if_blank();
  check_identity();
  // Never write into a damaged file (a new session in it could be lost with the rest, and
  // SQLite may make the damage worse), and never compute statistics or exports from one (the
  // trials on bad pages would silently be missing).
  db_.refuse_if_damaged();
  if (access == Access::read_write) migrate_if_older();
  rating_columns_ = sqlite_trials_have_rating_columns(db_);
  if (access == Access::read_write) create_lock_table();
  // Scans of large stores (stats, export) read through a memory map instead of copying pages.
  db_.exec("PRAGMA mmap_size = 1073741824");
  if (access == Access::read_write) {
    // WAL: readers never block the writer; synchronous FULL: a committed trial survives a
    // crash of the process and of the machine.
    db_.exec_waiting("PRAGMA journal_mode = WAL");
    db_.exec("PRAGMA synchronous = FULL; PRAGMA foreign_keys = ON;");
  }
} catch (const SqliteError& e) {
  // Whatever the member initialiser or the checks threw, the file was the problem.
  if (e.code() == SQLITE_NOTADB) {
    throw InputError(file.string(), "file", "a palprig trial database (this is not an SQLite database)");
  }
  // Opening, creating or migrating a store writes none of its trials: a read-only file or
  // folder, a full disk, is one line naming the file and the cause, exit 2.
  if (e.environment() || e.code() == SQLITE_CANTOPEN) {
    std::string cause = sqlite_environment_cause(file.string(), e.code(), e.system_errno());
    throw InputError(file.string(), "file",
                     "a trial database palprig can open and write (" + (cause.empty() ? std::string(e.what()) : cause) +
                         "; nothing was written)");
  }
  throw;
}

SqliteTrialStore::~SqliteTrialStore() {
  const std::vector<std::int64_t> held = held_;  // release_session edits held_
  for (std::int64_t session_id : held) {
    try {
      release_session(session_id);
    } catch (...) {
      // A database gone bad on the way out: the lock row names a dead process, which the next
      // claim recognises as stale.
    }
  }
}

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
  const bool same_host = host == this_host();
  if (same_host && pid == ::getpid() && start == process_start(::getpid())) return;  // ours
  if (same_host && !process_alive(pid, start)) return;  // its process died (kill -9, power loss): stale
  std::string expected = "no other palprig process running session " + std::to_string(session_id) + " of " + who +
                         " (process " + std::to_string(pid) + " on " + host + " has run it since " + since +
                         "; wait for it to finish, or stop it and continue with --resume";
  if (!same_host) {
    expected += "; if that process is gone, run: sqlite3 " + db_.file() + " \"DELETE FROM session_locks WHERE session_id = " +
                std::to_string(session_id) + "\"";
  }
  throw InputError(db_.file(), "session " + std::to_string(session_id), expected + ")");
}

void SqliteTrialStore::write_lock_row(std::int64_t session_id) {
  auto ins = db_.prepare(
      "INSERT OR REPLACE INTO session_locks (session_id, pid, host, process_start, since_utc) VALUES (?1, ?2, ?3, ?4, ?5)");
  ins.bind(1, session_id)
      .bind(2, static_cast<std::int64_t>(::getpid()))
      .bind(3, this_host())
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
  del.bind(1, session_id).bind(2, static_cast<std::int64_t>(::getpid())).bind(3, this_host()).run();
  tx.commit();
  held_.erase(std::remove(held_.begin(), held_.end(), session_id), held_.end());
}

bool SqliteTrialStore::is_blank() {
  if (db_.pragma_integer("application_id") != 0 || db_.pragma_integer("user_version") != 0) return false;
  auto tables = db_.prepare("SELECT count(*) FROM sqlite_master");
  tables.step();
  return tables.integer(0) == 0;
}

void SqliteTrialStore::create_schema_if_blank() {
  if (!is_blank()) return;
  // Two processes starting on one new file: the write lock of BEGIN IMMEDIATE lets one create
  // the schema; the other waits (busy timeout), then finds the file no longer blank.
  Transaction tx(db_);
  if (!is_blank()) return;
  db_.exec(kSchema);
  db_.exec("PRAGMA application_id = " + std::to_string(kTrialStoreApplicationId));
  db_.exec("PRAGMA user_version = " + std::to_string(kTrialStoreSchemaVersion));
  tx.commit();
}

void SqliteTrialStore::migrate_if_older() {
  if (db_.pragma_integer("user_version") >= kTrialStoreSchemaVersion) return;
  // One transaction under the write lock: another process may have migrated it meanwhile, and a
  // failure half-way leaves the file (and every trial) as it was.
  Transaction tx(db_);
  if (db_.pragma_integer("user_version") >= kTrialStoreSchemaVersion) return;
  try {
    db_.exec(kMigrationTo2);
  } catch (const SqliteError& e) {
    // Busy: another writer; try again later (not the file's fault). Anything else: the file's
    // tables are not what schema 1 says (hand-edited, or a foreign tool): refused, unchanged.
    const int primary = e.code() & 0xff;
    if (primary == SQLITE_BUSY || primary == SQLITE_LOCKED) throw;
    throw InputError(db_.file(), "trials (schema 1 -> 2 migration)",
                     std::string("a schema-1 trial database palprig can migrate (SQLite: ") + e.what() +
                         "); the file was not changed");
  }
  tx.commit();
}

void SqliteTrialStore::check_identity() {
  if (db_.pragma_integer("application_id") != kTrialStoreApplicationId) {
    throw InputError(db_.file(), "PRAGMA application_id",
                     "a palprig trial database (this SQLite file belongs to another program or is empty)");
  }
  const std::int64_t version = db_.pragma_integer("user_version");
  if (version > kTrialStoreSchemaVersion) {
    throw InputError(db_.file(), "PRAGMA user_version",
                     "schema version " + std::to_string(kTrialStoreSchemaVersion) +
                         " or older (written by a newer palprig: schema " + std::to_string(version) + ")");
  }
  if (version < 1) throw InputError(db_.file(), "PRAGMA user_version", "a palprig schema version (found none)");
}

std::optional<ParticipantRecord> SqliteTrialStore::find_participant(const std::string& code) {
  auto s = db_.prepare("SELECT id, code, number, simulated FROM participants WHERE code = ?1");
  s.bind(1, code);
  if (!s.step()) return std::nullopt;
  return ParticipantRecord{s.integer(0), s.text(1), static_cast<int>(s.integer(2)), s.integer(3) != 0};
}

ParticipantRecord SqliteTrialStore::enrol(const std::string& code, bool simulated) {
  if (auto p = find_participant(code)) return *p;
  Transaction tx(db_);
  // Another process may have enrolled the same code between the look-up and the write lock.
  if (auto p = find_participant(code)) return *p;
  auto next = db_.prepare("SELECT COALESCE(MAX(number), 0) + 1 FROM participants");
  next.step();
  const int number = static_cast<int>(next.integer(0));
  auto ins = db_.prepare("INSERT INTO participants (code, number, simulated, created_utc) VALUES (?1, ?2, ?3, ?4)");
  ins.bind(1, code).bind(2, number).bind(3, simulated ? 1 : 0).bind(4, utc_now_text()).run();
  const std::int64_t id = db_.last_insert_rowid();
  tx.commit();
  return ParticipantRecord{id, code, number, simulated};
}

std::optional<std::int64_t> SqliteTrialStore::find_unfinished_session(const ParticipantRecord& who, const std::string& protocol_name) {
  auto s = db_.prepare(
      "SELECT id FROM sessions WHERE participant_id = ?1 AND protocol_name = ?2 AND status = 'running' "
      "ORDER BY id DESC LIMIT 1");
  s.bind(1, who.id).bind(2, protocol_name);
  if (!s.step()) return std::nullopt;
  return s.integer(0);
}

std::int64_t SqliteTrialStore::insert_session_row(const ParticipantRecord& who, const TaskSessionRow& row,
                                                 const SessionSetup& setup) {
  // Under the write lock: another process may have started this participant's session since
  // the caller looked for an unfinished one (the same participant started twice at once).
  {
    auto running = db_.prepare(
        "SELECT id FROM sessions WHERE participant_id = ?1 AND protocol_name = ?2 AND status = 'running' "
        "ORDER BY id DESC LIMIT 1");
    running.bind(1, who.id).bind(2, row.protocol_name);
    if (running.step()) {
      const std::int64_t other = running.integer(0);
      const std::string name = "participant '" + who.code + "'";
      refuse_if_held_elsewhere(other, name);
      throw InputError(db_.file(), name,
                       "already has an unfinished session with protocol '" + row.protocol_name + "' (session " +
                           std::to_string(other) + "); to continue it, run the same command again with --resume");
    }
  }
  auto ins = db_.prepare(
      "INSERT INTO sessions (participant_id, protocol_name, task, bids_task, protocol_json, protocol_dir, seed, "
      "condition_order, rig_id, rig_backend, calibration, participant_model, status, started_utc) "
      "VALUES (?1, ?2, ?3, ?4, ?5, ?6, ?7, ?8, ?9, ?10, ?11, ?12, 'running', ?13)");
  ins.bind(1, who.id)
      .bind(2, row.protocol_name)
      .bind(3, row.task)
      .bind(4, row.bids_task)
      .bind(5, row.protocol_snapshot.dump())
      .bind(6, setup.protocol_dir)
      .bind(7, static_cast<std::int64_t>(row.seed))  // stored as the same 64 bits
      .bind(8, row.condition_order.dump())
      .bind(9, setup.rig_id)
      .bind(10, setup.rig_backend)
      .bind(11, setup.calibration);
  if (setup.participant_model.is_null()) ins.bind_null(12);
  else ins.bind(12, setup.participant_model.dump());
  ins.bind(13, utc_now_text()).run();
  return db_.last_insert_rowid();
}

std::int64_t SqliteTrialStore::create_task_session(const ParticipantRecord& who, const TaskSessionRow& row,
                                                   const SessionSetup& setup) {
  Transaction tx(db_);
  const std::int64_t session_id = insert_session_row(who, row, setup);
  write_lock_row(session_id);
  tx.commit();
  return session_id;
}

StoredTaskSession SqliteTrialStore::load_task_session(std::int64_t session_id, const std::string& task,
                                                      const std::string& trial_table) {
  auto q = db_.prepare(
      "SELECT s.id, s.protocol_json, s.protocol_dir, s.seed, s.status, p.id, p.code, p.number, p.simulated, s.task "
      "FROM sessions s JOIN participants p ON p.id = s.participant_id WHERE s.id = ?1");
  q.bind(1, session_id);
  const std::string which = "session " + std::to_string(session_id);
  if (!q.step()) throw InputError(db_.file(), which, "an existing " + task + " session");
  if (q.text(9) != task) throw InputError(db_.file(), which, "a " + task + " session, got task " + q.text(9));
  StoredTaskSession s;
  s.id = q.integer(0);
  s.protocol_snapshot = nlohmann::json::parse(q.text(1));
  s.protocol_dir = q.text(2);
  s.seed = static_cast<std::uint64_t>(q.integer(3));
  s.status = q.text(4);
  s.participant = ParticipantRecord{q.integer(5), q.text(6), static_cast<int>(q.integer(7)), q.integer(8) != 0};
  // trial_table is one of the store's own table names (threshold_trials, pulse_trials), never user text.
  auto done = db_.prepare("SELECT count(*), COALESCE(MAX(position), -1) FROM " + trial_table + " WHERE session_id = ?1");
  done.bind(1, session_id);
  done.step();
  s.completed_trials = static_cast<int>(done.integer(0));
  if (done.integer(1) != s.completed_trials - 1) {
    throw InputError(db_.file(), which,
                     task + " trials committed in order (positions are missing; the database was edited)");
  }
  return s;
}

std::int64_t SqliteTrialStore::create_session(const ParticipantRecord& who, const Protocol& protocol, const SessionPlan& plan,
                                        const SessionSetup& setup) {
  Transaction tx(db_);
  const TaskSessionRow row{to_string(protocol.task), protocol.name, protocol.bids_task, protocol.snapshot, plan.seed,
                           nlohmann::json(plan.condition_order)};
  const std::int64_t session_id = insert_session_row(who, row, setup);

  auto planned = db_.prepare(
      "INSERT INTO planned_trials (session_id, position, block, condition_index, condition, practice, combination, "
      "break_after) VALUES (?1, ?2, ?3, ?4, ?5, ?6, ?7, ?8)");
  for (const PlannedTrial& t : plan.trials) {
    planned.bind(1, session_id)
        .bind(2, t.position)
        .bind(3, t.block)
        .bind(4, t.condition)
        .bind(5, protocol.conditions.at(static_cast<std::size_t>(t.condition)).name)
        .bind(6, t.practice ? 1 : 0)
        .bind(7, t.combination)
        .bind(8, t.break_after ? 1 : 0)
        .run();
  }
  write_lock_row(session_id);
  tx.commit();
  return session_id;
}

StoredSession SqliteTrialStore::load_session(std::int64_t session_id) {
  StoredSession s;
  auto q = db_.prepare(
      "SELECT s.id, s.protocol_json, s.protocol_dir, s.status, s.seed, s.condition_order, p.id, p.code, p.number, "
      "p.simulated FROM sessions s JOIN participants p ON p.id = s.participant_id WHERE s.id = ?1");
  q.bind(1, session_id);
  if (!q.step()) throw InputError(db_.file(), "session " + std::to_string(session_id), "an existing session");
  s.id = q.integer(0);
  s.protocol_snapshot = nlohmann::json::parse(q.text(1));
  s.protocol_dir = q.text(2);
  s.status = q.text(3);
  s.plan.seed = static_cast<std::uint64_t>(q.integer(4));
  s.plan.condition_order = nlohmann::json::parse(q.text(5)).get<std::vector<int>>();
  s.participant = ParticipantRecord{q.integer(6), q.text(7), static_cast<int>(q.integer(8)), q.integer(9) != 0};
  s.plan.participant_number = s.participant.number;

  auto t = db_.prepare(
      "SELECT position, block, condition_index, practice, combination, break_after FROM planned_trials "
      "WHERE session_id = ?1 ORDER BY position");
  t.bind(1, session_id);
  while (t.step()) {
    s.plan.trials.push_back(PlannedTrial{static_cast<int>(t.integer(0)), static_cast<int>(t.integer(1)),
                                         static_cast<int>(t.integer(2)), t.integer(3) != 0,
                                         static_cast<int>(t.integer(4)), t.integer(5) != 0});
  }
  auto done = db_.prepare("SELECT count(*), COALESCE(MAX(position), -1) FROM trials WHERE session_id = ?1");
  done.bind(1, session_id);
  done.step();
  s.completed_trials = static_cast<int>(done.integer(0));
  // Trials are committed in order, so the committed ones are exactly positions 0..n-1.
  if (done.integer(1) != s.completed_trials - 1) {
    throw InputError(db_.file(), "session " + std::to_string(session_id),
                     "trials committed in order (positions are missing; the database was edited)");
  }
  return s;
}

void SqliteTrialStore::complete_session(std::int64_t session_id) {
  Transaction tx(db_);
  auto u = db_.prepare("UPDATE sessions SET status = 'completed', finished_utc = ?2 WHERE id = ?1");
  u.bind(1, session_id).bind(2, utc_now_text()).run();
  auto del = db_.prepare("DELETE FROM session_locks WHERE session_id = ?1");
  del.bind(1, session_id).run();
  tx.commit();
  held_.erase(std::remove(held_.begin(), held_.end(), session_id), held_.end());
}

void SqliteTrialStore::insert_trial(std::int64_t session_id, const TrialRecord& r) {
  const bool discrimination = r.mode != PresentationMode::scene;
  if (!insert_trial_) {
    insert_trial_ = std::make_unique<Statement>(db_,
      "INSERT INTO trials (session_id, position, block, condition, mode, practice, combination, combination_label, "
      "stimulus1_kPa, stimulus2_kPa, stimulus3_kPa, truth, answered, answer, response_time_s, onset_s, felt1_kPa, "
      "felt2_kPa, felt3_kPa, outcome1, outcome2, outcome3, false_marks, completed_utc, confidence, stimulus_end_s) "
      "VALUES (?1, ?2, ?3, ?4, ?5, ?6, ?7, ?8, ?9, ?10, ?11, ?12, ?13, ?14, ?15, ?16, ?17, ?18, ?19, ?20, ?21, ?22, "
      "?23, ?24, ?25, ?26)");
  }
  Statement& ins = *insert_trial_;
  ins.bind(1, session_id)
      .bind(2, r.planned.position)
      .bind(3, r.planned.block)
      .bind(4, r.condition)
      .bind(5, to_string(r.mode))
      .bind(6, r.planned.practice ? 1 : 0)
      .bind(7, r.planned.combination)
      .bind(13, r.answered ? 1 : 0)
      .bind(16, r.onset_s)
      .bind(24, utc_now_text());
  if (auto end = finite_or_null(r.stimulus_end_s)) ins.bind(26, *end);
  if (r.answered && r.confidence) ins.bind(25, static_cast<std::int64_t>(*r.confidence));
  if (discrimination) {
    ins.bind(8, r.combination_label);
    for (int f = 0; f < kFingerCount; ++f) ins.bind(9 + f, r.stimulus_kPa[static_cast<std::size_t>(f)]);
    ins.bind(12, flags_text(r.truth));
  }
  for (int f = 0; f < kFingerCount; ++f) ins.bind(17 + f, finite_or_null(r.felt_kPa[static_cast<std::size_t>(f)]));
  if (r.answered) {
    ins.bind(15, r.response_time_s);
    if (discrimination) {
      ins.bind(14, flags_text(r.answer));
      for (int f = 0; f < kFingerCount; ++f) ins.bind(20 + f, to_string(r.finger_outcomes[static_cast<std::size_t>(f)]));
    } else {
      ins.bind(23, r.localisation.false_marks);
    }
  }
  ins.run();
  const std::int64_t trial_id = db_.last_insert_rowid();
  if (!discrimination && r.answered) {
    auto ts = db_.prepare("INSERT INTO tumor_scores (trial_id, tumor, outcome, nearest_mark_mm) VALUES (?1, ?2, ?3, ?4)");
    for (const TumorScore& score : r.localisation.tumors) {
      ts.bind(1, trial_id).bind(2, score.tumor).bind(3, score.hit ? "TP" : "FN");
      if (score.nearest_mark_mm >= 0) ts.bind(4, score.nearest_mark_mm);
      ts.run();
    }
    auto mk = db_.prepare("INSERT INTO marks (trial_id, mark, x_mm, y_mm, tumor) VALUES (?1, ?2, ?3, ?4, ?5)");
    for (std::size_t i = 0; i < r.marks.size(); ++i) {
      mk.bind(1, trial_id).bind(2, static_cast<std::int64_t>(i)).bind(3, r.marks[i].x_mm).bind(4, r.marks[i].y_mm);
      const int hit = i < r.localisation.mark_tumor.size() ? r.localisation.mark_tumor[i] : -1;
      if (hit >= 0) mk.bind(5, r.localisation.tumors[static_cast<std::size_t>(hit)].tumor);
      mk.run();
    }
  }
}

void SqliteTrialStore::commit_trial(std::int64_t session_id, const TrialRecord& trial) {
  Transaction tx(db_);
  insert_trial(session_id, trial);
  tx.commit();
}

void SqliteTrialStore::commit_trials(std::int64_t session_id, std::span<const TrialRecord> trials) {
  Transaction tx(db_);
  for (const TrialRecord& t : trials) insert_trial(session_id, t);
  tx.commit();
}

std::vector<SessionOverview> SqliteTrialStore::list_sessions() {
  std::vector<SessionOverview> sessions;
  auto q = db_.prepare(
      "SELECT s.id, p.id, p.code, p.number, p.simulated, s.protocol_name, s.task, s.bids_task, s.status "
      "FROM sessions s JOIN participants p ON p.id = s.participant_id ORDER BY s.id");
  while (q.step()) {
    sessions.push_back(SessionOverview{
        q.integer(0), ParticipantRecord{q.integer(1), q.text(2), static_cast<int>(q.integer(3)), q.integer(4) != 0},
        q.text(5), q.text(6), q.text(7), q.text(8)});
  }
  return sessions;
}

nlohmann::json SqliteTrialStore::protocol_snapshot(std::int64_t session_id) {
  auto q = db_.prepare("SELECT protocol_json FROM sessions WHERE id = ?1");
  q.bind(1, session_id);
  if (!q.step()) throw InputError(db_.file(), "session " + std::to_string(session_id), "an existing session");
  // A snapshot that no longer parses is reported as null: readers fall back to defaults.
  return nlohmann::json::parse(q.text_view(0), nullptr, false);
}

std::string SqliteTrialStore::rating_columns(const char* prefix) const {
  if (!rating_columns_) return "NULL, NULL";  // a schema-1 file read as it is
  return std::string(prefix) + "confidence, " + prefix + "stimulus_end_s";
}

void SqliteTrialStore::scan_scored_trials(TrialFamily family, bool include_practice,
                                          const std::function<void(const ScoredTrial&)>& visit) {
  if (family == TrialFamily::discrimination) {
    auto q = db_.prepare(
        "SELECT t.id, t.session_id, t.condition, t.answered, t.response_time_s, t.outcome1, t.outcome2, t.outcome3, "
        "t.combination_label, t.onset_s, " + rating_columns("t.") + " FROM trials t WHERE t.mode != 'scene'" +
        practice_filter(include_practice, "AND"));
    ScoredTrial t;
    while (q.step()) {
      t.trial_id = q.integer(0);
      t.session_id = q.integer(1);
      t.condition = q.text_view(2);
      t.answered = q.integer(3) != 0;
      t.response_time_s = real_or_nan(q, 4);
      for (int f = 0; f < kFingerCount; ++f) {
        t.finger_outcomes[static_cast<std::size_t>(f)] = t.answered ? outcome_from_string(q.text_view(5 + f)) : std::nullopt;
      }
      t.combination_label = q.is_null(8) ? std::nullopt : std::optional<std::string_view>(q.text_view(8));
      t.rt_after_stimulus_s = response_time_after_stimulus_s(q.real(9), t.response_time_s, real_or_nan(q, 11));
      t.confidence = q.is_null(10) ? std::nullopt : std::optional<int>(static_cast<int>(q.integer(10)));
      visit(t);
    }
    return;
  }
  // Localisation: one row per (trial, tumor score); the rows of a trial are gathered and the
  // trial handed on when the next one starts.
  auto q = db_.prepare(
      "SELECT t.id, t.session_id, t.condition, t.answered, t.response_time_s, ts.tumor, ts.outcome, t.false_marks, "
      "t.onset_s, " + rating_columns("t.") + " FROM trials t LEFT JOIN tumor_scores ts ON ts.trial_id = t.id WHERE t.mode = 'scene'" +
      practice_filter(include_practice, "AND") + " ORDER BY t.id");
  ScoredTrial t;
  std::string condition;
  std::vector<std::string> tumor_names;  // reused: the views in `tumors` point into it
  std::vector<ScoredTumor> tumors;
  std::size_t tumor_count = 0;
  bool pending = false;
  const auto flush = [&] {
    if (!pending) return;
    tumors.resize(tumor_count);
    for (std::size_t i = 0; i < tumor_count; ++i) tumors[i].tumor = tumor_names[i];
    t.condition = condition;
    t.tumors = std::span<const ScoredTumor>(tumors.data(), tumor_count);
    visit(t);
    pending = false;
  };
  while (q.step()) {
    const std::int64_t trial_id = q.integer(0);
    if (!pending || trial_id != t.trial_id) {
      flush();
      pending = true;
      tumor_count = 0;
      t = ScoredTrial{};
      t.trial_id = trial_id;
      t.session_id = q.integer(1);
      condition.assign(q.text_view(2));
      t.answered = q.integer(3) != 0;
      t.response_time_s = real_or_nan(q, 4);
      t.false_marks = q.is_null(7) ? 0 : q.integer(7);
      t.rt_after_stimulus_s = response_time_after_stimulus_s(q.real(8), t.response_time_s, real_or_nan(q, 10));
    }
    if (q.is_null(5)) continue;
    const auto outcome = outcome_from_string(q.text_view(6));
    if (!outcome) continue;
    if (tumor_names.size() <= tumor_count) tumor_names.emplace_back();
    if (tumors.size() <= tumor_count) tumors.emplace_back();
    tumor_names[tumor_count].assign(q.text_view(5));
    tumors[tumor_count].outcome = *outcome;
    ++tumor_count;
  }
  flush();
}

std::vector<StoredTrial> SqliteTrialStore::read_trials(bool include_practice) {
  std::vector<StoredTrial> trials;
  auto q = db_.prepare(
      "SELECT p.code, p.simulated, p.number, s.id, s.protocol_name, s.task, s.bids_task, t.id, t.position, t.block, "
      "t.condition, t.mode, t.practice, t.combination, t.combination_label, t.stimulus1_kPa, t.stimulus2_kPa, "
      "t.stimulus3_kPa, t.felt1_kPa, t.felt2_kPa, t.felt3_kPa, t.truth, t.answered, t.answer, t.response_time_s, "
      "t.onset_s, t.outcome1, t.outcome2, t.outcome3, t.false_marks, t.completed_utc, " + rating_columns("t.") +
      " FROM trials t JOIN sessions s ON s.id = t.session_id JOIN participants p ON p.id = s.participant_id" +
      practice_filter(include_practice, "WHERE") + " ORDER BY p.number, s.id, t.position");
  while (q.step()) {
    StoredTrial t;
    t.participant = q.text(0);
    t.simulated = q.integer(1) != 0;
    t.participant_number = static_cast<int>(q.integer(2));
    t.session = q.integer(3);
    t.protocol = q.text(4);
    t.task = q.text(5);
    t.bids_task = q.text(6);
    t.id = q.integer(7);
    t.position = static_cast<int>(q.integer(8));
    t.block = static_cast<int>(q.integer(9));
    t.condition = q.text(10);
    t.mode = q.text(11);
    t.practice = q.integer(12) != 0;
    t.combination = static_cast<int>(q.integer(13));
    t.combination_label = q.text(14);
    for (int f = 0; f < kFingerCount; ++f) {
      t.stimulus_kPa[static_cast<std::size_t>(f)] = real_or_null(q, 15 + f);
      t.felt_kPa[static_cast<std::size_t>(f)] = real_or_null(q, 18 + f);
      t.outcome[static_cast<std::size_t>(f)] = q.text(26 + f);
    }
    t.truth = q.text(21);
    t.answered = q.integer(22) != 0;
    t.answer = q.text(23);
    t.response_time_s = real_or_null(q, 24);
    t.onset_s = q.real(25);
    if (!q.is_null(29)) t.false_marks = q.integer(29);
    t.completed_utc = q.text(30);
    if (!q.is_null(31)) t.confidence = static_cast<int>(q.integer(31));
    t.stimulus_end_s = real_or_null(q, 32);
    if (t.answered && t.response_time_s && t.stimulus_end_s) {
      t.rt_after_stimulus_s = response_time_after_stimulus_s(t.onset_s, *t.response_time_s, *t.stimulus_end_s);
    }
    trials.push_back(std::move(t));
  }
  auto ts = db_.prepare("SELECT tumor, outcome FROM tumor_scores WHERE trial_id = ?1 ORDER BY tumor");
  auto mk = db_.prepare("SELECT mark, x_mm, y_mm, tumor FROM marks WHERE trial_id = ?1 ORDER BY mark");
  for (StoredTrial& t : trials) {
    if (t.mode != "scene") continue;
    ts.bind(1, t.id);
    while (ts.step()) t.tumor_outcomes.emplace_back(ts.text(0), ts.text(1));
    ts.reset();
    mk.bind(1, t.id);
    while (mk.step()) {
      StoredMark m{static_cast<int>(mk.integer(0)), mk.real(1), mk.real(2), std::nullopt};
      if (!mk.is_null(3)) m.tumor = mk.text(3);
      t.marks.push_back(std::move(m));
    }
    mk.reset();
  }
  return trials;
}

SqliteTrialStore open_sqlite_trial_store_for_reading(const std::filesystem::path& file) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec)) {
    throw InputError(file.string(), "file", "an existing palprig trial database");
  }
  return SqliteTrialStore(file, TrialStore::Access::read_only);
}

}  // namespace palprig
