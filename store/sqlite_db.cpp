#include "store/sqlite_db.hpp"

#include <unistd.h>

#include <sqlite3.h>

#include <chrono>
#include <thread>

#include "models/parse_error.hpp"

namespace palprig {

namespace {

// A damaged file is bad input, not a fault of palprig: one line naming the file, exit 2.
// SQLITE_CORRUPT can surface at any statement (a damaged page is only read when a query reaches
// it), so every error passes through here. `what` is the statement, `detail` SQLite's reason.
[[noreturn]] void throw_sqlite(const std::string& file, const std::string& what, const std::string& detail, int code) {
  if ((code & 0xff) == SQLITE_CORRUPT) throw InputError(file, "database pages", damaged_database_expectation(detail));
  throw SqliteError(file + ": " + (what.empty() ? detail : what + ": " + detail), code);
}

}  // namespace

Database::Database(const std::filesystem::path& file, Mode mode) : file_(file.string()) {
  // NOMUTEX: a connection is used by one thread at a time, so SQLite's per-call mutex (a tenth
  // of the time of a million-row scan) buys nothing.
  // Read-only where we may write the file is query_only on a read-write connection: an
  // SQLITE_OPEN_READONLY connection can neither checkpoint nor delete the -wal and -shm files
  // when it is the last to close, so every `stats`/`export` run and the GUI's statistics view
  // left them beside a database that had been closed cleanly. query_only refuses every change.
  const bool query_only = mode == Mode::read_only && ::access(file_.c_str(), W_OK) == 0 &&
                          open(SQLITE_OPEN_READWRITE | SQLITE_OPEN_NOMUTEX) == SQLITE_OK;
  if (!query_only) {
    const int flags = (mode == Mode::read_only ? SQLITE_OPEN_READONLY : (SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE)) |
                      SQLITE_OPEN_NOMUTEX;
    const int rc = open(flags);
    if (rc != SQLITE_OK) {
      const std::string message = db_ ? sqlite3_errmsg(db_) : sqlite3_errstr(rc);
      sqlite3_close(db_);
      db_ = nullptr;
      throw SqliteError(file_ + ": " + message, rc);
    }
  }
  // A writer holds the lock only for one short transaction per trial: readers (stats, export,
  // the GUI) wait for it rather than failing.
  sqlite3_busy_timeout(db_, kBusyTimeoutMs);
  if (query_only && sqlite3_exec(db_, "PRAGMA query_only = ON", nullptr, nullptr, nullptr) != SQLITE_OK) {
    const std::string message = sqlite3_errmsg(db_);
    sqlite3_close(db_);
    db_ = nullptr;
    throw SqliteError(file_ + ": PRAGMA query_only: " + message, SQLITE_ERROR);
  }
}

int Database::open(int flags) {
  if (db_) sqlite3_close(db_);
  db_ = nullptr;
  return sqlite3_open_v2(file_.c_str(), &db_, flags, nullptr);
}

Database::~Database() { sqlite3_close(db_); }

std::string damaged_database_expectation(const std::string& sqlite_says) {
  std::string reason = sqlite_says.substr(0, 160);
  for (char& c : reason) {
    if (static_cast<unsigned char>(c) < 0x20) c = ' ';  // quick_check lines may hold newlines
  }
  return "an undamaged SQLite database (SQLite: " + reason +
         "); nothing was read from it or written to it: restore it from a backup";
}

void Database::refuse_if_damaged() {
  // quick_check(1): stop at the first problem; O(file size), without the index cross-checks
  // of integrity_check. A damaged schema page fails the pragma itself (InputError from
  // throw_sqlite); damage further in is the pragma's first result row.
  Statement s(*this, "PRAGMA quick_check(1)");
  const std::string first = s.step() ? s.text(0) : std::string("PRAGMA quick_check returned nothing");
  if (first != "ok") throw InputError(file_, "database pages", damaged_database_expectation(first));
}

void Database::fail(const std::string& what, int code) const {
  throw_sqlite(file_, what, sqlite3_errmsg(db_), code);
}

void Database::exec(std::string_view sql) {
  const std::string text(sql);
  char* error = nullptr;
  const int rc = sqlite3_exec(db_, text.c_str(), nullptr, nullptr, &error);
  if (rc != SQLITE_OK) {
    const std::string message = error ? error : sqlite3_errstr(rc);
    sqlite3_free(error);
    throw_sqlite(file_, text.substr(0, 60), message, rc);
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
  if (rc == SQLITE_DONE) return false;
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
