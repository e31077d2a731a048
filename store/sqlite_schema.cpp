#include "store/sqlite_trial_store.hpp"

// The SQLite store's schema: creation of a blank file, identity checks, and migration of older
// files in one transaction (the PostgreSQL side's is store/postgres_schema.cpp).
#include <sqlite3.h>

#include <string>

#include "core/input_error.hpp"

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
  stimulus_reached_s REAL,                     -- when it reached the fingers (half the level; onset_s's clock)
  case_name         TEXT,                      -- localisation: the case palpated
  case_seed         INTEGER,                   -- a generated case's seed
  case_difficulty   TEXT,                      -- a generated case's difficulty
  case_tumors       INTEGER,                   -- tumors in the case (0: a normal case)
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
)sql"
                                R"sql(
CREATE TABLE trainees (                        -- a trainee enrolled in a curriculum
  code         TEXT NOT NULL,                  -- the participant code they train under
  curriculum   TEXT NOT NULL,                  -- the curriculum's name
  enrolled_utc TEXT NOT NULL,
  PRIMARY KEY (code, curriculum)
) WITHOUT ROWID;
CREATE TABLE training_sessions (               -- a trainee's session at a level
  session_id    INTEGER PRIMARY KEY REFERENCES sessions(id),
  trainee       TEXT NOT NULL,
  curriculum    TEXT NOT NULL,
  level         INTEGER NOT NULL,              -- 0-based, in the curriculum's order
  level_name    TEXT NOT NULL,
  cases         TEXT NOT NULL,                 -- JSON array of case keys
  status        TEXT NOT NULL CHECK (status IN ('running', 'completed')),
  scores        TEXT,                          -- JSON: the session's measures, once completed
  met_benchmark INTEGER CHECK (met_benchmark IN (0, 1)),
  started_utc   TEXT NOT NULL,
  finished_utc  TEXT
);
CREATE TABLE training_cases (                  -- never the same case twice for one trainee
  trainee    TEXT NOT NULL,
  case_key   TEXT NOT NULL,
  session_id INTEGER NOT NULL REFERENCES sessions(id),
  PRIMARY KEY (trainee, case_key)
) WITHOUT ROWID;
)sql";

// Schema 1 -> 2: the confidence rating and the stimulus end (appended, as in kSchema).
constexpr const char* kMigrationTo2 = R"sql(
ALTER TABLE trials ADD COLUMN confidence INTEGER CHECK (confidence BETWEEN 1 AND 9);
ALTER TABLE trials ADD COLUMN stimulus_end_s REAL;
PRAGMA user_version = 2;
)sql";

// Schema 3: threshold trials no longer carry every track's state (it grew with each trial; the
// tracks are replayed from the trial rows, study/threshold_record.hpp). Every trial is kept.
void migrate_to_3(Database& db) {
  auto column = db.prepare("SELECT count(*) FROM pragma_table_info('threshold_trials') WHERE name = 'state'");
  column.step();
  if (column.integer(0) > 0) db.exec("ALTER TABLE threshold_trials DROP COLUMN state");
  db.exec("PRAGMA user_version = 3");
}

// Schema 4: when the stimulus reached the fingers (appended, as in kSchema); every trial kept,
// NULL for those stored before (their monitor crossings were not recorded).
void migrate_to_4(Database& db) {
  auto column = db.prepare("SELECT count(*) FROM pragma_table_info('trials') WHERE name = 'stimulus_reached_s'");
  column.step();
  if (column.integer(0) == 0) db.exec("ALTER TABLE trials ADD COLUMN stimulus_reached_s REAL");
  db.exec("PRAGMA user_version = 4");
}

// Schema 5: the localisation case of each trial (appended, as in kSchema; NULL for the trials
// stored before: they palpated their session's one scene) and the training tables.
void migrate_to_5(Database& db) {
  auto column = db.prepare("SELECT count(*) FROM pragma_table_info('trials') WHERE name = ?1");
  for (const char* spec : {"case_name TEXT", "case_seed INTEGER", "case_difficulty TEXT", "case_tumors INTEGER"}) {
    const std::string name = std::string(spec).substr(0, std::string(spec).find(' '));
    column.bind(1, name);
    column.step();
    const bool present = column.integer(0) > 0;
    column.reset();
    if (!present) db.exec(std::string("ALTER TABLE trials ADD COLUMN ") + spec);
  }
  // The training tables as a new file has them (a file that already has them, e.g. set back to an
  // older version number by hand, keeps them).
  std::string tables = std::string(kSchema).substr(std::string(kSchema).find("CREATE TABLE trainees"));
  for (std::size_t at = tables.find("CREATE TABLE "); at != std::string::npos;
       at = tables.find("CREATE TABLE ", at + 1))
    tables.replace(at, 13, "CREATE TABLE IF NOT EXISTS ");
  db.exec(tables);
  db.exec("PRAGMA user_version = 5");
}

}  // namespace

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
  const std::int64_t version = db_.pragma_integer("user_version");
  if (version >= kTrialStoreSchemaVersion) return;
  std::string step = "trials and training tables (schema 4 -> 5 migration)";
  try {
    if (version < 2) {
      step = "trials (schema 1 -> 2 migration)";
      db_.exec(kMigrationTo2);
    }
    if (version < 3) {
      step = "threshold_trials (schema 2 -> 3 migration)";
      migrate_to_3(db_);
    }
    if (version < 4) {
      step = "trials (schema 3 -> 4 migration)";
      migrate_to_4(db_);
    }
    step = "trials and training tables (schema 4 -> 5 migration)";
    migrate_to_5(db_);
  } catch (const SqliteError& e) {
    // Busy: another writer; try again later (not the file's fault). Anything else: the file's
    // tables are not what the older schema says (hand-edited, or a foreign tool): refused, unchanged.
    const int primary = e.code() & 0xff;
    if (primary == SQLITE_BUSY || primary == SQLITE_LOCKED) throw;
    throw InputError(db_.file(), step,
                     std::string("a schema-") + std::to_string(version) +
                         " trial database palprig can migrate (SQLite: " + e.what() + "); the file was not changed");
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

}  // namespace palprig
