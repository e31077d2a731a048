#include "store/postgres_trial_store.hpp"

#include <unistd.h>

#include <chrono>
#include <cmath>
#include <ctime>
#include <map>
#include <random>

#include "study/scoring.hpp"
#include "core/input_error.hpp"
#include "store/postgres_schema.hpp"
#include "store/postgres_session_rows.hpp"
#include "store/host_identity.hpp"
#include "store/trial_rows.hpp"
#include "store/utc_time.hpp"

namespace palprig {

namespace {

SqlValue finite_or_sql_null(double x) {
  if (std::isfinite(x)) return x;
  return std::monostate{};
}

// One row of a result as the decoders of store/trial_rows.hpp read it.
struct PgRow {
  const PgResult& r;
  int row;
  bool is_null(int c) const noexcept { return r.is_null(row, c); }
  std::int64_t integer(int c) const { return r.integer(row, c); }
  double real(int c) const { return r.real(row, c); }
  std::string_view text_view(int c) const noexcept { return r.text_view(row, c); }
};

// Streams the rows of a query in batches through a cursor, inside one read-only snapshot, so
// a million trials are never in memory at once. `binary`: the rows come in binary format
// (the scans for `stats trials`, whose columns are read only through integer/real/text_view).
template <class RowFn>
void stream_rows(PgConnection& db, const std::string& sql, RowFn on_row, bool binary = false) {
  PgTransaction tx(db, "BEGIN ISOLATION LEVEL REPEATABLE READ READ ONLY");
  db.exec("DECLARE palprig_scan NO SCROLL CURSOR FOR " + sql);
  for (;;) {
    const std::string fetch = "FETCH FORWARD 50000 FROM palprig_scan";
    const PgResult batch = binary ? db.exec_binary(fetch) : db.exec(fetch);
    if (batch.rows() == 0) break;
    for (int i = 0; i < batch.rows(); ++i) on_row(batch, i);
  }
  db.exec("CLOSE palprig_scan");
  tx.commit();
}

}  // namespace

std::string new_session_uid() {
  std::random_device device;
  const std::uint64_t bits = (static_cast<std::uint64_t>(device()) << 32) ^ device();
  char hex[17];
  std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(bits));
  return this_host_name() + "/" + utc_now_text() + "/" + hex;
}

TrialRows trial_rows_of(const TrialRecord& r) {
  const bool discrimination = r.mode != PresentationMode::scene;
  TrialRows rows;
  SqlRow& t = rows.trial;
  t.assign(kTrialColumns.size(), std::monostate{});
  t[0] = std::int64_t{r.planned.position};
  t[1] = std::int64_t{r.planned.block};
  t[2] = r.condition;
  t[3] = std::string(to_string(r.mode));
  t[4] = std::int64_t{r.planned.practice ? 1 : 0};
  t[5] = std::int64_t{r.planned.combination};
  t[11] = std::int64_t{r.answered ? 1 : 0};
  t[14] = r.onset_s;
  t[22] = utc_now_text();
  t[kTrialStimulusEnd] = finite_or_sql_null(r.stimulus_end_s);
  t[kTrialStimulusReached] = finite_or_sql_null(r.stimulus_reached_s);
  if (r.answered && r.confidence) t[kTrialConfidence] = std::int64_t{*r.confidence};
  if (!discrimination && !r.case_name.empty()) {  // a case named by the runner (not a hand-made record)
    t[kTrialCaseName] = r.case_name;
    if (r.case_seed) t[kTrialCaseSeed] = static_cast<std::int64_t>(*r.case_seed);
    if (r.case_difficulty) t[kTrialCaseDifficulty] = std::string(to_string(*r.case_difficulty));
    t[kTrialCaseTumors] = std::int64_t{r.case_tumors};
  }
  if (discrimination) {
    t[6] = r.combination_label;
    for (std::size_t f = 0; f < kFingerCount; ++f) t[7 + f] = r.stimulus_kPa[f];
    t[10] = trial_rows::flags_text(r.truth);
  }
  for (std::size_t f = 0; f < kFingerCount; ++f) t[15 + f] = finite_or_sql_null(r.felt_kPa[f]);
  if (r.answered) {
    t[13] = r.response_time_s;
    if (discrimination) {
      t[12] = trial_rows::flags_text(r.answer);
      for (std::size_t f = 0; f < kFingerCount; ++f) t[18 + f] = std::string(to_string(r.finger_outcomes[f]));
    } else {
      t[21] = std::int64_t{r.localisation.false_marks};
    }
  }
  if (!discrimination && r.answered) {
    for (const TumorScore& score : r.localisation.tumors) {
      rows.tumor_scores.push_back(SqlRow{score.tumor, std::string(score.hit ? "TP" : "FN"),
                                         score.nearest_mark_mm >= 0 ? SqlValue(score.nearest_mark_mm) : SqlValue()});
    }
    for (std::size_t i = 0; i < r.marks.size(); ++i) {
      const int hit = i < r.localisation.mark_tumor.size() ? r.localisation.mark_tumor[i] : -1;
      rows.marks.push_back(
          SqlRow{static_cast<std::int64_t>(i), r.marks[i].x_mm, r.marks[i].y_mm,
                 hit >= 0 ? SqlValue(r.localisation.tumors[static_cast<std::size_t>(hit)].tumor) : SqlValue()});
    }
  }
  return rows;
}

PostgresTrialStore::PostgresTrialStore(const PgTarget& target, Access access, int connect_timeout_s) try
    : db_(target, connect_timeout_s), location_(target.conninfo) {
  if (access == Access::read_write)
    ensure_pg_schema(db_);
  else
    check_pg_schema(db_);
  trial_columns_ = pg_trial_column_count(pg_schema_version(db_));
} catch (const PgError& e) {
  // Nothing moves on the rig before the store is known to be writable: a server that cannot
  // be reached or refuses the login is a refused input (exit 2), named with libpq's reason.
  if (e.connection_lost()) {
    throw InputError(target.describe(), "connection", "a reachable PostgreSQL server (libpq: " + e.reason() + ")");
  }
  throw InputError(target.describe(), "palprig_schema",
                   "a database where palprig may create and read its tables (server: " + e.reason() + ")");
}

std::optional<ParticipantRecord> PostgresTrialStore::find_participant(const std::string& code) {
  const PgResult r = db_.exec("SELECT id, code, number, simulated FROM participants WHERE code = $1", {code});
  if (r.rows() == 0) return std::nullopt;
  return ParticipantRecord{r.integer(0, 0), r.text(0, 1), static_cast<int>(r.integer(0, 2)), r.integer(0, 3) != 0};
}

ParticipantRecord PostgresTrialStore::enrol(const std::string& code, bool simulated) {
  if (auto p = find_participant(code)) return *p;
  PgTransaction tx(db_);
  int number = 0;
  const std::int64_t id = pg_participant_id(db_, code, simulated, utc_now_text(), &number);
  tx.commit();
  return find_participant(code).value_or(ParticipantRecord{id, code, number, simulated});
}

std::optional<std::int64_t> PostgresTrialStore::find_unfinished_session(const ParticipantRecord& who,
                                                                        const std::string& protocol_name) {
  const PgResult r = db_.exec(
      "SELECT id FROM sessions WHERE participant_id = $1 AND protocol_name = $2 AND status = 'running' "
      "ORDER BY id DESC LIMIT 1",
      {pg_text(who.id), protocol_name});
  if (r.rows() == 0) return std::nullopt;
  return r.integer(0, 0);
}

std::int64_t PostgresTrialStore::create_session(const ParticipantRecord& who, const Protocol& protocol,
                                                const SessionPlan& plan, const SessionSetup& setup) {
  SessionRows s;
  s.session_uid = new_session_uid();
  s.host_name = this_host_name();
  s.origin = "palprig";
  s.participant_code = who.code;
  s.simulated = who.simulated;
  s.participant_created_utc = utc_now_text();
  s.session = SqlRow{protocol.name,
                     std::string(to_string(protocol.task)),
                     protocol.bids_task,
                     protocol.snapshot.dump(),
                     setup.protocol_dir,
                     static_cast<std::int64_t>(plan.seed),  // stored as the same 64 bits
                     nlohmann::json(plan.condition_order).dump(),
                     setup.rig_id,
                     setup.rig_backend,
                     setup.calibration,
                     setup.participant_model.is_null() ? SqlValue() : SqlValue(setup.participant_model.dump()),
                     std::string("running"),
                     utc_now_text(),
                     SqlValue()};
  for (const PlannedTrial& t : plan.trials) {
    s.planned.push_back(SqlRow{std::int64_t{t.position}, std::int64_t{t.block}, std::int64_t{t.condition},
                               protocol.conditions.at(static_cast<std::size_t>(t.condition)).name,
                               std::int64_t{t.practice ? 1 : 0}, std::int64_t{t.combination},
                               std::int64_t{t.break_after ? 1 : 0}});
  }
  PgTransaction tx(db_);
  // The participant's row locked for this transaction: another process may have started this
  // participant's session since the caller looked for an unfinished one (the same participant
  // started on two benches at once); the second waits here and then finds the first's session.
  db_.exec("SELECT id FROM participants WHERE id = $1 FOR UPDATE", {pg_text(who.id)});
  const PgResult running = db_.exec(
      "SELECT id FROM sessions WHERE participant_id = $1 AND protocol_name = $2 AND status = 'running' "
      "ORDER BY id DESC LIMIT 1",
      {pg_text(who.id), protocol.name});
  const std::string name = "participant '" + who.code + "'";
  if (running.rows() > 0) {
    const std::int64_t other = running.integer(0, 0);
    refuse_if_held_elsewhere(other, name);
    throw InputError(location_, name,
                     "already has an unfinished session with protocol '" + protocol.name + "' (session " +
                         std::to_string(other) + "); to continue it, run the same command again with --resume");
  }
  const std::int64_t id = pg_push_session(db_, s);
  take_lock(id, name);  // the new session is claimed
  try {
    tx.commit();
  } catch (...) {
    drop_lock(id);
    throw;
  }
  return id;
}

std::string PostgresTrialStore::session_uid(std::int64_t session_id) {
  const PgResult r = db_.exec("SELECT session_uid FROM sessions WHERE id = $1", {pg_text(session_id)});
  if (r.rows() == 0) throw InputError(location_, "session " + std::to_string(session_id), "an existing session");
  return r.text(0, 0);
}

StoredSession PostgresTrialStore::load_session(std::int64_t session_id) {
  StoredSession s;
  const PgResult q = db_.exec(
      "SELECT s.id, s.protocol_json, s.protocol_dir, s.status, s.seed, s.condition_order, p.id, p.code, p.number, "
      "p.simulated FROM sessions s JOIN participants p ON p.id = s.participant_id WHERE s.id = $1",
      {pg_text(session_id)});
  if (q.rows() == 0) throw InputError(location_, "session " + std::to_string(session_id), "an existing session");
  s.id = q.integer(0, 0);
  s.protocol_snapshot = nlohmann::json::parse(q.text(0, 1));
  s.protocol_dir = q.text(0, 2);
  s.status = q.text(0, 3);
  s.plan.seed = static_cast<std::uint64_t>(q.integer(0, 4));
  s.plan.condition_order = nlohmann::json::parse(q.text(0, 5)).get<std::vector<int>>();
  s.participant =
      ParticipantRecord{q.integer(0, 6), q.text(0, 7), static_cast<int>(q.integer(0, 8)), q.integer(0, 9) != 0};
  s.plan.participant_number = s.participant.number;
  const PgResult t = db_.exec(
      "SELECT position, block, condition_index, practice, combination, break_after FROM planned_trials "
      "WHERE session_id = $1 ORDER BY position",
      {pg_text(session_id)});
  for (int i = 0; i < t.rows(); ++i) {
    s.plan.trials.push_back(PlannedTrial{static_cast<int>(t.integer(i, 0)), static_cast<int>(t.integer(i, 1)),
                                         static_cast<int>(t.integer(i, 2)), t.integer(i, 3) != 0,
                                         static_cast<int>(t.integer(i, 4)), t.integer(i, 5) != 0});
  }
  const PgResult done =
      db_.exec("SELECT count(*), COALESCE(MAX(position), -1) FROM trials WHERE session_id = $1", {pg_text(session_id)});
  s.completed_trials = static_cast<int>(done.integer(0, 0));
  if (done.integer(0, 1) != s.completed_trials - 1) {
    throw InputError(location_, "session " + std::to_string(session_id),
                     "trials committed in order (positions are missing on the server: push the journal with "
                     "palprig store sync)");
  }
  return s;
}

void PostgresTrialStore::complete_session(std::int64_t session_id) {
  db_.exec("UPDATE sessions SET status = 'completed', finished_utc = $2 WHERE id = $1",
           {pg_text(session_id), utc_now_text()});
  release_session(session_id);
}

void PostgresTrialStore::commit_trial(std::int64_t session_id, const TrialRecord& trial) {
  const TrialRows rows = trial_rows_of(trial);
  PgTransaction tx(db_);
  pg_push_trials(db_, session_id, std::span<const TrialRows>(&rows, 1));
  tx.commit();
}

void PostgresTrialStore::commit_trials(std::int64_t session_id, std::span<const TrialRecord> trials) {
  std::vector<TrialRows> rows;
  rows.reserve(trials.size());
  for (const TrialRecord& t : trials) rows.push_back(trial_rows_of(t));
  PgTransaction tx(db_);
  pg_push_trials(db_, session_id, rows);
  tx.commit();
}

std::vector<SessionOverview> PostgresTrialStore::list_sessions() {
  const PgResult q = db_.exec(
      "SELECT s.id, p.id, p.code, p.number, p.simulated, s.protocol_name, s.task, s.bids_task, s.status "
      "FROM sessions s JOIN participants p ON p.id = s.participant_id ORDER BY s.id");
  std::vector<SessionOverview> sessions;
  sessions.reserve(static_cast<std::size_t>(q.rows()));
  for (int i = 0; i < q.rows(); ++i) {
    sessions.push_back(SessionOverview{
        q.integer(i, 0),
        ParticipantRecord{q.integer(i, 1), q.text(i, 2), static_cast<int>(q.integer(i, 3)), q.integer(i, 4) != 0},
        q.text(i, 5), q.text(i, 6), q.text(i, 7), q.text(i, 8)});
  }
  return sessions;
}

nlohmann::json PostgresTrialStore::protocol_snapshot(std::int64_t session_id) {
  const PgResult q = db_.exec("SELECT protocol_json FROM sessions WHERE id = $1", {pg_text(session_id)});
  if (q.rows() == 0) throw InputError(location_, "session " + std::to_string(session_id), "an existing session");
  return nlohmann::json::parse(q.text_view(0, 0), nullptr, false);
}

std::string PostgresTrialStore::later_columns() const {
  // An older server read as it is: the columns it lacks read as NULL.
  return trial_select_list(trial_columns_, "t.", kTrialColumnsBeforeRating, true);
}

void PostgresTrialStore::scan_scored_trials(TrialFamily family, bool include_practice,
                                            const std::function<void(const ScoredTrial&)>& visit) {
  using namespace trial_rows;
  if (family == TrialFamily::discrimination) {
    ScoredTrial t;
    // ORDER BY id: commit order, as the SQLite store's rowid scan (response-time means then add
    // up in the same order, to the last bit).
    stream_rows(
        db_,
        std::string("SELECT ") + kScoredDiscriminationColumns + later_columns() +
            " FROM trials t WHERE t.mode != 'scene'" + practice_filter(include_practice, "AND") + " ORDER BY t.id",
        [&](const PgResult& q, int i) {
          decode_scored_discrimination(PgRow{q, i}, t);
          visit(t);
        },
        true);
    return;
  }
  // Localisation: one row per (trial, tumor score), gathered per trial.
  LocalisationGatherer gather(visit);
  stream_rows(
      db_,
      std::string("SELECT ") + kScoredLocalisationColumns + later_columns() +
          " FROM trials t LEFT JOIN tumor_scores ts ON ts.trial_id = t.id WHERE t.mode = 'scene'" +
          practice_filter(include_practice, "AND") + " ORDER BY t.id, ts.tumor COLLATE \"C\"",
      [&](const PgResult& q, int i) {
        gather.add(PgRow{q, i});
      },
      true);
  gather.finish();
}

std::vector<StoredTrial> PostgresTrialStore::read_trials(bool include_practice) {
  return read_trials_where(trial_rows::practice_filter(include_practice, "WHERE"));
}

std::vector<StoredTrial> PostgresTrialStore::read_session_trials(std::int64_t session_id) {
  return read_trials_where(" WHERE s.id = " + std::to_string(session_id));
}

int PostgresTrialStore::next_participant_number() {
  const PgResult r = db_.exec("SELECT COALESCE(MAX(number), 0) + 1 FROM participants");
  return static_cast<int>(r.integer(0, 0));
}

std::vector<StoredTrial> PostgresTrialStore::read_trials_where(const std::string& where) {
  using namespace trial_rows;
  std::vector<StoredTrial> trials;
  std::map<std::int64_t, std::size_t> scene_trials;  // trial id -> index, for scores and marks
  stream_rows(
      db_,
      std::string("SELECT ") + kStoredTrialColumns + later_columns() +
          " FROM trials t JOIN sessions s ON s.id = t.session_id JOIN participants p ON p.id = s.participant_id" +
          where + " ORDER BY p.number, s.id, t.position",
      [&](const PgResult& q, int i) {
        StoredTrial t = decode_stored_trial(PgRow{q, i});
        if (t.mode == "scene") scene_trials[t.id] = trials.size();
        trials.push_back(std::move(t));
      });
  if (scene_trials.empty()) return trials;
  stream_rows(db_, "SELECT trial_id, tumor, outcome FROM tumor_scores ORDER BY trial_id, tumor COLLATE \"C\"",
              [&](const PgResult& q, int i) {
                const auto it = scene_trials.find(q.integer(i, 0));
                if (it != scene_trials.end())
                  trials[it->second].tumor_outcomes.push_back(decode_tumor_outcome(PgRow{q, i}, 1));
              });
  stream_rows(db_, "SELECT trial_id, mark, x_mm, y_mm, tumor FROM marks ORDER BY trial_id, mark",
              [&](const PgResult& q, int i) {
                const auto it = scene_trials.find(q.integer(i, 0));
                if (it == scene_trials.end()) return;
                trials[it->second].marks.push_back(decode_mark(PgRow{q, i}, 1));
              });
  return trials;
}

}  // namespace palprig
