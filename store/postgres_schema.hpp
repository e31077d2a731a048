#pragma once
// The lab store's schema on PostgreSQL: the SQLite store's tables (participants, sessions,
// planned_trials, trials, tumor_scores, marks; same columns, so the same SQL reads both) plus
// what a shared store needs: each session's globally unique id (session_uid, the key pushes and
// copies are idempotent on), the host it ran on and where it came from, and the table
// palprig_schema recording every schema version applied.
//
// Created on first use and migrated forward, under an advisory lock so rigs starting at the same
// moment do not race. A schema newer than this program is refused with one line.
#include <cstddef>
#include <cstdint>

#include "store/pg_connection.hpp"

namespace palprig {

// 1: the trial store's tables; 2: session_locks; 3: trials.confidence, trials.stimulus_end_s;
// 4: palprig_store (the store's own id); 5: trials.stimulus_reached_s; 6: the trials' case
// columns and the training tables (trainees, training_sessions, training_cases).
inline constexpr int kPgSchemaVersion = 6;
// The first version whose trials have the rating columns; older servers read them as NULL.
inline constexpr int kPgSchemaRatingColumnsFrom = 3;
// The first version whose trials have stimulus_reached_s; older servers read it as NULL.
inline constexpr int kPgSchemaReachedColumnFrom = 5;
// The first version with the trials' case columns and the training tables.
inline constexpr int kPgSchemaCaseColumnsFrom = 6;
// How many of kTrialColumns (store/session_rows.hpp) a server of this schema version has.
std::size_t pg_trial_column_count(int schema_version) noexcept;
// Readers (stats, export, copy from) need only the tables of version 1: an older lab server is
// read as it is, without writing to it.
inline constexpr int kPgSchemaReadableFrom = 1;
// pg_advisory_xact_lock key taken while the schema is checked, created or migrated.
inline constexpr std::int64_t kPgSchemaLockKey = 0x50616C50;  // "PalP", as the SQLite application_id

// The schema version found (0: a database palprig has not used yet).
int pg_schema_version(PgConnection& db);

// Read-write: creates or migrates the schema up to `target_version` (tests build an older
// server with a smaller one), all steps in one transaction. Throws InputError (location = the
// target's description) for a newer schema or a database whose tables palprig did not create.
void ensure_pg_schema(PgConnection& db, int target_version = kPgSchemaVersion);

// Which store this connection reaches, as the bench journal remembers it: PostgreSQL's system
// identifier of the cluster (pg_control_system(); "?" where the role may not read it) and the
// id palprig_store keeps in the database (schema 4; "?" on an older one). Host, port and
// database name are no identity: a fresh server at the same address is another store.
std::string pg_store_identity(PgConnection& db);

// Read-only: refuses a database without palprig's schema, or with a newer one; reads one as old
// as kPgSchemaReadableFrom as it is.
void check_pg_schema(PgConnection& db);

}  // namespace palprig
