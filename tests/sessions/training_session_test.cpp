// A training programme run end to end on the simulated rig (sessions/training_session.hpp):
// a simulated trainee who learns reaches the last level in the number of sessions its learning
// rate predicts; one who does not learn never leaves the first level; no trainee gets a case
// twice; an unfinished session is continued; bad curricula, unknown trainees and a benchmark
// without expert sessions are refused with one line and nothing stored is lost.
#include "sessions/training_session.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <set>

#include "core/input_error.hpp"
#include "store/sqlite_trial_store.hpp"
#include "tests/support/support.hpp"
#include "tests/support/temp_dir.hpp"

namespace palprig {
namespace {

using testing::ScratchDir;

// Three levels of generated easy cases (large, shallow tumors), so what a trainee finds is their
// skill times what a skilled one finds on such cases: found_min 0.6 on two sessions in a row, 4
// cases a session. The pilot starts at skill 0.2 and learns at `rate` per case.
std::filesystem::path write_course(const ScratchDir& dir, double rate, double initial = 0.2,
                                   const std::string& name = "course", int cases = 4) {
  nlohmann::json level = {{"cases", {{"generate", "easy"}}},
                          {"cases_per_session", cases},
                          {"time_limit_s", 90},
                          {"benchmark", {{"found_min", 0.6}, {"consecutive_sessions", 2}}}};
  nlohmann::json doc = {{"version", 1}, {"kind", "curriculum"}, {"name", name}, {"levels", nlohmann::json::array()}};
  for (const char* level_name : {"one", "two", "three"}) {
    level["name"] = level_name;
    doc["levels"].push_back(level);
  }
  doc["pilot"] = {{"initial_skill", initial}, {"learning_rate_per_case", rate}};
  auto path = dir / (name + ".json");
  std::ofstream(path) << doc.dump(2);
  return path;
}

TrainingRequest request_for(const std::filesystem::path& course, const std::filesystem::path& db,
                            const std::string& trainee, const std::string& sim) {
  TrainingRequest r;
  r.curriculum_file = course;
  r.trainee = trainee;
  r.store_location = db.string();
  r.participant = sim;
  r.rig_file = testing::source_dir() / "data" / "rigs" / "simulated.json";
  return r;
}

// Runs sessions until the trainee first trains at `level` (returns that session number) or
// `max_sessions` have run (returns none); every case a trainee got is checked new to them.
std::optional<int> sessions_until_level(const std::filesystem::path& course, const std::filesystem::path& db,
                                        const std::string& trainee, const std::string& sim, int level, int max_sessions,
                                        std::set<std::string>& cases) {
  const Curriculum c = load_curriculum(course);
  enrol_trainee(db.string(), c, trainee);
  std::optional<int> reached;
  for (int session = 1; session <= max_sessions && !reached; ++session) {
    const TrainingOutcome out = run_training_session(request_for(course, db, trainee, sim), {}, RunControl{});
    EXPECT_TRUE(out.scored) << "session " << session;
    if (out.plan.level >= level) reached = session;
  }
  for (const auto& r : trainee_standing(db.string(), c, trainee).sessions) {
    for (const auto& k : r.cases) {
      std::string given = trainee;
      given.append(" ").append(k);
      EXPECT_TRUE(cases.insert(given).second) << k << " given twice";
    }
  }
  return reached;
}

// What a fully skilled simulated trainee finds on the course's cases (the prediction's
// ceiling): two experts, 24 cases each.
double expert_found(const ScratchDir& dir) {
  const auto course = write_course(dir, 0.0, 1.0, "experts", 24);
  const Curriculum c = load_curriculum(course);
  int found = 0, tumors = 0;
  for (const char* expert : {"E1", "E2"}) {
    enrol_trainee((dir / "experts.db").string(), c, expert);
    const TrainingOutcome out = run_training_session(
        request_for(course, dir / "experts.db", expert, expert[1] == '1' ? "sim:21" : "sim:22"), {}, RunControl{});
    EXPECT_TRUE(out.scored);
    found += out.scores.found();
    tumors += out.scores.targets();
  }
  return static_cast<double>(found) / tumors;
}

TEST(TrainingSession, ALearnerReachesTheLastLevelInTheSessionsItsLearningRatePredicts) {
  ScratchDir dir;
  const double ceiling = expert_found(dir);
  EXPECT_GT(ceiling, 0.7) << "a skilled trainee finds most tumors of easy cases";
  const auto course = write_course(dir, 0.15);
  const Curriculum c = load_curriculum(course);
  const auto predicted = predict_pilot_sessions(c, 40, {ceiling, ceiling, ceiling});
  ASSERT_TRUE(predicted[2].has_value());
  // The tolerance: a session's 4 cases hold 4-8 tumors, so its found fraction scatters around the
  // expected one and a run of two may come a session early or late at each of two levels (a
  // binomial model of these sessions puts 200 of 200 seeds within 3 sessions, sd 1).
  constexpr int kTolerance = 3;
  std::set<std::string> cases;
  int total = 0;
  for (int seed : {1, 2, 3, 4}) {
    const std::string trainee = "learner" + std::to_string(seed);
    const auto reached = sessions_until_level(course, dir / "train.db", trainee, "sim:" + std::to_string(seed), 2,
                                              *predicted[2] + 2 * kTolerance, cases);
    ASSERT_TRUE(reached.has_value()) << trainee << " did not reach the last level";
    EXPECT_NEAR(*reached, *predicted[2], kTolerance) << trainee;
    total += *reached;
  }
  EXPECT_NEAR(total / 4.0, *predicted[2], 1.5) << "the mean over the seeds";
}

TEST(TrainingSession, ATraineeWhoDoesNotLearnNeverLeavesTheFirstLevel) {
  ScratchDir dir;
  const auto course = write_course(dir, 0.0);
  std::set<std::string> cases;
  for (int seed : {5, 6}) {
    const std::string trainee = "stuck" + std::to_string(seed);
    EXPECT_FALSE(sessions_until_level(course, dir / "train.db", trainee, "sim:" + std::to_string(seed), 1, 6, cases)
                     .has_value());
    const auto standing = trainee_standing((dir / "train.db").string(), load_curriculum(course), trainee);
    EXPECT_EQ(standing.standing.level, 0);
    EXPECT_EQ(standing.standing.sessions, 6);
  }
}

TEST(TrainingSession, AnUnfinishedSessionIsContinuedWithItsOwnCases) {
  ScratchDir dir;
  const auto course = write_course(dir, 0.2);
  const auto db = dir / "train.db";
  const Curriculum c = load_curriculum(course);
  enrol_trainee(db.string(), c, "T");
  RunControl stop;
  // Stopped after the first committed case.
  class StopAfterFirst final : public SessionListener {
   public:
    explicit StopAfterFirst(RunControl& stop) : stop_(stop) {}
    void trial_committed(const TrialRecord&, int) override { stop_.request_stop(); }

   private:
    RunControl& stop_;
  } stopper(stop);
  TrainingFrontEnd front;
  front.listener = &stopper;
  const TrainingOutcome first = run_training_session(request_for(course, db, "T", "sim:9"), front, stop);
  EXPECT_FALSE(first.scored);
  EXPECT_EQ(first.end.committed_trials, 1);
  const TrainingOutcome second = run_training_session(request_for(course, db, "T", "sim:9"), {}, RunControl{});
  EXPECT_TRUE(second.plan.resumed);
  EXPECT_EQ(second.plan.cases, first.plan.cases);
  ASSERT_TRUE(second.scored);
  EXPECT_EQ(second.scores.cases.size(), 4u);  // the first case from the store, three from this run
  const auto standing = trainee_standing(db.string(), c, "T");
  EXPECT_EQ(standing.standing.sessions, 1);
  EXPECT_EQ(standing.sessions.size(), 1u);
}

TEST(TrainingSession, RefusalsAreOneLineAndLoseNothingStored) {
  ScratchDir dir;
  const auto course = write_course(dir, 0.2);
  const auto db = dir / "train.db";
  const Curriculum c = load_curriculum(course);
  enrol_trainee(db.string(), c, "T");
  ASSERT_TRUE(run_training_session(request_for(course, db, "T", "sim:1"), {}, RunControl{}).scored);
  const auto trials_before = [&] {
    SqliteTrialStore store(db, TrialStore::Access::read_only);
    return store.read_trials(true).size();
  }();
  const auto one_line = [](const std::function<void()>& f) {
    try {
      f();
    } catch (const InputError& e) {
      std::string line = e.what();
      EXPECT_EQ(line.find('\n'), std::string::npos) << line;
      return line;
    }
    return std::string("accepted");
  };
  // An unknown trainee.
  EXPECT_NE(one_line([&] {
              run_training_session(request_for(course, db, "nobody", "sim:1"), {}, RunControl{});
            }).find("trainee 'nobody'"),
            std::string::npos);
  // A bad curriculum file.
  const auto bad = dir / "bad.json";
  std::ofstream(bad) << R"({"version": 1, "kind": "curriculum", "name": "x", "levels": [{"name": "a",
      "cases": {"generate": "easy"}, "benchmark": {"found_min": 2}}]})";
  EXPECT_NE(one_line([&] {
              run_training_session(request_for(bad, db, "T", "sim:1"), {}, RunControl{});
            }).find("levels[0].benchmark.found_min"),
            std::string::npos);
  // A person at a front end that cannot ask one (the terminal has no pen).
  EXPECT_NE(
      one_line([&] { run_training_session(request_for(course, db, "T", ""), {}, RunControl{}); }).find("participant"),
      std::string::npos);
  // A benchmark from experts who have no session at the level.
  EXPECT_NE(one_line([&] {
              expert_benchmark(db.string(), c, 1, {"T", "expert2"}, std::nullopt);
            }).find("experts"),
            std::string::npos);
  // An unknown level.
  TrainingRequest r = request_for(course, db, "T", "sim:1");
  r.level = "four";
  EXPECT_NE(one_line([&] { run_training_session(r, {}, RunControl{}); }).find("'four'"), std::string::npos);
  // Nothing stored was lost, nothing was added, and the next session runs as it would have.
  SqliteTrialStore store(db, TrialStore::Access::read_only);
  EXPECT_EQ(store.read_trials(true).size(), trials_before);
  EXPECT_EQ(store.training_sessions("T").size(), 1u);
}

TEST(TrainingSession, ExpertBenchmarkIsTheMeanOrAPercentileOfTheirSessionsAtTheLevel) {
  ScratchDir dir;
  const auto course = write_course(dir, 0.0, 1.0);  // fully skilled from the start
  const auto db = dir / "train.db";
  const Curriculum c = load_curriculum(course);
  for (const char* expert : {"E1", "E2"}) {
    enrol_trainee(db.string(), c, expert);
    TrainingRequest r = request_for(course, db, expert, std::string("sim:") + (expert[1] == '1' ? "11" : "12"));
    r.level = "two";
    ASSERT_TRUE(run_training_session(r, {}, RunControl{}).scored);
  }
  const ExpertBenchmark mean = expert_benchmark(db.string(), c, 1, {"E1", "E2"}, std::nullopt);
  EXPECT_EQ(mean.sessions, 2);
  ASSERT_TRUE(mean.benchmark.found_min.has_value());
  ASSERT_TRUE(mean.benchmark.time_per_case_max_s.has_value());
  const ExpertBenchmark p0 = expert_benchmark(db.string(), c, 1, {"E1", "E2"}, 0.0);
  EXPECT_LE(*p0.benchmark.found_min, *mean.benchmark.found_min);                      // the lowest expert session
  EXPECT_GE(*p0.benchmark.time_per_case_max_s, *mean.benchmark.time_per_case_max_s);  // the slowest
  // Sessions at level two did not move the experts off level one.
  EXPECT_EQ(trainee_standing(db.string(), c, "E1").standing.level, 0);
}

}  // namespace
}  // namespace palprig
