// The trial store's confidence and stimulus_end_s columns (schema 2): a round trip, and an
// SQLite file made by the schema-1 DDL (what an older palprig wrote) read as it is and then
// migrated, keeping every trial and its statistics.
#include <gtest/gtest.h>
#include <sqlite3.h>

#include <cmath>

#include "core/input_error.hpp"
#include "store/sqlite_trial_store.hpp"
#include "store/trial_summary.hpp"
#include "store/trial_summary_report.hpp"
#include "tests/support/support.hpp"

namespace palprig {
namespace {

using testing::ScratchDir;

// Schema 1, verbatim from the palprig that wrote it (before the rating columns).
constexpr const char* kSchemaVersion1 = R"sql(
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
)sql";

void rating_raw_sql(const std::filesystem::path& file, const std::string& sql) {
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open(file.c_str(), &db), SQLITE_OK);
  char* error = nullptr;
  ASSERT_EQ(sqlite3_exec(db, sql.c_str(), nullptr, nullptr, &error), SQLITE_OK) << (error ? error : "");
  sqlite3_close(db);
}

Protocol rated_protocol() {
  auto doc = nlohmann::json::parse(R"({
    "version": 1, "name": "rated", "task": "discrimination", "levels_kPa": [0, 30],
    "combinations": {"how_chosen": "test", "list_kPa": [[0, 30, 0], [0, 0, 0]]},
    "conditions": [{"name": "three", "mode": "simultaneous"}, {"name": "one", "mode": "sequential"}],
    "randomisation": {"scheme": "fixed"}, "confidence": {"levels": 4}})");
  return parse_protocol(doc, "rated.json", ".");
}

TrialRecord rated_trial_of(const Protocol& p, const PlannedTrial& planned) {
  TrialRecord r;
  r.planned = planned;
  r.condition = p.conditions[static_cast<std::size_t>(planned.condition)].name;
  r.mode = p.conditions[static_cast<std::size_t>(planned.condition)].mode;
  const auto& c = p.combinations[static_cast<std::size_t>(planned.combination)];
  r.combination_label = c.label;
  r.stimulus_kPa = c.pressure_kPa;
  r.truth = c.tumor;
  r.answered = planned.position != 2;  // one trial times out
  if (r.answered) {
    r.answer = c.tumor;
    r.finger_outcomes = score_discrimination(r.truth, r.answer);
    r.confidence = 1 + planned.position % 4;
  }
  r.onset_s = 10.0 * planned.position;
  r.stimulus_end_s = r.onset_s + 4.0;
  r.response_time_s = r.answered ? 5.0 + planned.position : std::nan("");
  r.felt_kPa = c.pressure_kPa;
  return r;
}

TEST(store_rating_columns, confidence_and_stimulus_end_round_trip) {
  ScratchDir dir;
  const Protocol p = rated_protocol();
  const SessionPlan plan = make_session_plan(p, 1, 7);
  {
    SqliteTrialStore store(dir / "t.db", TrialStore::Access::read_write);
    const auto who = store.enrol("P01", false);
    const auto session = store.create_session(who, p, plan, {});
    for (const PlannedTrial& t : plan.trials) store.commit_trial(session, rated_trial_of(p, t));
  }
  SqliteTrialStore reader(dir / "t.db", TrialStore::Access::read_only);
  const auto trials = reader.read_trials(true);
  ASSERT_EQ(trials.size(), plan.trials.size());
  for (const StoredTrial& t : trials) {
    const TrialRecord want = rated_trial_of(p, plan.trials[static_cast<std::size_t>(t.position)]);
    EXPECT_EQ(t.confidence, want.confidence) << t.position;
    ASSERT_TRUE(t.stimulus_end_s.has_value());
    EXPECT_DOUBLE_EQ(*t.stimulus_end_s, want.stimulus_end_s);
    if (t.answered) {
      ASSERT_TRUE(t.rt_after_stimulus_s.has_value());
      EXPECT_DOUBLE_EQ(*t.rt_after_stimulus_s, want.response_time_s - 4.0);  // onset + rt - (onset + 4)
    } else {
      EXPECT_FALSE(t.rt_after_stimulus_s.has_value());
      EXPECT_FALSE(t.confidence.has_value());
    }
  }
  // The scan `stats trials` reads carries both too.
  int rated = 0;
  reader.scan_scored_trials(TrialFamily::discrimination, true, [&](const ScoredTrial& t) {
    if (t.confidence) ++rated;
    if (t.answered) {
      EXPECT_DOUBLE_EQ(t.rt_after_stimulus_s, t.response_time_s - 4.0);
    } else {
      EXPECT_TRUE(std::isnan(t.rt_after_stimulus_s));
    }
  });
  EXPECT_EQ(rated, static_cast<int>(plan.trials.size()) - 1);
  const TrialSummary s = summarise_trials(reader, {});
  ASSERT_TRUE(s.any_rated);
  ASSERT_EQ(s.rows.size(), 1u);
  EXPECT_EQ(s.rows[0].rated, rated);
}

TEST(store_rating_columns, the_check_refuses_a_rating_outside_1_to_9) {
  ScratchDir dir;
  const Protocol p = rated_protocol();
  const SessionPlan plan = make_session_plan(p, 1, 7);
  SqliteTrialStore store(dir / "t.db", TrialStore::Access::read_write);
  const auto session = store.create_session(store.enrol("P01", false), p, plan, {});
  TrialRecord bad = rated_trial_of(p, plan.trials[0]);
  bad.confidence = 12;
  EXPECT_ANY_THROW(store.commit_trial(session, bad));
  EXPECT_TRUE(store.read_trials(true).empty());
}

// A schema-1 file with two sessions' trials, written by the old DDL and plain INSERTs.
void make_version1_file(const std::filesystem::path& file, const Protocol& p, const SessionPlan& plan) {
  std::string sql = kSchemaVersion1;
  sql += "PRAGMA application_id = " + std::to_string(kTrialStoreApplicationId) + "; PRAGMA user_version = 1;";
  sql += "INSERT INTO participants VALUES (1, 'P01', 1, 0, '2026-01-01T00:00:00Z');";
  sql += "INSERT INTO participants VALUES (2, 'P02', 2, 0, '2026-01-01T00:00:00Z');";
  for (int session = 1; session <= 2; ++session) {
    sql +=
        "INSERT INTO sessions (id, participant_id, protocol_name, task, bids_task, protocol_json, protocol_dir, seed, "
        "condition_order, rig_id, rig_backend, calibration, status, started_utc) VALUES (" +
        std::to_string(session) + ", " + std::to_string(session) + ", 'rated', 'discrimination', 'rated', '" +
        p.snapshot.dump() + "', '.', 7, '[0,1]', 'rig', 'simulated', 'cal', 'completed', '2026-01-01T00:00:00Z');";
    for (const PlannedTrial& t : plan.trials) {
      const TrialRecord r = rated_trial_of(p, t);
      const auto flags = [](const FingerFlags& f) {
        std::string s;
        for (bool b : f) s += b ? '1' : '0';
        return s;
      };
      const bool wrong = session == 2 && t.position == 0;  // one error, so the measures are not all 1
      std::string answer = flags(r.answer), o[3];
      if (wrong) answer = "111";
      for (int f = 0; f < 3; ++f) {
        const bool truth = r.truth[static_cast<std::size_t>(f)], said = answer[static_cast<std::size_t>(f)] == '1';
        o[f] = truth ? (said ? "TP" : "FN") : (said ? "FP" : "TN");
      }
      sql +=
          "INSERT INTO trials (session_id, position, block, condition, mode, practice, combination, "
          "combination_label, stimulus1_kPa, stimulus2_kPa, stimulus3_kPa, truth, answered, answer, response_time_s, "
          "onset_s, outcome1, outcome2, outcome3, completed_utc) VALUES (" +
          std::to_string(session) + ", " + std::to_string(t.position) + ", " + std::to_string(t.block) + ", '" +
          r.condition + "', '" + to_string(r.mode) + "', 0, " + std::to_string(t.combination) + ", '" +
          r.combination_label + "', 0, 30, 0, '" + flags(r.truth) + "', " +
          (r.answered ? "1, '" + answer + "', " + std::to_string(r.response_time_s) : std::string("0, NULL, NULL")) +
          ", " + std::to_string(r.onset_s) + ", " +
          (r.answered ? "'" + o[0] + "', '" + o[1] + "', '" + o[2] + "'" : std::string("NULL, NULL, NULL")) +
          ", '2026-01-01T00:00:00Z');";
    }
  }
  rating_raw_sql(file, sql);
}

TEST(store_rating_columns, a_version1_file_is_read_as_it_is_then_migrated_keeping_every_trial) {
  ScratchDir dir;
  const auto file = dir / "old.db";
  const Protocol p = rated_protocol();
  const SessionPlan plan = make_session_plan(p, 1, 7);
  make_version1_file(file, p, plan);
  const std::size_t n = 2 * plan.trials.size();

  SummaryOptions by;
  by.by = {SummaryKey::participant, SummaryKey::condition, SummaryKey::finger};
  std::string stats_before;
  std::vector<StoredTrial> before;
  {
    // A reader opens it as it is: nothing written, the new columns read as NULL.
    SqliteTrialStore reader(file, TrialStore::Access::read_only);
    EXPECT_EQ(reader.database().pragma_integer("user_version"), 1);
    before = reader.read_trials(true);
    ASSERT_EQ(before.size(), n);
    for (const StoredTrial& t : before) {
      EXPECT_FALSE(t.confidence.has_value());
      EXPECT_FALSE(t.stimulus_end_s.has_value());
      EXPECT_FALSE(t.rt_after_stimulus_s.has_value());
    }
    const TrialSummary s = summarise_trials(reader, by);
    EXPECT_FALSE(s.any_rated);
    stats_before = summary_json(s, 0.95).dump();
  }
  {
    SqliteTrialStore again(file, TrialStore::Access::read_only);
    EXPECT_EQ(again.database().pragma_integer("user_version"), 1) << "a reader never migrates";
  }
  // A writer migrates it in one transaction.
  SqliteTrialStore writer(file, TrialStore::Access::read_write);
  EXPECT_EQ(writer.database().pragma_integer("user_version"), kTrialStoreSchemaVersion);
  const auto after = writer.read_trials(true);
  ASSERT_EQ(after.size(), n);
  for (std::size_t i = 0; i < n; ++i) {
    EXPECT_EQ(after[i].id, before[i].id);
    EXPECT_EQ(after[i].answer, before[i].answer);
    EXPECT_EQ(after[i].outcome, before[i].outcome);
    EXPECT_EQ(after[i].response_time_s, before[i].response_time_s);
    EXPECT_EQ(after[i].onset_s, before[i].onset_s);
    EXPECT_FALSE(after[i].confidence.has_value());
    EXPECT_FALSE(after[i].stimulus_end_s.has_value());
  }
  EXPECT_EQ(summary_json(summarise_trials(writer, by), 0.95).dump(), stats_before);
  // The migrated file takes rated trials.
  const auto who = writer.enrol("P03", false);
  const auto session = writer.create_session(who, p, plan, {});
  writer.commit_trial(session, rated_trial_of(p, plan.trials[0]));
  auto q = writer.database().prepare("SELECT confidence, stimulus_end_s FROM trials WHERE session_id = ?1");
  q.bind(1, session);
  ASSERT_TRUE(q.step());
  EXPECT_EQ(q.integer(0), 1);
  EXPECT_DOUBLE_EQ(q.real(1), 4.0);
}

TEST(store_rating_columns, a_failed_migration_leaves_the_file_as_it_was) {
  ScratchDir dir;
  const auto file = dir / "old.db";
  const Protocol p = rated_protocol();
  make_version1_file(file, p, make_session_plan(p, 1, 7));
  // A column of that name already there (an edited file): the ALTER fails half-way.
  rating_raw_sql(file, "ALTER TABLE trials ADD COLUMN stimulus_end_s REAL;");
  try {
    SqliteTrialStore refused(file, TrialStore::Access::read_write);
    ADD_FAILURE() << "a file that cannot be migrated was opened";
  } catch (const InputError& e) {  // one line naming the file and what was expected: exit 2
    EXPECT_EQ(e.file(), file.string());
    EXPECT_EQ(e.where(), "trials (schema 1 -> 2 migration)");
    EXPECT_NE(e.expected().find("the file was not changed"), std::string::npos) << e.what();
  }
  SqliteTrialStore reader(file, TrialStore::Access::read_only);
  EXPECT_EQ(reader.database().pragma_integer("user_version"), 1);
  auto q = reader.database().prepare("SELECT count(*) FROM pragma_table_info('trials') WHERE name = 'confidence'");
  ASSERT_TRUE(q.step());
  EXPECT_EQ(q.integer(0), 0) << "the first ALTER was rolled back with the second";
}

}  // namespace
}  // namespace palprig
