#include "store/threshold_store.hpp"

#include <cmath>
#include <limits>

#include "core/input_error.hpp"
#include "store/utc_time.hpp"

namespace palprig {

namespace {

constexpr const char* kThresholdSchema = R"sql(
CREATE TABLE IF NOT EXISTS threshold_trials (
  session_id        INTEGER NOT NULL REFERENCES sessions(id),
  position          INTEGER NOT NULL,
  track             INTEGER NOT NULL,
  track_name        TEXT NOT NULL,
  fingers           TEXT NOT NULL CHECK (fingers IN ('one', 'three')),
  level_kPa         REAL NOT NULL,                -- the increment over the reference
  reference_kPa     REAL NOT NULL,
  signal_interval   INTEGER NOT NULL,             -- 0 or 1
  answered          INTEGER NOT NULL CHECK (answered IN (0, 1)),
  response          INTEGER,                      -- 2afc: interval 0/1; yes-no: 1 yes, 0 no
  correct           INTEGER,                      -- 1/0; NULL when not answered
  reversal          INTEGER NOT NULL,
  response_time_s   REAL,
  onset_s           REAL NOT NULL,
  felt1_kPa         REAL, felt2_kPa REAL,         -- mean pressure on the active fingers per interval
  completed_utc     TEXT NOT NULL,
  PRIMARY KEY (session_id, position)
) WITHOUT ROWID;
)sql";

}  // namespace

ThresholdStore::ThresholdStore(SqliteTrialStore& store, bool writable) : store_(store) {
  if (writable) store_.database().exec(kThresholdSchema);
}

bool ThresholdStore::has_table() {
  auto q = store_.database().prepare("SELECT count(*) FROM sqlite_master WHERE name = 'threshold_trials'");
  q.step();
  return q.integer(0) > 0;
}

std::int64_t ThresholdStore::create_session(const ParticipantRecord& who, const ThresholdProtocol& protocol,
                                            std::uint64_t seed, const SessionSetup& setup) {
  return store_.create_task_session(who, {"threshold", protocol.name, protocol.bids_task, protocol.snapshot, seed},
                                    setup);
}

StoredThresholdSession ThresholdStore::load_session(std::int64_t session_id) {
  StoredThresholdSession s;
  static_cast<StoredTaskSession&>(s) = store_.load_task_session(session_id, "threshold", "threshold_trials");
  if (s.completed_trials > 0) {
    for (ThresholdTrialRow& row : trials(session_id)) s.trials.push_back(std::move(row.trial));
  }
  return s;
}

void ThresholdStore::commit_trial(std::int64_t session_id, const ThresholdTrialRecord& r) {
  Database& db = store_.database();
  Transaction tx(db);
  auto ins = db.prepare(
      "INSERT INTO threshold_trials (session_id, position, track, track_name, fingers, level_kPa, reference_kPa, "
      "signal_interval, answered, response, correct, reversal, response_time_s, onset_s, felt1_kPa, felt2_kPa, "
      "completed_utc) VALUES (?1, ?2, ?3, ?4, ?5, ?6, ?7, ?8, ?9, ?10, ?11, ?12, ?13, ?14, ?15, ?16, ?17)");
  ins.bind(1, session_id)
      .bind(2, r.position)
      .bind(3, r.track)
      .bind(4, r.track_name)
      .bind(5, r.fingers)
      .bind(6, r.level_kPa)
      .bind(7, r.reference_kPa)
      .bind(8, r.signal_interval)
      .bind(9, r.answered ? 1 : 0)
      .bind(12, r.reversal ? 1 : 0)
      .bind(14, r.onset_s)
      .bind(17, utc_now_text());
  if (r.answered) {
    ins.bind(10, r.response).bind(11, r.correct ? 1 : 0).bind(13, r.response_time_s);
  }
  for (int i = 0; i < 2; ++i) {
    const double f = r.felt_kPa[static_cast<std::size_t>(i)];
    if (std::isfinite(f)) ins.bind(15 + i, f);
  }
  ins.run();
  tx.commit();
}

std::vector<ThresholdTrialRow> ThresholdStore::trials(std::optional<std::int64_t> session_id) {
  std::vector<ThresholdTrialRow> rows;
  if (!has_table()) return rows;
  auto q = store_.database().prepare(
      "SELECT t.session_id, p.code, t.position, t.track, t.track_name, t.fingers, t.level_kPa, t.reference_kPa, "
      "t.signal_interval, t.answered, t.response, t.correct, t.reversal, t.response_time_s, t.onset_s, t.felt1_kPa, "
      "t.felt2_kPa FROM threshold_trials t JOIN sessions s ON s.id = t.session_id JOIN participants p ON "
      "p.id = s.participant_id WHERE ?1 IS NULL OR t.session_id = ?1 ORDER BY t.session_id, t.position");
  if (session_id)
    q.bind(1, *session_id);
  else
    q.bind_null(1);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  while (q.step()) {
    ThresholdTrialRow row;
    row.session_id = q.integer(0);
    row.participant = q.text(1);
    ThresholdTrialRecord& r = row.trial;
    r.position = static_cast<int>(q.integer(2));
    r.track = static_cast<int>(q.integer(3));
    r.track_name = q.text(4);
    r.fingers = q.text(5);
    r.level_kPa = q.real(6);
    r.reference_kPa = q.real(7);
    r.signal_interval = static_cast<int>(q.integer(8));
    r.answered = q.integer(9) != 0;
    r.response = q.is_null(10) ? -1 : static_cast<int>(q.integer(10));
    r.correct = !q.is_null(11) && q.integer(11) != 0;
    r.reversal = q.integer(12) != 0;
    r.response_time_s = q.is_null(13) ? nan : q.real(13);
    r.onset_s = q.real(14);
    r.felt_kPa = {q.is_null(15) ? nan : q.real(15), q.is_null(16) ? nan : q.real(16)};
    rows.push_back(std::move(row));
  }
  return rows;
}

}  // namespace palprig
