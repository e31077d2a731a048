#pragma once
// Sessions on the lab server as store-neutral rows (store/session_rows.hpp), and back. Every
// write is idempotent: a session is found by its session_uid, a trial by (session, position),
// so pushing the same rows twice stores them once. The caller holds the transaction.
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "store/pg_connection.hpp"
#include "store/session_rows.hpp"

namespace palprig {

// The participant of this code (enrolled with the next number when new); needs a transaction.
std::int64_t pg_participant_id(PgConnection& db, const std::string& code, bool simulated,
                               const std::string& created_utc, int* number = nullptr);

// Finds or adds the session and its planned order; marks it completed when the rows say so.
// Returns its id on the server and whether it was added.
std::int64_t pg_push_session(PgConnection& db, const SessionRows& session, bool* added = nullptr);

// Adds the trials not there yet; returns how many were added.
int pg_push_trials(PgConnection& db, std::int64_t session_id, std::span<const TrialRows> trials);

// Sessions on the server (of one study when given), without trials, by id.
struct ServerSession {
  std::int64_t id = 0;
  SessionRows rows;
};
std::vector<ServerSession> pg_read_sessions(PgConnection& db, const std::optional<std::string>& study);
std::optional<ServerSession> pg_read_session(PgConnection& db, std::int64_t session_id);
std::vector<TrialRows> pg_read_trials(PgConnection& db, std::int64_t session_id, std::int64_t from_position);

// Training (schema 6; an older server read as it is has none): as the SQLite file's
// (store/sqlite_session_rows.hpp). The caller holds the transaction for the writes.
bool pg_has_training_tables(PgConnection& db);
std::optional<SqlRow> pg_read_training_row(PgConnection& db, std::int64_t session_id);
void pg_write_training_row(PgConnection& db, std::int64_t session_id, const SqlRow& row, bool refuse_repeats);
std::vector<SqlRow> pg_read_trainees(PgConnection& db);
void pg_write_trainees(PgConnection& db, const std::vector<SqlRow>& rows);

}  // namespace palprig
