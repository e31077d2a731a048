#pragma once
// A thin RAII layer over the SQLite C API for the trial store: a connection, prepared
// statements with bind/step/column, and a transaction that rolls back unless committed.
// Errors throw SqliteError with SQLite's message and the database file; a damaged file
// (SQLITE_CORRUPT, at whichever statement first reads a bad page) throws InputError instead,
// since it is bad input rather than a fault of the program.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

#include "core/error.hpp"

struct sqlite3;
struct sqlite3_stmt;

namespace palprig {

// An Error (core/error.hpp, exit 1): the file or the machine failed while the store was used;
// where it is the user's file that is refused, the store throws InputError instead.
class SqliteError : public Error {
 public:
  SqliteError(const std::string& what, int code, bool environment = false, int system_errno = 0)
      : Error(what), code_(code), environment_(environment), system_errno_(system_errno) {}
  int code() const noexcept { return code_; }
  int system_errno() const noexcept { return system_errno_; }
  // The machine, not the data: a read-only file or folder, a full disk, a failed write. The
  // message is then palprig's own ("FILE: the trial database cannot be used: the disk is full
  // (SQLite: ...)").
  bool environment() const noexcept { return environment_; }

 private:
  int code_;
  bool environment_;
  int system_errno_;
};

// What keeps SQLite from writing `file`, in words, for an error `code` (SQLITE_READONLY,
// SQLITE_CANTOPEN, SQLITE_FULL, SQLITE_IOERR, SQLITE_PERM) with the system's errno beside it;
// "" for an error that is not the environment's.
std::string sqlite_environment_cause(const std::string& file, int code, int system_errno);

class Statement;

// What a refusal of a damaged database file says it expected (SQLite's reason, shortened).
std::string damaged_database_expectation(const std::string& sqlite_says);

// One connection, used by one thread at a time (opened without SQLite's internal mutex).
class Database {
 public:
  enum class Mode { read_only, read_write_create };
  Database(const std::filesystem::path& file, Mode mode);
  ~Database();
  Database(const Database&) = delete;
  Database& operator=(const Database&) = delete;

  static constexpr int kBusyTimeoutMs = 5000;  // how long a statement waits for another process's lock
  void exec(std::string_view sql);             // one or more statements, no results
  void exec_waiting(std::string_view sql);     // exec, retrying SQLITE_BUSY for up to kBusyTimeoutMs
  Statement prepare(std::string_view sql);
  std::int64_t pragma_integer(std::string_view name);  // e.g. "user_version"
  std::int64_t last_insert_rowid() const noexcept;
  // Throws InputError naming the file unless PRAGMA quick_check finds it sound. A writer checks
  // at every open; a reader skips a file state an earlier reader found sound
  // (store/integrity_check_cache.hpp). Says which it did.
  enum class Check { checked, known_sound };
  Check refuse_if_damaged();
  // A reader opened `immutable` (store/sqlite_read_access.hpp) reads without SQLite's locks:
  // throws SqliteError naming the file when the database file changed since it was opened.
  // Called when a statement finishes; nothing for other connections.
  void refuse_if_changed_during_read() const;
  Mode mode() const noexcept { return mode_; }
  bool immutable() const noexcept { return immutable_; }
  const std::string& file() const noexcept { return file_; }
  sqlite3* handle() noexcept { return db_; }

  [[noreturn]] void fail(const std::string& what, int code) const;

 private:
  int open(int flags);  // sqlite3_open_v2 into db_ (closing any earlier handle); its result code
  void open_for_reading();
  void open_for_writing();
  [[noreturn]] void fail_open(int rc);  // closes the half-open handle, throws the line naming the file

  sqlite3* db_ = nullptr;
  std::string file_;
  Mode mode_;
  bool immutable_ = false;
  bool tidy_sidecars_ = false;    // remove the -wal/-shm this reader's connection made (on close)
  std::string identity_at_open_;  // immutable readers: the file's identity when opened
};

class Statement {
 public:
  Statement(Database& db, std::string_view sql);
  ~Statement();
  Statement(Statement&& other) noexcept;
  Statement(const Statement&) = delete;
  Statement& operator=(const Statement&) = delete;
  Statement& operator=(Statement&&) = delete;

  // Parameters are 1-based, as in SQL's ?1, ?2, ...
  Statement& bind(int index, std::int64_t value);
  Statement& bind(int index, int value) { return bind(index, static_cast<std::int64_t>(value)); }
  Statement& bind(int index, double value);
  Statement& bind(int index, std::string_view value);
  Statement& bind(int index, const char* value) { return bind(index, std::string_view(value)); }
  Statement& bind(int index, const std::string& value) { return bind(index, std::string_view(value)); }
  Statement& bind_null(int index);
  template <class T>
  Statement& bind(int index, const std::optional<T>& value) {
    return value ? bind(index, *value) : bind_null(index);
  }

  bool step();   // true while a row is available
  void run();    // step once, expect no row (INSERT/UPDATE)
  void reset();  // for reuse: clears the bindings too

  bool is_null(int column) const noexcept;
  std::int64_t integer(int column) const noexcept;
  double real(int column) const noexcept;
  std::string text(int column) const;
  std::string_view text_view(int column) const noexcept;  // valid until the next step

 private:
  Database* db_;
  sqlite3_stmt* stmt_ = nullptr;
};

// BEGIN IMMEDIATE on construction (the write lock is taken at once, so a busy database fails
// here rather than mid-way); ROLLBACK in the destructor unless commit() ran.
class Transaction {
 public:
  explicit Transaction(Database& db);
  ~Transaction();
  Transaction(const Transaction&) = delete;
  Transaction& operator=(const Transaction&) = delete;
  void commit();

 private:
  Database& db_;
  bool done_ = false;
};

}  // namespace palprig
