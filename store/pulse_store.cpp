#include "store/pulse_store.hpp"

#include <cmath>
#include <cstdio>
#include <limits>
#include <map>

#include "core/input_error.hpp"
#include "statistics/statistics_describe.hpp"
#include "statistics/statistics_proportion.hpp"
#include "store/utc_time.hpp"

namespace palprig {

namespace {

constexpr const char* kPulseSchema = R"sql(
CREATE TABLE IF NOT EXISTS pulse_trials (
  session_id      INTEGER NOT NULL REFERENCES sessions(id),
  position        INTEGER NOT NULL,
  condition       TEXT NOT NULL,
  scene_seed      INTEGER,              -- generated conditions: the case's seed
  answered        INTEGER NOT NULL CHECK (answered IN (0, 1)),
  mark_x_mm       REAL, mark_y_mm REAL,
  artery          TEXT,                 -- the artery scored against
  distance_mm     REAL,                 -- mark to its centreline; NULL when not answered
  hit             INTEGER NOT NULL CHECK (hit IN (0, 1)),
  response_time_s REAL,
  onset_s         REAL NOT NULL,
  completed_utc   TEXT NOT NULL,
  PRIMARY KEY (session_id, position)
) WITHOUT ROWID;
)sql";

}  // namespace

PulseStore::PulseStore(SqliteTrialStore& store, bool writable) : store_(store) {
  if (writable) store_.database().exec(kPulseSchema);
}

std::int64_t PulseStore::create_session(const ParticipantRecord& who, const PulseProtocol& protocol, std::uint64_t seed,
                                        const SessionSetup& setup) {
  return store_.create_task_session(who,
                                    {"pulse", protocol.name, protocol.bids_task, protocol.snapshot, seed,
                                     nlohmann::json(pulse_trial_order(protocol, seed))},
                                    setup);
}

StoredPulseSession PulseStore::load_session(std::int64_t session_id) {
  return store_.load_task_session(session_id, "pulse", "pulse_trials");
}

void PulseStore::commit_trial(std::int64_t session_id, const PulseTrialRecord& r) {
  Database& db = store_.database();
  Transaction tx(db);
  auto ins = db.prepare(
      "INSERT INTO pulse_trials (session_id, position, condition, answered, mark_x_mm, mark_y_mm, artery, distance_mm, "
      "hit, response_time_s, onset_s, completed_utc, scene_seed) VALUES (?1, ?2, ?3, ?4, ?5, ?6, ?7, ?8, ?9, ?10, ?11, "
      "?12, ?13)");
  ins.bind(1, session_id).bind(2, r.position).bind(3, r.condition).bind(4, r.answered ? 1 : 0).bind(9, r.hit ? 1 : 0);
  ins.bind(11, r.onset_s).bind(12, utc_now_text());
  if (r.scene_seed) ins.bind(13, static_cast<std::int64_t>(*r.scene_seed));
  if (r.answered) {
    ins.bind(5, r.mark_x_mm).bind(6, r.mark_y_mm).bind(7, r.artery).bind(8, r.distance_mm).bind(10, r.response_time_s);
  }
  ins.run();
  tx.commit();
}

bool PulseStore::has_trials() {
  auto t = store_.database().prepare("SELECT count(*) FROM sqlite_master WHERE name = 'pulse_trials'");
  t.step();
  if (t.integer(0) == 0) return false;
  auto q = store_.database().prepare("SELECT count(*) FROM pulse_trials");
  q.step();
  return q.integer(0) > 0;
}

std::vector<PulseTrialRecord> PulseStore::read_trials(std::int64_t session_id) {
  std::vector<PulseTrialRecord> out;
  if (!has_trials()) return out;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  auto q = store_.database().prepare(
      "SELECT position, condition, scene_seed, answered, mark_x_mm, mark_y_mm, artery, distance_mm, hit, "
      "response_time_s, onset_s FROM pulse_trials WHERE session_id = ?1 ORDER BY position");
  q.bind(1, session_id);
  while (q.step()) {
    PulseTrialRecord r;
    r.position = static_cast<int>(q.integer(0));
    r.condition = q.text(1);
    if (!q.is_null(2)) r.scene_seed = static_cast<std::uint64_t>(q.integer(2));
    r.answered = q.integer(3) != 0;
    r.mark_x_mm = q.is_null(4) ? 0.0 : q.real(4);
    r.mark_y_mm = q.is_null(5) ? 0.0 : q.real(5);
    r.artery = q.is_null(6) ? std::string() : q.text(6);
    r.distance_mm = q.is_null(7) ? nan : q.real(7);
    r.hit = q.integer(8) != 0;
    r.response_time_s = q.is_null(9) ? nan : q.real(9);
    r.onset_s = q.real(10);
    out.push_back(std::move(r));
  }
  return out;
}

std::vector<PulseConditionSummary> PulseStore::summarise(double confidence) {
  std::vector<PulseConditionSummary> out;
  if (!has_trials()) return out;
  std::map<std::string, std::vector<double>> distances;
  std::map<std::string, PulseConditionSummary> by;
  std::vector<std::string> order;
  auto q = store_.database().prepare(
      "SELECT condition, answered, hit, distance_mm FROM pulse_trials ORDER BY session_id, position");
  while (q.step()) {
    const std::string c = q.text(0);
    if (!by.count(c)) order.push_back(c);
    auto& s = by[c];
    s.condition = c;
    ++s.trials;
    if (q.integer(1) != 0) {
      ++s.answered;
      distances[c].push_back(q.real(3));
    }
    s.hits += q.integer(2) != 0 ? 1 : 0;
  }
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (const auto& c : order) {
    PulseConditionSummary s = by[c];
    const auto w = stats::wilson_interval(s.hits, s.trials, confidence);
    s.hit_rate = w.p;
    s.hit_low = w.lower;
    s.hit_high = w.upper;
    s.distance_mean_mm = s.distance_median_mm = s.distance_q1_mm = s.distance_q3_mm = s.distance_iqr_mm = nan;
    if (!distances[c].empty()) {
      const auto d = stats::describe(distances[c]);
      s.distance_mean_mm = d.mean;
      s.distance_median_mm = d.median;
      s.distance_q1_mm = d.q1;
      s.distance_q3_mm = d.q3;
      s.distance_iqr_mm = d.iqr;
    }
    out.push_back(s);
  }
  return out;
}

nlohmann::ordered_json pulse_summary_json(const std::vector<PulseConditionSummary>& rows, double confidence) {
  nlohmann::ordered_json j;
  j["task"] = "pulse";
  j["convention"] =
      "hit rate = hits / trials (unanswered trials count as misses), Wilson interval without continuity "
      "correction; distance from the mark to the artery centreline over answered trials, quartiles R type 7";
  j["confidence"] = confidence;
  j["conditions"] = nlohmann::ordered_json::array();
  for (const auto& r : rows) {
    j["conditions"].push_back({{"condition", r.condition},
                               {"trials", r.trials},
                               {"answered", r.answered},
                               {"hits", r.hits},
                               {"hit_rate", r.hit_rate},
                               {"hit_rate_low", r.hit_low},
                               {"hit_rate_high", r.hit_high},
                               {"distance_mean_mm", r.distance_mean_mm},
                               {"distance_median_mm", r.distance_median_mm},
                               {"distance_q1_mm", r.distance_q1_mm},
                               {"distance_q3_mm", r.distance_q3_mm},
                               {"distance_iqr_mm", r.distance_iqr_mm}});
  }
  return j;
}

std::string pulse_summary_table(const std::vector<PulseConditionSummary>& rows, double confidence) {
  std::string out = "Pulse localisation (hit rate with " +
                    std::to_string(static_cast<int>(std::round(confidence * 100))) +
                    " % Wilson interval; distance to the artery centreline)\n";
  char line[256];
  std::snprintf(line, sizeof line, "  %-16s %6s %6s %22s %10s %12s %10s\n", "condition", "trials", "hits",
                "hit rate [CI]", "mean mm", "median mm", "IQR mm");
  out += line;
  for (const auto& r : rows) {
    std::snprintf(line, sizeof line, "  %-16s %6d %6d %6.3f [%.3f, %.3f] %10.2f %12.2f %10.2f\n", r.condition.c_str(),
                  r.trials, r.hits, r.hit_rate, r.hit_low, r.hit_high, r.distance_mean_mm, r.distance_median_mm,
                  r.distance_iqr_mm);
    out += line;
  }
  return out;
}

}  // namespace palprig
