#include "store/postgres_session_rows.hpp"

#include "core/input_error.hpp"
#include "store/postgres_schema.hpp"
#include "store/training_rows.hpp"

#include <algorithm>
#include <functional>
#include <map>
#include <variant>

namespace palprig {

namespace {

PgParam param_of(const SqlValue& v) {
  if (const auto* i = std::get_if<std::int64_t>(&v)) return pg_text(*i);
  if (const auto* d = std::get_if<double>(&v)) return pg_text(*d);
  if (const auto* t = std::get_if<std::string>(&v)) return *t;
  return std::nullopt;
}

SqlValue pg_read_value(const PgResult& r, int row, int column, char type) {
  if (r.is_null(row, column)) return std::monostate{};
  switch (type) {
    case 'i': return r.integer(row, column);
    case 'r': return r.real(row, column);
    default: return r.text(row, column);
  }
}

template <std::size_t N>
SqlRow pg_read_row(const PgResult& r, int row, int first_column, const std::array<SqlColumn, N>& columns) {
  SqlRow out;
  out.reserve(N);
  for (std::size_t i = 0; i < N; ++i)
    out.push_back(pg_read_value(r, row, first_column + static_cast<int>(i), columns[i].type));
  return out;
}

template <std::size_t N>
std::string pg_placeholders(std::size_t first) {
  std::string s;
  for (std::size_t i = 0; i < N; ++i) s += (i ? ", $" : "$") + std::to_string(first + i);
  return s;
}

// Rows per INSERT: one statement carries many rows (a round trip per trial made `store copy`
// of a million trials take 18 minutes); 1000 trials of 24 parameters stay far below the
// protocol's 65535 parameters.
constexpr std::size_t kRowsPerInsert = 1000;

// Inserts `rows` (each `width` parameters, after the `shared` ones every row repeats) with
// statements "<head> VALUES (<shared>, row 1), (<shared>, row 2), ... <tail>", at most
// kRowsPerInsert rows each; `on_result` sees each statement's result (RETURNING rows).
void insert_many(PgConnection& db, const std::string& head, const std::string& tail, const std::vector<PgParam>& shared,
                 std::size_t width, const std::vector<PgParam>& rows,
                 const std::function<void(const PgResult&)>& on_result = {}) {
  const std::size_t count = width == 0 ? 0 : rows.size() / width;
  std::vector<PgParam> params;
  std::string sql;
  for (std::size_t first = 0; first < count; first += kRowsPerInsert) {
    const std::size_t n = std::min(kRowsPerInsert, count - first);
    params.assign(shared.begin(), shared.end());
    params.insert(params.end(), rows.begin() + static_cast<std::ptrdiff_t>(first * width),
                  rows.begin() + static_cast<std::ptrdiff_t>((first + n) * width));
    sql = head + " VALUES ";
    std::size_t next = shared.size() + 1;
    for (std::size_t r = 0; r < n; ++r) {
      sql += r ? ", (" : "(";
      for (std::size_t i = 0; i < shared.size() + width; ++i) {
        if (i) sql += ", ";
        sql += '$';
        sql += std::to_string(i < shared.size() ? i + 1 : next++);
      }
      sql += ')';
    }
    sql += tail;
    const PgResult result = db.exec(sql, params);
    if (on_result) on_result(result);
  }
}

void append_params(std::vector<PgParam>& to, const SqlRow& row) {
  for (const SqlValue& v : row) to.push_back(param_of(v));
}

}  // namespace

std::int64_t pg_participant_id(PgConnection& db, const std::string& code, bool simulated,
                               const std::string& created_utc, int* number) {
  // Numbers are the enrolment order across every rig: one enrolment at a time.
  db.exec("LOCK TABLE participants IN SHARE ROW EXCLUSIVE MODE");
  PgResult found = db.exec("SELECT id, number FROM participants WHERE code = $1", {code});
  if (found.rows() == 0) {
    found = db.exec(
        "INSERT INTO participants (code, number, simulated, created_utc) "
        "VALUES ($1, (SELECT COALESCE(MAX(number), 0) + 1 FROM participants), $2, $3) RETURNING id, number",
        {code, std::string(simulated ? "1" : "0"), created_utc});
  }
  if (number) *number = static_cast<int>(found.integer(0, 1));
  return found.integer(0, 0);
}

std::int64_t pg_push_session(PgConnection& db, const SessionRows& in, bool* added) {
  if (added) *added = false;
  PgResult known = db.exec("SELECT id FROM sessions WHERE session_uid = $1", {in.session_uid});
  std::int64_t id = 0;
  if (known.rows() > 0) {
    id = known.integer(0, 0);
  } else {
    const std::int64_t participant =
        pg_participant_id(db, in.participant_code, in.simulated, in.participant_created_utc);
    std::vector<PgParam> params{pg_text(participant), in.session_uid, in.host_name, in.origin};
    for (const SqlValue& v : in.session) params.push_back(param_of(v));
    // ON CONFLICT: another process pushing the same session at the same moment.
    PgResult ins =
        db.exec("INSERT INTO sessions (participant_id, session_uid, host_name, origin, " +
                    column_list(kSessionColumns) + ") VALUES ($1, $2, $3, $4, " +
                    pg_placeholders<kSessionColumns.size()>(5) + ") ON CONFLICT (session_uid) DO NOTHING RETURNING id",
                params);
    if (ins.rows() == 0) {
      id = db.exec("SELECT id FROM sessions WHERE session_uid = $1", {in.session_uid}).integer(0, 0);
    } else {
      id = ins.integer(0, 0);
      if (added) *added = true;
      std::vector<PgParam> planned;
      for (const SqlRow& row : in.planned) append_params(planned, row);
      insert_many(db, "INSERT INTO planned_trials (session_id, " + column_list(kPlannedColumns) + ")",
                  " ON CONFLICT DO NOTHING", {pg_text(id)}, kPlannedColumns.size(), planned);
    }
  }
  if (in.text(kSessionStatus) == "completed") {
    db.exec("UPDATE sessions SET status = 'completed', finished_utc = $2 WHERE id = $1 AND status <> 'completed'",
            {pg_text(id), param_of(in.session[kSessionFinishedUtc])});
  }
  if (in.training) pg_write_training_row(db, id, *in.training, false);
  return id;
}

int pg_push_trials(PgConnection& db, std::int64_t session_id, std::span<const TrialRows> trials) {
  // Trials first; those the server already has are skipped (ON CONFLICT: pushing twice stores
  // once) and only the added ones come back, with their ids, for their scores and marks.
  // A server older than the later columns (writers migrate it first; a push straight onto one,
  // as an older palprig's server, is only ever made by tests) takes the columns it has: the
  // times it has no column for are left out (they read as unknown), a confidence rating is
  // refused (an answer would be lost).
  const std::size_t column_count = pg_trial_column_count(pg_schema_version(db));
  std::string columns;
  for (std::size_t i = 0; i < column_count; ++i) columns += (i ? ", " : "") + std::string(kTrialColumns[i].name);
  std::vector<PgParam> rows;
  rows.reserve(trials.size() * column_count);
  std::map<std::int64_t, const TrialRows*> by_position;
  for (const TrialRows& t : trials) {
    if (column_count <= kTrialConfidence && !std::holds_alternative<std::monostate>(t.trial.at(kTrialConfidence))) {
      throw InputError(db.target().describe(), "palprig_schema.version",
                       "schema version " + std::to_string(kPgSchemaRatingColumnsFrom) +
                           " or newer for trials with a confidence rating (open it for writing to migrate)");
    }
    append_params(rows, SqlRow(t.trial.begin(), t.trial.begin() + static_cast<std::ptrdiff_t>(column_count)));
    by_position[t.position()] = &t;
  }
  std::vector<PgParam> scores, marks;
  int added = 0;
  insert_many(db, "INSERT INTO trials (session_id, " + columns + ")",
              " ON CONFLICT (session_id, position) DO NOTHING RETURNING id, position", {pg_text(session_id)},
              column_count, rows, [&](const PgResult& r) {
                for (int i = 0; i < r.rows(); ++i) {
                  ++added;
                  const TrialRows& t = *by_position.at(r.integer(i, 1));
                  const std::string trial_id = r.text(i, 0);
                  for (const SqlRow& row : t.tumor_scores) {
                    scores.push_back(trial_id);
                    append_params(scores, row);
                  }
                  for (const SqlRow& row : t.marks) {
                    marks.push_back(trial_id);
                    append_params(marks, row);
                  }
                }
              });
  insert_many(db, "INSERT INTO tumor_scores (trial_id, " + column_list(kTumorScoreColumns) + ")", "", {},
              kTumorScoreColumns.size() + 1, scores);
  insert_many(db, "INSERT INTO marks (trial_id, " + column_list(kMarkColumns) + ")", "", {}, kMarkColumns.size() + 1,
              marks);
  return added;
}

namespace {

std::vector<ServerSession> read_sessions_where(PgConnection& db, const std::string& where,
                                               const std::vector<PgParam>& params) {
  const bool training = pg_has_training_tables(db);
  const PgResult r =
      db.exec("SELECT s.id, p.code, p.simulated, p.created_utc, s.session_uid, s.host_name, s.origin, " +
                  column_list(kSessionColumns, "s.") +
                  " FROM sessions s JOIN participants p ON p.id = s.participant_id " + where + " ORDER BY s.id",
              params);
  std::vector<ServerSession> sessions;
  for (int i = 0; i < r.rows(); ++i) {
    ServerSession s;
    s.id = r.integer(i, 0);
    s.rows.participant_code = r.text(i, 1);
    s.rows.simulated = r.integer(i, 2) != 0;
    s.rows.participant_created_utc = r.text(i, 3);
    s.rows.session_uid = r.text(i, 4);
    s.rows.host_name = r.text(i, 5);
    s.rows.origin = r.text(i, 6);
    s.rows.session = pg_read_row(r, i, 7, kSessionColumns);
    const PgResult p = db.exec(
        "SELECT " + column_list(kPlannedColumns) + " FROM planned_trials WHERE session_id = $1 ORDER BY position",
        {pg_text(s.id)});
    for (int j = 0; j < p.rows(); ++j) s.rows.planned.push_back(pg_read_row(p, j, 0, kPlannedColumns));
    if (training) s.rows.training = pg_read_training_row(db, s.id);
    sessions.push_back(std::move(s));
  }
  return sessions;
}

}  // namespace

std::vector<ServerSession> pg_read_sessions(PgConnection& db, const std::optional<std::string>& study) {
  if (!study) return read_sessions_where(db, "", {});
  return read_sessions_where(db, "WHERE s.protocol_name = $1", {*study});
}

std::optional<ServerSession> pg_read_session(PgConnection& db, std::int64_t session_id) {
  auto found = read_sessions_where(db, "WHERE s.id = $1", {pg_text(session_id)});
  if (found.empty()) return std::nullopt;
  return std::move(found.front());
}

std::vector<TrialRows> pg_read_trials(PgConnection& db, std::int64_t session_id, std::int64_t from_position) {
  const PgResult r = db.exec("SELECT id, " + trial_select_list(pg_trial_column_count(pg_schema_version(db))) +
                                 " FROM trials WHERE session_id = $1 AND position >= $2 ORDER BY position",
                             {pg_text(session_id), pg_text(from_position)});
  std::vector<TrialRows> trials;
  std::map<std::int64_t, std::size_t> index;
  for (int i = 0; i < r.rows(); ++i) {
    index[r.integer(i, 0)] = trials.size();
    trials.push_back(TrialRows{pg_read_row(r, i, 1, kTrialColumns), {}, {}});
  }
  const std::vector<PgParam> p{pg_text(session_id), pg_text(from_position)};
  const PgResult ts =
      db.exec("SELECT ts.trial_id, " + column_list(kTumorScoreColumns, "ts.") +
                  " FROM tumor_scores ts JOIN trials t ON t.id = ts.trial_id "
                  "WHERE t.session_id = $1 AND t.position >= $2 ORDER BY ts.trial_id, ts.tumor COLLATE \"C\"",
              p);
  for (int i = 0; i < ts.rows(); ++i) {
    trials[index.at(ts.integer(i, 0))].tumor_scores.push_back(pg_read_row(ts, i, 1, kTumorScoreColumns));
  }
  const PgResult mk = db.exec("SELECT m.trial_id, " + column_list(kMarkColumns, "m.") +
                                  " FROM marks m JOIN trials t ON t.id = m.trial_id "
                                  "WHERE t.session_id = $1 AND t.position >= $2 ORDER BY m.trial_id, m.mark",
                              p);
  for (int i = 0; i < mk.rows(); ++i)
    trials[index.at(mk.integer(i, 0))].marks.push_back(pg_read_row(mk, i, 1, kMarkColumns));
  return trials;
}

bool pg_has_training_tables(PgConnection& db) {
  return !db.exec("SELECT to_regclass('training_sessions')").is_null(0, 0);
}

std::optional<SqlRow> pg_read_training_row(PgConnection& db, std::int64_t session_id) {
  const PgResult r =
      db.exec("SELECT " + column_list(kTrainingColumns) + " FROM training_sessions WHERE session_id = $1",
              {pg_text(session_id)});
  if (r.rows() == 0) return std::nullopt;
  return pg_read_row(r, 0, 0, kTrainingColumns);
}

void pg_write_training_row(PgConnection& db, std::int64_t session_id, const SqlRow& row, bool refuse_repeats) {
  const std::string trainee = std::get<std::string>(row.at(0));
  for (const std::string& key : training_row_cases(row)) {
    // The server's primary key keeps one session per (trainee, case), whichever rig asks.
    const PgResult given = db.exec(
        "INSERT INTO training_cases (trainee, case_key, session_id) VALUES ($1, $2, $3) "
        "ON CONFLICT (trainee, case_key) DO UPDATE SET session_id = training_cases.session_id RETURNING session_id",
        {trainee, key, pg_text(session_id)});
    const std::int64_t holder = given.integer(0, 0);
    if (holder != session_id && refuse_repeats) {
      throw InputError(db.target().describe(), "training_cases", case_not_given_before(trainee, key, holder));
    }
  }
  std::vector<PgParam> params{pg_text(session_id)};
  append_params(params, row);
  db.exec("INSERT INTO training_sessions (session_id, " + column_list(kTrainingColumns) + ") VALUES ($1, " +
              pg_placeholders<kTrainingColumns.size()>(2) +
              ") ON CONFLICT (session_id) DO UPDATE SET status = excluded.status, scores = excluded.scores, "
              "met_benchmark = excluded.met_benchmark, finished_utc = excluded.finished_utc "
              "WHERE training_sessions.status <> 'completed'",
          params);
}

std::vector<SqlRow> pg_read_trainees(PgConnection& db) {
  std::vector<SqlRow> rows;
  if (!pg_has_training_tables(db)) return rows;
  const PgResult r =
      db.exec("SELECT " + column_list(kTraineeColumns) + " FROM trainees ORDER BY code COLLATE \"C\", curriculum");
  for (int i = 0; i < r.rows(); ++i) rows.push_back(pg_read_row(r, i, 0, kTraineeColumns));
  return rows;
}

void pg_write_trainees(PgConnection& db, const std::vector<SqlRow>& rows) {
  std::vector<PgParam> params;
  for (const SqlRow& row : rows) append_params(params, row);
  insert_many(db, "INSERT INTO trainees (" + column_list(kTraineeColumns) + ")", " ON CONFLICT DO NOTHING", {},
              kTraineeColumns.size(), params);
}

}  // namespace palprig
