#include "store/sqlite_session_rows.hpp"

#include <sqlite3.h>

#include "core/input_error.hpp"
#include "store/training_rows.hpp"

namespace palprig {

namespace {

SqlValue read_value(const Statement& s, int column, char type) {
  if (s.is_null(column)) return std::monostate{};
  switch (type) {
    case 'i': return s.integer(column);
    case 'r': return s.real(column);
    default: return s.text(column);
  }
}

template <std::size_t N>
SqlRow read_row(const Statement& s, int first_column, const std::array<SqlColumn, N>& columns) {
  SqlRow row;
  row.reserve(N);
  for (std::size_t i = 0; i < N; ++i) row.push_back(read_value(s, first_column + static_cast<int>(i), columns[i].type));
  return row;
}

void bind_value(Statement& s, int index, const SqlValue& v) {
  if (const auto* i = std::get_if<std::int64_t>(&v))
    s.bind(index, *i);
  else if (const auto* d = std::get_if<double>(&v))
    s.bind(index, *d);
  else if (const auto* t = std::get_if<std::string>(&v))
    s.bind(index, *t);
  else
    s.bind_null(index);
}

template <std::size_t N>
std::string placeholders(std::size_t first) {
  std::string s;
  for (std::size_t i = 0; i < N; ++i) s += (i ? ", ?" : "?") + std::to_string(first + i);
  return s;
}

std::string text_of(const SqlValue& v) {
  if (const auto* i = std::get_if<std::int64_t>(&v)) return std::to_string(*i);
  if (const auto* t = std::get_if<std::string>(&v)) return *t;
  return "";
}

}  // namespace

void ensure_lab_sessions_table(Database& db) {
  db.exec(
      "CREATE TABLE IF NOT EXISTS lab_store_sessions ("
      "  session_id        INTEGER PRIMARY KEY REFERENCES sessions(id),"
      "  session_uid       TEXT NOT NULL UNIQUE,"  // the session's identity on every store
      "  host_name         TEXT NOT NULL,"
      "  server            TEXT,"                       // journal: the server it is pushed to (host port database)
      "  server_uri        TEXT,"                       // journal: the URI (holds no password)
      "  server_session_id INTEGER,"                    // journal: its id there
      "  synced            INTEGER NOT NULL DEFAULT 0"  // journal: every trial and the end are on the server
      ")");
}

std::size_t sqlite_trial_column_count(Database& db) {
  // The later columns were appended in kTrialColumns' order: the file has those up to the first
  // one missing.
  auto s = db.prepare("SELECT count(*) FROM pragma_table_info('trials') WHERE name = ?1");
  for (std::size_t i = kTrialColumnsBeforeRating; i < kTrialColumns.size(); ++i) {
    s.bind(1, std::string(kTrialColumns[i].name));
    s.step();
    const bool present = s.integer(0) > 0;
    s.reset();
    if (!present) return i;
  }
  return kTrialColumns.size();
}

bool has_lab_sessions_table(Database& db) {
  auto s = db.prepare("SELECT count(*) FROM sqlite_master WHERE type = 'table' AND name = 'lab_store_sessions'");
  s.step();
  return s.integer(0) > 0;
}

std::vector<LocalSession> read_sqlite_sessions(Database& db, const std::optional<std::string>& study,
                                               const std::function<bool(std::int64_t)>& wanted) {
  const bool lab = has_lab_sessions_table(db);
  const bool training = has_training_tables(db);
  const std::string sql = "SELECT s.id, p.code, p.simulated, p.created_utc, " +
                          std::string(lab ? "l.session_uid, l.host_name" : "NULL, NULL") + ", " +
                          column_list(kSessionColumns, "s.") +
                          " FROM sessions s JOIN participants p ON p.id = s.participant_id " +
                          (lab ? "LEFT JOIN lab_store_sessions l ON l.session_id = s.id " : "") +
                          (study ? "WHERE s.protocol_name = ?1 " : "") + "ORDER BY s.id";
  auto q = db.prepare(sql);
  if (study) q.bind(1, *study);
  std::vector<LocalSession> sessions;
  while (q.step()) {
    if (wanted && !wanted(q.integer(0))) continue;
    LocalSession s;
    s.id = q.integer(0);
    s.rows.participant_code = q.text(1);
    s.rows.simulated = q.integer(2) != 0;
    s.rows.participant_created_utc = q.text(3);
    s.rows.session = read_row(q, 6, kSessionColumns);
    if (!q.is_null(4)) {
      s.rows.session_uid = q.text(4);
      s.rows.host_name = q.text(5);
    } else {
      // A plain file's session: unique within the file by its id, recognisable by what it is.
      s.rows.session_uid = "sqlite-session:" + s.rows.text(kSessionStartedUtc) + "/" + s.rows.participant_code + "/" +
                           s.rows.text(kSessionProtocolName) + "/" + text_of(s.rows.session[kSessionSeed]) + "/" +
                           std::to_string(s.id);
    }
    s.rows.origin = "copy:" + db.file();
    auto p = db.prepare("SELECT " + column_list(kPlannedColumns) +
                        " FROM planned_trials WHERE session_id = ?1 ORDER BY position");
    p.bind(1, s.id);
    while (p.step()) s.rows.planned.push_back(read_row(p, 0, kPlannedColumns));
    if (training) s.rows.training = read_sqlite_training_row(db, s.id);
    sessions.push_back(std::move(s));
  }
  return sessions;
}

std::vector<TrialRows> read_sqlite_trials(Database& db, std::int64_t session_id, std::int64_t from_position) {
  std::vector<TrialRows> trials;
  std::vector<std::int64_t> ids;
  auto q = db.prepare("SELECT id, " + trial_select_list(sqlite_trial_column_count(db)) +
                      " FROM trials WHERE session_id = ?1 AND position >= ?2 ORDER BY position");
  q.bind(1, session_id).bind(2, from_position);
  while (q.step()) {
    ids.push_back(q.integer(0));
    trials.push_back(TrialRows{read_row(q, 1, kTrialColumns), {}, {}});
  }
  auto ts =
      db.prepare("SELECT " + column_list(kTumorScoreColumns) + " FROM tumor_scores WHERE trial_id = ?1 ORDER BY tumor");
  auto mk = db.prepare("SELECT " + column_list(kMarkColumns) + " FROM marks WHERE trial_id = ?1 ORDER BY mark");
  for (std::size_t i = 0; i < trials.size(); ++i) {
    ts.bind(1, ids[i]);
    while (ts.step()) trials[i].tumor_scores.push_back(read_row(ts, 0, kTumorScoreColumns));
    ts.reset();
    mk.bind(1, ids[i]);
    while (mk.step()) trials[i].marks.push_back(read_row(mk, 0, kMarkColumns));
    mk.reset();
  }
  return trials;
}

SqliteWriteResult write_sqlite_session(Database& db, const SessionRows& in) {
  ensure_lab_sessions_table(db);
  SqliteWriteResult result;
  Transaction tx(db);
  auto known = db.prepare("SELECT session_id FROM lab_store_sessions WHERE session_uid = ?1");
  known.bind(1, in.session_uid);
  if (known.step()) {
    result.session_id = known.integer(0);
  } else {
    std::int64_t participant = 0;
    auto find = db.prepare("SELECT id FROM participants WHERE code = ?1");
    find.bind(1, in.participant_code);
    if (find.step()) {
      participant = find.integer(0);
    } else {
      auto ins = db.prepare(
          "INSERT INTO participants (code, number, simulated, created_utc) "
          "VALUES (?1, (SELECT COALESCE(MAX(number), 0) + 1 FROM participants), ?2, ?3)");
      ins.bind(1, in.participant_code).bind(2, in.simulated ? 1 : 0).bind(3, in.participant_created_utc).run();
      participant = db.last_insert_rowid();
    }
    auto ins = db.prepare("INSERT INTO sessions (participant_id, " + column_list(kSessionColumns) + ") VALUES (?1, " +
                          placeholders<kSessionColumns.size()>(2) + ")");
    ins.bind(1, participant);
    for (std::size_t i = 0; i < kSessionColumns.size(); ++i) bind_value(ins, static_cast<int>(i + 2), in.session[i]);
    ins.run();
    result.session_id = db.last_insert_rowid();
    result.session_added = true;
    auto lab = db.prepare("INSERT INTO lab_store_sessions (session_id, session_uid, host_name) VALUES (?1, ?2, ?3)");
    lab.bind(1, result.session_id).bind(2, in.session_uid).bind(3, in.host_name).run();
    auto planned = db.prepare("INSERT INTO planned_trials (session_id, " + column_list(kPlannedColumns) +
                              ") VALUES (?1, " + placeholders<kPlannedColumns.size()>(2) + ")");
    for (const SqlRow& row : in.planned) {
      planned.bind(1, result.session_id);
      for (std::size_t i = 0; i < row.size(); ++i) bind_value(planned, static_cast<int>(i + 2), row[i]);
      planned.run();
    }
  }
  // A session completed in the source is completed here too (never the other way round).
  if (in.text(kSessionStatus) == "completed") {
    auto done = db.prepare(
        "UPDATE sessions SET status = 'completed', finished_utc = ?2 WHERE id = ?1 AND status != 'completed'");
    done.bind(1, result.session_id);
    bind_value(done, 2, in.session[kSessionFinishedUtc]);
    done.run();
  }
  auto trial = db.prepare("INSERT OR IGNORE INTO trials (session_id, " + column_list(kTrialColumns) + ") VALUES (?1, " +
                          placeholders<kTrialColumns.size()>(2) + ")");
  auto ts = db.prepare("INSERT INTO tumor_scores (trial_id, " + column_list(kTumorScoreColumns) + ") VALUES (?1, " +
                       placeholders<kTumorScoreColumns.size()>(2) + ")");
  auto mk = db.prepare("INSERT INTO marks (trial_id, " + column_list(kMarkColumns) + ") VALUES (?1, " +
                       placeholders<kMarkColumns.size()>(2) + ")");
  for (const TrialRows& t : in.trials) {
    trial.bind(1, result.session_id);
    for (std::size_t i = 0; i < t.trial.size(); ++i) bind_value(trial, static_cast<int>(i + 2), t.trial[i]);
    trial.run();
    if (sqlite3_changes(db.handle()) == 0) continue;  // already there: idempotent
    const std::int64_t trial_id = db.last_insert_rowid();
    ++result.trials_added;
    for (const SqlRow& row : t.tumor_scores) {
      ts.bind(1, trial_id);
      for (std::size_t i = 0; i < row.size(); ++i) bind_value(ts, static_cast<int>(i + 2), row[i]);
      ts.run();
    }
    for (const SqlRow& row : t.marks) {
      mk.bind(1, trial_id);
      for (std::size_t i = 0; i < row.size(); ++i) bind_value(mk, static_cast<int>(i + 2), row[i]);
      mk.run();
    }
  }
  if (in.training) write_sqlite_training_row(db, result.session_id, *in.training, false);
  tx.commit();
  return result;
}

bool has_training_tables(Database& db) {
  auto s = db.prepare("SELECT count(*) FROM sqlite_master WHERE type = 'table' AND name = 'training_sessions'");
  s.step();
  return s.integer(0) > 0;
}

std::optional<SqlRow> read_sqlite_training_row(Database& db, std::int64_t session_id) {
  auto q = db.prepare("SELECT " + column_list(kTrainingColumns) + " FROM training_sessions WHERE session_id = ?1");
  q.bind(1, session_id);
  if (!q.step()) return std::nullopt;
  return read_row(q, 0, kTrainingColumns);
}

void write_sqlite_training_row(Database& db, std::int64_t session_id, const SqlRow& row, bool refuse_repeats) {
  const std::string trainee = text_of(row.at(0));
  auto given = db.prepare("SELECT session_id FROM training_cases WHERE trainee = ?1 AND case_key = ?2");
  auto reserve = db.prepare("INSERT OR IGNORE INTO training_cases (trainee, case_key, session_id) VALUES (?1, ?2, ?3)");
  for (const std::string& key : training_row_cases(row)) {
    given.bind(1, trainee).bind(2, key);
    const bool before = given.step() && given.integer(0) != session_id;
    const std::int64_t other = before ? given.integer(0) : 0;
    given.reset();
    if (before && refuse_repeats) {
      throw InputError(db.file(), "training_cases", case_not_given_before(trainee, key, other));
    }
    reserve.bind(1, trainee).bind(2, key).bind(3, session_id).run();
  }
  // Added, or brought forward: a completed row replaces a running one, never the other way.
  auto upsert =
      db.prepare("INSERT INTO training_sessions (session_id, " + column_list(kTrainingColumns) + ") VALUES (?1, " +
                 placeholders<kTrainingColumns.size()>(2) +
                 ") ON CONFLICT (session_id) DO UPDATE SET status = excluded.status, scores = excluded.scores, "
                 "met_benchmark = excluded.met_benchmark, finished_utc = excluded.finished_utc "
                 "WHERE training_sessions.status <> 'completed'");
  upsert.bind(1, session_id);
  for (std::size_t i = 0; i < row.size(); ++i) bind_value(upsert, static_cast<int>(i + 2), row[i]);
  upsert.run();
}

std::vector<SqlRow> read_sqlite_trainees(Database& db) {
  std::vector<SqlRow> rows;
  if (!has_training_tables(db)) return rows;
  auto q = db.prepare("SELECT " + column_list(kTraineeColumns) + " FROM trainees ORDER BY code, curriculum");
  while (q.step()) rows.push_back(read_row(q, 0, kTraineeColumns));
  return rows;
}

void write_sqlite_trainees(Database& db, const std::vector<SqlRow>& rows) {
  auto ins = db.prepare("INSERT OR IGNORE INTO trainees (" + column_list(kTraineeColumns) + ") VALUES (" +
                        placeholders<kTraineeColumns.size()>(1) + ")");
  for (const SqlRow& row : rows) {
    for (std::size_t i = 0; i < row.size(); ++i) bind_value(ins, static_cast<int>(i + 1), row[i]);
    ins.run();
  }
}

}  // namespace palprig
