#include "store/sqlite_db.hpp"

#include <sys/stat.h>
#include <unistd.h>

#include <sqlite3.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <thread>

#include "core/input_error.hpp"
#include "store/integrity_check_cache.hpp"
#include "store/sqlite_read_access.hpp"

namespace palprig {

namespace {

// A damaged file is bad input, not a fault of palprig: one line naming the file, exit 2.
// SQLITE_CORRUPT can surface at any statement (a damaged page is only read when a query reaches
// it), so every error passes through here. `what` is the statement, `detail` SQLite's reason.
[[noreturn]] void throw_sqlite(const std::string& file, const std::string& what, const std::string& detail, int code,
                               int system_errno = 0) {
  if ((code & 0xff) == SQLITE_CORRUPT) throw InputError(file, "database pages", damaged_database_expectation(detail));
  if (const std::string cause = sqlite_environment_cause(file, code, system_errno); !cause.empty())
    throw SqliteError(
        file + ": the trial database cannot be used: " + cause + " (SQLite: " + detail.substr(0, 120) + ")", code, true,
        system_errno);
  throw SqliteError(file + ": " + (what.empty() ? detail : what + ": " + detail), code);
}

bool writable(const std::filesystem::path& p) { return ::access(p.c_str(), W_OK) == 0; }

// Device, inode, size, modification and status-change times: any write changes one of them.
std::string file_identity(const std::string& file) {
  struct stat st {};
  if (::stat(file.c_str(), &st) != 0) return "gone";
  return std::to_string(st.st_dev) + ":" + std::to_string(st.st_ino) + " " + std::to_string(st.st_size) + " " +
         std::to_string(st.st_mtim.tv_sec) + "." + std::to_string(st.st_mtim.tv_nsec) + " " +
         std::to_string(st.st_ctim.tv_sec) + "." + std::to_string(st.st_ctim.tv_nsec);
}

}  // namespace

std::string sqlite_environment_cause(const std::string& file, int code, int system_errno) {
  const std::filesystem::path path(file);
  const std::filesystem::path folder = path.has_parent_path() ? path.parent_path() : std::filesystem::path(".");
  const std::string os = system_errno != 0 ? std::string(": ") + std::strerror(system_errno) : "";
  switch (code & 0xff) {
    case SQLITE_READONLY:
      if (std::filesystem::exists(path) && !writable(path)) return "the file is read-only";
      if (!writable(folder))
        return "its folder " + folder.string() + " is read-only (SQLite writes -wal and -shm files beside it)";
      return "the file or its folder is read-only" + os;
    case SQLITE_CANTOPEN:
      if (!std::filesystem::is_directory(folder)) return "its folder " + folder.string() + " does not exist";
      if (!std::filesystem::exists(path) && !writable(folder)) return "its folder " + folder.string() + " is read-only";
      return "it cannot be opened" + os;
    case SQLITE_PERM: return "permission denied" + os;
    case SQLITE_FULL: return "the disk is full (or the file may grow no further)";
    case SQLITE_IOERR:
      if (system_errno == ENOSPC || system_errno == EFBIG || system_errno == EDQUOT)
        return "the disk is full (or the file may grow no further)" + os;
      // SQLite's errno is often lost by the time it reports (it rolls back first): say what
      // a failed write usually is.
      return "a read or write failed (the disk may be full, the file may grow no further, or the device failed)" + os;
    default: return "";
  }
}

Database::Database(const std::filesystem::path& file, Mode mode) : file_(file.string()), mode_(mode) {
  // NOMUTEX: a connection is used by one thread at a time, so SQLite's per-call mutex (a tenth
  // of the time of a million-row scan) buys nothing.
  if (mode == Mode::read_only) {
    open_for_reading();
  } else {
    open_for_writing();
  }
  // A writer holds the lock only for one short transaction per trial: readers (stats, export,
  // the GUI) wait for it rather than failing.
  sqlite3_busy_timeout(db_, kBusyTimeoutMs);
}

void Database::fail_open(int rc) {
  const std::string message = db_ ? sqlite3_errmsg(db_) : sqlite3_errstr(rc);
  const int system_errno = db_ ? sqlite3_system_errno(db_) : 0;
  sqlite3_close(db_);
  db_ = nullptr;
  throw_sqlite(file_, "", message, rc, system_errno);
}

void Database::open_for_writing() {
  const int rc = open(SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE | SQLITE_OPEN_NOMUTEX);
  if (rc != SQLITE_OK) fail_open(rc);
  // SQLite opens a file it may not write read-only without a word, and the first trial would
  // then fail: a writer learns it here, before anything is written.
  if (sqlite3_db_readonly(db_, "main") == 1) {
    sqlite3_close(db_);
    db_ = nullptr;
    throw_sqlite(file_, "", "attempt to write a readonly database", SQLITE_READONLY);
  }
}

void Database::open_for_reading() {
  // Readers never write: SQLITE_OPEN_READONLY can neither change a page nor checkpoint, so a
  // -wal a crashed writer left is read as it is and stays byte for byte. How the -wal and -shm
  // files are handled (immutable, tidying up) is store/sqlite_read_access.hpp.
  const ReadAccess access = plan_read_access(file_);
  immutable_ = access.immutable;
  if (immutable_) identity_at_open_ = file_identity(file_);
  const int rc =
      sqlite3_open_v2(access.uri.c_str(), &db_, SQLITE_OPEN_READONLY | SQLITE_OPEN_URI | SQLITE_OPEN_NOMUTEX, nullptr);
  if (rc != SQLITE_OK) fail_open(rc);
  tidy_sidecars_ = access.tidy_sidecars;
}

void Database::refuse_if_changed_during_read() const {
  if (!immutable_ || file_identity(file_) == identity_at_open_) return;
  throw SqliteError(file_ +
                        ": the database file was written by another process while it was read (it was read without "
                        "SQLite's locks, as this user may not create its -wal and -shm files); run the command again",
                    SQLITE_BUSY, true);
}

int Database::open(int flags) {
  if (db_) sqlite3_close(db_);
  db_ = nullptr;
  return sqlite3_open_v2(file_.c_str(), &db_, flags, nullptr);
}

Database::~Database() {
  sqlite3_close(db_);
  if (tidy_sidecars_) tidy_reader_sidecars(file_);
}

std::string damaged_database_expectation(const std::string& sqlite_says) {
  std::string reason = sqlite_says.substr(0, 160);
  for (char& c : reason) {
    if (static_cast<unsigned char>(c) < 0x20) c = ' ';  // quick_check lines may hold newlines
  }
  return "an undamaged SQLite database (SQLite: " + reason +
         "); nothing was read from it or written to it: restore it from a backup";
}

Database::Check Database::refuse_if_damaged() {
  // A reader meets the same unchanged file again and again (stats by one key, then another;
  // export; the window's statistics): the file state an earlier reader found sound is not
  // checked again. A writer always checks.
  std::optional<StoreFileState> before;
  if (mode_ == Mode::read_only) {
    before = store_file_state(file_);
    if (before && known_sound(*before)) return Check::known_sound;
  }
  // quick_check(1): stop at the first problem; O(file size), without the index cross-checks
  // of integrity_check. A damaged schema page fails the pragma itself (InputError from
  // throw_sqlite); damage further in is the pragma's first result row.
  {
    Statement s(*this, "PRAGMA quick_check(1)");
    const std::string first = s.step() ? s.text(0) : std::string("PRAGMA quick_check returned nothing");
    if (first != "ok") throw InputError(file_, "database pages", damaged_database_expectation(first));
  }
  // Remembered only if nothing changed while it was checked (a writer appending to the -wal).
  if (before && store_file_state(file_) == before) remember_sound(*before);
  return Check::checked;
}

void Database::fail(const std::string& what, int code) const {
  throw_sqlite(file_, what, sqlite3_errmsg(db_), code, sqlite3_system_errno(db_));
}

void Database::exec(std::string_view sql) {
  const std::string text(sql);
  char* error = nullptr;
  const int rc = sqlite3_exec(db_, text.c_str(), nullptr, nullptr, &error);
  if (rc != SQLITE_OK) {
    const std::string message = error ? error : sqlite3_errstr(rc);
    sqlite3_free(error);
    throw_sqlite(file_, text.substr(0, 60), message, rc, sqlite3_system_errno(db_));
  }
}

Statement Database::prepare(std::string_view sql) { return Statement(*this, sql); }

std::int64_t Database::pragma_integer(std::string_view name) {
  Statement s(*this, "PRAGMA " + std::string(name));
  return s.step() ? s.integer(0) : 0;
}

std::int64_t Database::last_insert_rowid() const noexcept { return sqlite3_last_insert_rowid(db_); }

Statement::Statement(Database& db, std::string_view sql) : db_(&db) {
  const int rc = sqlite3_prepare_v2(db.handle(), sql.data(), static_cast<int>(sql.size()), &stmt_, nullptr);
  if (rc != SQLITE_OK) db.fail("preparing \"" + std::string(sql.substr(0, 60)) + "\"", rc);
}

Statement::~Statement() { sqlite3_finalize(stmt_); }

Statement::Statement(Statement&& other) noexcept : db_(other.db_), stmt_(other.stmt_) { other.stmt_ = nullptr; }

Statement& Statement::bind(int index, std::int64_t value) {
  const int rc = sqlite3_bind_int64(stmt_, index, value);
  if (rc != SQLITE_OK) db_->fail("binding an integer", rc);
  return *this;
}

Statement& Statement::bind(int index, double value) {
  const int rc = sqlite3_bind_double(stmt_, index, value);
  if (rc != SQLITE_OK) db_->fail("binding a number", rc);
  return *this;
}

Statement& Statement::bind(int index, std::string_view value) {
  const int rc = sqlite3_bind_text(stmt_, index, value.data(), static_cast<int>(value.size()), SQLITE_TRANSIENT);
  if (rc != SQLITE_OK) db_->fail("binding a text", rc);
  return *this;
}

Statement& Statement::bind_null(int index) {
  const int rc = sqlite3_bind_null(stmt_, index);
  if (rc != SQLITE_OK) db_->fail("binding NULL", rc);
  return *this;
}

bool Statement::step() {
  const int rc = sqlite3_step(stmt_);
  if (rc == SQLITE_ROW) return true;
  if (rc == SQLITE_DONE) {
    // A scan read without locks is only as good as the file's staying still until its end.
    db_->refuse_if_changed_during_read();
    return false;
  }
  db_->fail("executing \"" + std::string(sqlite3_sql(stmt_)).substr(0, 60) + "\"", rc);
}

void Statement::run() {
  step();
  reset();
}

void Statement::reset() {
  sqlite3_reset(stmt_);
  sqlite3_clear_bindings(stmt_);
}

bool Statement::is_null(int column) const noexcept { return sqlite3_column_type(stmt_, column) == SQLITE_NULL; }
std::int64_t Statement::integer(int column) const noexcept { return sqlite3_column_int64(stmt_, column); }
double Statement::real(int column) const noexcept { return sqlite3_column_double(stmt_, column); }

std::string_view Statement::text_view(int column) const noexcept {
  const auto* p = reinterpret_cast<const char*>(sqlite3_column_text(stmt_, column));
  if (!p) return {};
  return {p, static_cast<std::size_t>(sqlite3_column_bytes(stmt_, column))};
}

std::string Statement::text(int column) const { return std::string(text_view(column)); }

void Database::exec_waiting(std::string_view sql) {
  // SQLite returns SQLITE_BUSY without calling the busy handler where waiting could deadlock,
  // and while another process switches the file's journal mode or recovers its WAL index: with
  // several processes starting on one new file, BEGIN IMMEDIATE then fails at once. Those
  // states last milliseconds, so try again for as long as the busy timeout would have waited.
  const auto give_up = std::chrono::steady_clock::now() + std::chrono::milliseconds(kBusyTimeoutMs);
  for (;;) {
    try {
      exec(sql);
      return;
    } catch (const SqliteError& e) {
      if ((e.code() & 0xff) != SQLITE_BUSY || std::chrono::steady_clock::now() >= give_up) throw;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
}

Transaction::Transaction(Database& db) : db_(db) { db_.exec_waiting("BEGIN IMMEDIATE"); }

Transaction::~Transaction() {
  if (!done_) {
    try {
      db_.exec("ROLLBACK");
    } catch (...) {
      // Nothing more to do: SQLite has already rolled back a failed transaction.
    }
  }
}

void Transaction::commit() {
  db_.exec("COMMIT");
  done_ = true;
}

}  // namespace palprig
