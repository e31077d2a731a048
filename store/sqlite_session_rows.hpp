#pragma once
// Sessions of an SQLite trial file as store-neutral rows (store/session_rows.hpp), and back.
//
// The file's table lab_store_sessions links a local session to its global identity
// (session_uid) and, in a journal, to the lab server it is pushed to. A session without a
// row there (a plain file) gets an identity derived from what makes it unique in its file, so
// copying the same file twice stores it once.
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "store/session_rows.hpp"
#include "store/sqlite_db.hpp"

namespace palprig {

void ensure_lab_sessions_table(Database& db);
bool has_lab_sessions_table(Database& db);
// How many of kTrialColumns (store/session_rows.hpp) the file's `trials` has: all of them once
// migrated; fewer in an older file opened for reading (the later columns read as NULL).
std::size_t sqlite_trial_column_count(Database& db);

struct LocalSession {
  std::int64_t id = 0;  // in the file
  SessionRows rows;     // without trials
};

// Sessions of the file (of one study, i.e. protocol name, when given; only those `wanted`
// accepts, when given), by id.
std::vector<LocalSession> read_sqlite_sessions(Database& db, const std::optional<std::string>& study,
                                               const std::function<bool(std::int64_t)>& wanted = {});
// Trials of a local session at positions >= from_position, by position.
std::vector<TrialRows> read_sqlite_trials(Database& db, std::int64_t session_id, std::int64_t from_position);

// Training (schema 5): the tables exist (an older file read as it is has none).
bool has_training_tables(Database& db);
// The session's training_sessions row (kTrainingColumns), if it is a trainee's.
std::optional<SqlRow> read_sqlite_training_row(Database& db, std::int64_t session_id);
// Inside a transaction: the session's training row added, or brought forward (running to
// completed, never back), and its cases reserved for the trainee in training_cases. A case the
// trainee was given in another session is refused (InputError naming it) when `refuse_repeats`
// (a new session), else kept as it is (a copy or push of history that already happened).
void write_sqlite_training_row(Database& db, std::int64_t session_id, const SqlRow& row, bool refuse_repeats);
// trainees rows (kTraineeColumns); written inside a transaction, those already there kept.
std::vector<SqlRow> read_sqlite_trainees(Database& db);
void write_sqlite_trainees(Database& db, const std::vector<SqlRow>& rows);

struct SqliteWriteResult {
  std::int64_t session_id = 0;
  bool session_added = false;
  int trials_added = 0;
};
// Writes a session (found by its session_uid, or added) and those of its trials not there yet,
// in one transaction.
SqliteWriteResult write_sqlite_session(Database& db, const SessionRows& session);

}  // namespace palprig
