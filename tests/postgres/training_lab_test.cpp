// A trainee trains on any rig of the lab (with_server.sh: a real PostgreSQL server from
// pg_virtualenv; skipped with the reason when none can start): enrolled on the lab server, a
// session on one bench (its own journal) and the next on another continue the same history
// (level, sessions, never a case twice); a rig that trained offline into its own file carries
// the trainee's history to the server with `store copy`; a version-5 server holding trials is
// migrated to schema 6 in one transaction with every trial kept; a pulse level is refused on the
// server, nothing stored.
#include <gtest/gtest.h>

#include <fstream>
#include <set>

#include "core/input_error.hpp"
#include "sessions/training_session.hpp"
#include "store/lab_sync.hpp"
#include "store/postgres_trial_store.hpp"
#include "tests/postgres/pg_test_support.hpp"
#include "tests/support/process_support.hpp"
#include "tests/support/support.hpp"

namespace palprig {
namespace {

using testing::ScratchDir;

// Two levels of generated easy cases, 2 cases a session, passed after one session meeting
// found_min 0.5; a fully skilled pilot passes each level in one session.
std::filesystem::path write_course(const ScratchDir& dir, bool pulse_second = false) {
  nlohmann::json doc = {{"version", 1}, {"kind", "curriculum"}, {"name", "lab course"}};
  doc["levels"] = nlohmann::json::array();
  doc["levels"].push_back({{"name", "first"},
                           {"cases", {{"generate", "easy"}}},
                           {"cases_per_session", 2},
                           {"benchmark", {{"found_min", 0.5}, {"consecutive_sessions", 2}}}});
  doc["levels"].push_back(
      {{"name", "second"},
       {"cases", pulse_second ? nlohmann::json{{"pulse", "easy"}} : nlohmann::json{{"generate", "easy"}}},
       {"cases_per_session", 2},
       {"benchmark", {{"found_min", 0.5}, {"consecutive_sessions", 1}}}});
  doc["pilot"] = {{"initial_skill", 1.0}, {"learning_rate_per_case", 0.0}};
  auto path = dir / "course.json";
  std::ofstream(path) << doc.dump(2);
  return path;
}

TrainingRequest on(const std::filesystem::path& course, const std::string& store,
                   const std::filesystem::path& journal) {
  TrainingRequest r;
  r.curriculum_file = course;
  r.trainee = "T7";
  r.store_location = store;
  r.journal_file = journal;
  r.participant = "sim:7";
  r.rig_file = testing::source_dir() / "data" / "rigs" / "simulated.json";
  return r;
}

void expect_no_case_twice(const std::vector<TrainingSessionRecord>& history) {
  std::set<std::string> seen;
  for (const auto& r : history) {
    for (const auto& k : r.cases) EXPECT_TRUE(seen.insert(k).second) << k << " given twice";
  }
}

TEST(PostgresTraining, ATraineesHistoryMovesBetweenRigsThroughTheLabServer) {
  PALPRIG_REQUIRE_PG_SERVER();
  ScratchDir dir;
  const std::string uri = testing::fresh_database("training_rigs");
  const auto course = write_course(dir);
  const Curriculum c = load_curriculum(course);
  enrol_trainee(uri, c, "T7");
  // Rig A: the first session of level one.
  const TrainingOutcome a = run_training_session(on(course, uri, dir / "bench_a.sqlite"), {}, RunControl{});
  ASSERT_TRUE(a.scored);
  EXPECT_EQ(a.plan.level, 0);
  EXPECT_EQ(a.end.unpushed_trials, 0);
  // Rig B, another bench with its own journal: the trainee continues where rig A left them.
  const TrainingOutcome b = run_training_session(on(course, uri, dir / "bench_b.sqlite"), {}, RunControl{});
  ASSERT_TRUE(b.scored);
  EXPECT_EQ(b.before.sessions, 1) << "rig B sees the session rig A ran";
  EXPECT_EQ(b.plan.session_number, 2);
  EXPECT_EQ(b.after.level, 1) << "two sessions in a row met level one's benchmark, across two rigs";
  // Rig A again: level two.
  const TrainingOutcome a2 = run_training_session(on(course, uri, dir / "bench_a.sqlite"), {}, RunControl{});
  EXPECT_EQ(a2.plan.level, 1);
  const TraineeStanding t = trainee_standing(uri, c, "T7");
  EXPECT_TRUE(t.standing.finished);
  ASSERT_EQ(t.sessions.size(), 3u);
  for (const auto& r : t.sessions) EXPECT_TRUE(r.completed());
  expect_no_case_twice(t.sessions);
  // The server holds every trial of the three sessions, once.
  EXPECT_EQ(testing::pg_scalar(uri, "SELECT count(*) FROM trials"), 6);
  EXPECT_EQ(testing::pg_scalar(uri, "SELECT count(*) FROM training_cases WHERE trainee = 'T7'"), 6);
}

TEST(PostgresTraining, AnOfflineRigsHistoryIsCarriedToTheServerByStoreCopy) {
  PALPRIG_REQUIRE_PG_SERVER();
  ScratchDir dir;
  const std::string uri = testing::fresh_database("training_copy");
  const auto course = write_course(dir);
  const Curriculum c = load_curriculum(course);
  const auto file = (dir / "offline.db").string();
  enrol_trainee(file, c, "T7");
  ASSERT_TRUE(run_training_session(on(course, file, {}), {}, RunControl{}).scored);
  copy_study(file, uri, std::nullopt);
  copy_study(file, uri, std::nullopt);  // twice: stored once
  const TraineeStanding there = trainee_standing(uri, c, "T7");
  ASSERT_EQ(there.sessions.size(), 1u);
  EXPECT_EQ(there.standing.sessions, 1);
  // The next session on a lab rig continues that history, with new cases.
  const TrainingOutcome next = run_training_session(on(course, uri, dir / "bench.sqlite"), {}, RunControl{});
  ASSERT_TRUE(next.scored);
  EXPECT_EQ(next.plan.session_number, 2);
  EXPECT_EQ(next.after.level, 1);
  expect_no_case_twice(trainee_standing(uri, c, "T7").sessions);
}

TEST(PostgresTraining, Version5ServerIsMigratedWithEveryTrialKept) {
  PALPRIG_REQUIRE_PG_SERVER();
  ScratchDir dir;
  const std::string file = (dir / "bench.db").string();
  const auto run = testing::run_palprig({"experiment", "run", "--protocol",
                                         (testing::protocols_dir() / "localisation_002.json").string(), "--participant",
                                         "sim:3", "--db", file, "--quiet"});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const std::string uri = testing::old_server_holding("training_5_6", 5, file);
  const std::int64_t trials = testing::pg_scalar(uri, "SELECT count(*) FROM trials");
  const std::int64_t scores = testing::pg_scalar(uri, "SELECT count(*) FROM tumor_scores");
  ASSERT_GT(trials, 0);
  {
    // A reader reads it as it is: no training tables, no history, nothing written.
    PostgresTrialStore reader(parse_pg_target(uri), TrialStore::Access::read_only);
    EXPECT_TRUE(reader.trainees().empty());
    EXPECT_EQ(testing::pg_scalar(uri, "SELECT max(version) FROM palprig_schema"), 5);
  }
  PostgresTrialStore writer(parse_pg_target(uri), TrialStore::Access::read_write);
  EXPECT_EQ(testing::pg_scalar(uri, "SELECT max(version) FROM palprig_schema"), kPgSchemaVersion);
  EXPECT_EQ(testing::pg_scalar(uri, "SELECT count(*) FROM trials"), trials);
  EXPECT_EQ(testing::pg_scalar(uri, "SELECT count(*) FROM tumor_scores"), scores);
  EXPECT_EQ(testing::pg_scalar(uri, "SELECT count(*) FROM trials WHERE case_name IS NOT NULL"), 0);
  writer.enrol_trainee("T1", "course");
  EXPECT_EQ(writer.trainees().size(), 1u);
}

TEST(PostgresTraining, APulseLevelIsRefusedOnTheServerWithNothingStored) {
  PALPRIG_REQUIRE_PG_SERVER();
  ScratchDir dir;
  const std::string uri = testing::fresh_database("training_pulse");
  const auto course = write_course(dir, true);
  const Curriculum c = load_curriculum(course);
  enrol_trainee(uri, c, "T7");
  TrainingRequest r = on(course, uri, dir / "bench.sqlite");
  r.level = "second";
  try {
    run_training_session(r, {}, RunControl{});
    FAIL() << "a pulse level on the lab server was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("pulse"), std::string::npos) << e.what();
  }
  EXPECT_EQ(testing::pg_scalar(uri, "SELECT count(*) FROM sessions"), 0);
  EXPECT_EQ(testing::pg_scalar(uri, "SELECT count(*) FROM training_sessions"), 0);
}

}  // namespace
}  // namespace palprig
