// Trainees and their history in the SQLite trial store (schema 5): enrolments, training
// sessions with their cases (never the same case twice for one trainee), completion; the
// migration from schema 4 in one transaction with every trial kept; an older file read as it is;
// and `store copy` carrying the history with the sessions.
#include <gtest/gtest.h>

#include "sessions/session_setup.hpp"
#include "store/lab_sync.hpp"
#include "store/sqlite_session_rows.hpp"
#include "store/sqlite_trial_store.hpp"
#include "tests/support/support.hpp"

namespace palprig {
namespace {

using testing::ScratchDir;

std::int64_t phantom_session(TrialStore& store, const std::string& who, int trials) {
  const Protocol p = load_protocol(testing::protocols_dir() / "localisation_002.json");
  SessionRequest request;
  request.participant_code = who;
  const OpenedSession s = open_session(store, p, request);
  for (int i = 0; i < trials && i < static_cast<int>(s.plan.trials.size()); ++i) {
    TrialRecord r;
    r.planned = s.plan.trials[static_cast<std::size_t>(i)];
    r.condition = "three-finger";
    r.mode = PresentationMode::scene;
    r.answered = true;
    r.response_time_s = 42.5;
    const auto& tumors = p.localisation.cases.at(0).tumors;
    r.marks = {{tumors[1].x_mm, tumors[1].y_mm}, {5, 5}};
    r.localisation = score_localisation(tumors, r.marks, 5);
    r.case_name = p.localisation.cases.at(0).name;
    r.case_tumors = 3;
    store.commit_trial(s.session_id, r);
  }
  return s.session_id;
}

TrainingSessionRecord training_row(std::int64_t session, std::vector<std::string> cases) {
  TrainingSessionRecord r;
  r.session_id = session;
  r.trainee = "T1";
  r.curriculum = "course";
  r.level = 0;
  r.level_name = "easy";
  r.cases = std::move(cases);
  return r;
}

TEST(TrainingStore, EnrolmentsSessionsAndCasesAreKeptAndACaseIsNeverGivenTwice) {
  ScratchDir dir;
  SqliteTrialStore store(dir / "t.db", TrialStore::Access::read_write);
  store.enrol_trainee("T1", "course");
  store.enrol_trainee("T1", "course");  // again: nothing changes
  store.enrol_trainee("T2", "course");
  ASSERT_EQ(store.trainees().size(), 2u);
  EXPECT_EQ(store.trainees()[0].code, "T1");

  const std::int64_t first = phantom_session(store, "T1", 1);
  store.begin_training_session(training_row(first, {"generated:easy:1", "generated:easy:2"}));
  auto history = store.training_sessions("T1");
  ASSERT_EQ(history.size(), 1u);
  EXPECT_EQ(history[0].status, "running");
  EXPECT_EQ(history[0].cases, (std::vector<std::string>{"generated:easy:1", "generated:easy:2"}));
  EXPECT_FALSE(history[0].met_benchmark.has_value());

  store.complete_training_session(first, nlohmann::json{{"cases", nlohmann::json::array()}}, true);
  history = store.training_sessions("T1");
  EXPECT_TRUE(history[0].completed());
  EXPECT_EQ(history[0].met_benchmark, true);
  EXPECT_FALSE(history[0].finished_utc.empty());

  // A second session holding a case the trainee had: refused, and nothing of it is written.
  const std::int64_t second = phantom_session(store, "T1b", 0);
  EXPECT_THROW(store.begin_training_session(training_row(second, {"generated:easy:3", "generated:easy:2"})),
               InputError);
  EXPECT_EQ(store.training_sessions("T1").size(), 1u);
  auto count = store.database().prepare("SELECT count(*) FROM training_cases");
  count.step();
  EXPECT_EQ(count.integer(0), 2);
  // Another trainee may get that case.
  TrainingSessionRecord other = training_row(second, {"generated:easy:2"});
  other.trainee = "T2";
  store.begin_training_session(other);
  EXPECT_EQ(store.training_sessions("T2").size(), 1u);
}

TEST(TrainingStore, SchemaFourFileIsMigratedInOneTransactionWithEveryTrialKept) {
  ScratchDir dir;
  const auto file = dir / "old.db";
  std::vector<StoredTrial> before;
  {
    SqliteTrialStore store(file, TrialStore::Access::read_write);
    phantom_session(store, "P1", 1);
    phantom_session(store, "P2", 1);
    // Back to schema 4 as an older palprig left it: no case columns, no training tables.
    Database& db = store.database();
    for (const char* column : {"case_name", "case_seed", "case_difficulty", "case_tumors"})
      db.exec(std::string("ALTER TABLE trials DROP COLUMN ") + column);
    db.exec("DROP TABLE training_cases; DROP TABLE training_sessions; DROP TABLE trainees; PRAGMA user_version = 4");
  }
  {
    // Read as it is: no history, nothing written (the file stays schema 4).
    SqliteTrialStore reader(file, TrialStore::Access::read_only);
    EXPECT_TRUE(reader.trainees().empty());
    EXPECT_TRUE(reader.training_sessions("P1").empty());
    before = reader.read_trials(true);
    ASSERT_EQ(before.size(), 2u);
    EXPECT_FALSE(before[0].case_name.has_value());
    EXPECT_EQ(reader.database().pragma_integer("user_version"), 4);
  }
  SqliteTrialStore store(file, TrialStore::Access::read_write);
  EXPECT_EQ(store.database().pragma_integer("user_version"), kTrialStoreSchemaVersion);
  const std::vector<StoredTrial> after = store.read_trials(true);
  ASSERT_EQ(after.size(), before.size());
  for (std::size_t i = 0; i < after.size(); ++i) {
    EXPECT_EQ(after[i].id, before[i].id);
    EXPECT_EQ(after[i].response_time_s, before[i].response_time_s);
    EXPECT_EQ(after[i].tumor_outcomes, before[i].tumor_outcomes);
    EXPECT_EQ(after[i].false_marks, before[i].false_marks);
    EXPECT_FALSE(after[i].case_name.has_value());  // NULL for the trials stored before
  }
  store.enrol_trainee("P1", "course");  // the training tables are there now
  EXPECT_EQ(store.trainees().size(), 1u);
}

TEST(TrainingStore, StoreCopyCarriesTraineesAndTheirHistoryWithTheSessions) {
  ScratchDir dir;
  {
    SqliteTrialStore rig(dir / "rig.db", TrialStore::Access::read_write);
    rig.enrol_trainee("T1", "course");
    const std::int64_t s = phantom_session(rig, "T1", 1);
    rig.begin_training_session(training_row(s, {"generated:easy:9"}));
    rig.complete_training_session(s, nlohmann::json{{"cases", nlohmann::json::array()}}, false);
  }
  const CopyReport report = copy_study((dir / "rig.db").string(), (dir / "lab.db").string(), std::nullopt);
  EXPECT_EQ(report.sessions_added, 1);
  copy_study((dir / "rig.db").string(), (dir / "lab.db").string(), std::nullopt);  // twice: stored once
  SqliteTrialStore lab(dir / "lab.db", TrialStore::Access::read_only);
  ASSERT_EQ(lab.trainees().size(), 1u);
  const auto history = lab.training_sessions("T1");
  ASSERT_EQ(history.size(), 1u);
  EXPECT_EQ(history[0].cases, std::vector<std::string>{"generated:easy:9"});
  EXPECT_TRUE(history[0].completed());
  EXPECT_EQ(history[0].met_benchmark, false);
}

}  // namespace
}  // namespace palprig
