// The rules of a training programme (study/training.hpp), as pure functions: where a trainee
// stands, the cases of their next session (never one they had), the protocol that session runs,
// its benchmark, the CUSUM outcome of a case and the pilot's prediction.
#include "study/training.hpp"

#include <gtest/gtest.h>

#include <filesystem>

#include "study/localisation_case.hpp"
#include "study/pulse_protocol.hpp"

namespace palprig {
namespace {

const std::filesystem::path kRulesCurricula = std::filesystem::path(PALPRIG_SOURCE_DIR) / "data" / "curricula";

Curriculum shipped() { return load_curriculum(kRulesCurricula / "palpation_basics.json"); }

TrainingSessionRecord done(const Curriculum& c, int level, bool met, std::int64_t id) {
  TrainingSessionRecord r;
  r.session_id = id;
  r.trainee = "T1";
  r.curriculum = c.name;
  r.level = level;
  r.level_name = c.levels[static_cast<std::size_t>(level)].name;
  r.status = "completed";
  r.met_benchmark = met;
  return r;
}

TEST(TrainingRules, ATraineeMovesOnAfterTheLevelsRunOfConsecutiveSessionsMeetingItsBenchmark) {
  const Curriculum c = shipped();
  std::vector<TrainingSessionRecord> h;
  EXPECT_EQ(training_standing(c, h).level, 0);
  h.push_back(done(c, 0, true, 1));
  h.push_back(done(c, 0, false, 2));  // the run breaks
  h.push_back(done(c, 0, true, 3));
  TrainingStanding s = training_standing(c, h);
  EXPECT_EQ(s.level, 0);
  EXPECT_EQ(s.consecutive_met, 1);
  EXPECT_EQ(s.sessions_at_level, 3);
  h.push_back(done(c, 0, true, 4));  // two in a row: level 1 passed
  s = training_standing(c, h);
  EXPECT_EQ(s.level, 1);
  EXPECT_EQ(s.passed_after, std::vector<int>{4});
  // A session at another level (an expert's --level session) does not move the trainee.
  h.push_back(done(c, 3, true, 5));
  h.push_back(done(c, 3, true, 6));
  EXPECT_EQ(training_standing(c, h).level, 1);
  // Another curriculum's sessions are not this one's; a running one is there to resume.
  TrainingSessionRecord other = done(c, 0, true, 7);
  other.curriculum = "another course";
  h.push_back(other);
  TrainingSessionRecord running = done(c, 1, false, 8);
  running.status = "running";
  h.push_back(running);
  s = training_standing(c, h);
  EXPECT_EQ(s.sessions, 6);
  EXPECT_EQ(s.running_session, 8);
}

TEST(TrainingRules, PassingTheLastLevelFinishesTheCurriculum) {
  const Curriculum c = shipped();
  std::vector<TrainingSessionRecord> h;
  std::int64_t id = 1;
  for (int level = 0; level < static_cast<int>(c.levels.size()); ++level) {
    for (int i = 0; i < c.levels[static_cast<std::size_t>(level)].benchmark.consecutive_sessions; ++i)
      h.push_back(done(c, level, true, id++));
  }
  const TrainingStanding s = training_standing(c, h);
  EXPECT_TRUE(s.finished);
  EXPECT_EQ(s.level, static_cast<int>(c.levels.size()));
  EXPECT_EQ(s.passed_after.size(), c.levels.size());
}

TEST(TrainingRules, NextSessionNeverGivesACaseTheTraineeHad) {
  const Curriculum c = shipped();
  std::set<std::string> given;
  for (int session = 1; session <= 30; ++session) {
    const PlannedTrainingSession plan = plan_training_session(c, 0, "T1", given, session);
    ASSERT_EQ(plan.cases.size(), 4u);
    for (const TrainingCase& k : plan.cases) {
      EXPECT_TRUE(given.insert(k.key).second) << k.key << " given twice (session " << session << ")";
      EXPECT_TRUE(k.seed.has_value());
    }
  }
  // Even when the draw would repeat itself (the same trainee, level and session number again).
  const PlannedTrainingSession again = plan_training_session(c, 0, "T1", given, 1);
  for (const TrainingCase& k : again.cases) EXPECT_TRUE(given.insert(k.key).second) << k.key;
}

TEST(TrainingRules, TheSessionsProtocolIsAValidLocalisationProtocolOfExactlyItsCases) {
  const Curriculum c = shipped();
  const PlannedTrainingSession plan = plan_training_session(c, 1, "T1", {}, 1);
  EXPECT_EQ(plan.protocol_name, "palpation-basics / medium tumors");
  const Protocol p = parse_protocol(plan.protocol, "plan", kRulesCurricula);
  EXPECT_EQ(p.task, TaskKind::localisation);
  ASSERT_EQ(p.localisation.cases.size(), 5u);
  for (std::size_t i = 0; i < plan.cases.size(); ++i) {
    EXPECT_EQ(case_key(p.localisation.cases[i]), plan.cases[i].key);
    EXPECT_EQ(p.localisation.cases[i].name, plan.cases[i].name);
    EXPECT_EQ(p.localisation.cases[i].difficulty, CaseDifficulty::medium);
  }
  EXPECT_DOUBLE_EQ(p.timing.max_present_s, 120);
  EXPECT_EQ(p.feedback, Feedback::all);
  EXPECT_EQ(make_session_plan(p, 1, 7).trials.size(), 5u);
}

TEST(TrainingRules, PulseLevelsRunAPulseProtocolWithTheChosenSeeds) {
  const Curriculum c = shipped();
  const PlannedTrainingSession plan = plan_training_session(c, 4, "T1", {}, 1);
  EXPECT_TRUE(plan.pulse);
  const PulseProtocol p = parse_pulse_protocol(plan.protocol, "plan", kRulesCurricula);
  ASSERT_EQ(p.conditions.size(), 4u);
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_EQ(p.conditions[i].generated_seed, plan.cases[i].seed);
    EXPECT_EQ(plan.cases[i].key.rfind("pulse:easy:", 0), 0u);
  }
}

TEST(TrainingRules, ASceneSetGivesTheScenesNotHadFirst) {
  Curriculum c = shipped();
  c.levels[2].scenes.push_back(kRulesCurricula / ".." / "scenes" / "phantom_abc.json");
  c.levels[2].cases_per_session = 1;
  const PlannedTrainingSession first = plan_training_session(c, 2, "T1", {}, 1);
  ASSERT_EQ(first.cases.size(), 1u);
  const PlannedTrainingSession second = plan_training_session(c, 2, "T1", {first.cases[0].key}, 2);
  EXPECT_NE(second.cases[0].key, first.cases[0].key);
  // Every scene had: the set again (a fixed set repeats; generated cases never do).
  const PlannedTrainingSession third = plan_training_session(c, 2, "T1", {first.cases[0].key, second.cases[0].key}, 3);
  EXPECT_EQ(third.cases.size(), 1u);
}

CaseResult localisation_case(int tumors, int found, int false_marks, double time_s) {
  CaseResult c;
  c.answered = true;
  c.tumors = tumors;
  c.found = found;
  c.false_marks = false_marks;
  c.time_s = time_s;
  return c;
}

TEST(TrainingRules, BenchmarkNamesEveryShortfall) {
  LevelBenchmark b;
  b.found_min = 0.9;
  b.false_marks_per_case_max = 0.5;
  b.time_per_case_max_s = 60;
  b.normal_called_min = 0.5;
  SessionScores s;
  s.cases = {localisation_case(2, 2, 0, 40), localisation_case(2, 1, 1, 90), localisation_case(0, 0, 1, 30)};
  const BenchmarkResult r = check_benchmark(b, s);
  EXPECT_FALSE(r.met);
  ASSERT_EQ(r.shortfalls.size(), 3u);
  EXPECT_EQ(r.shortfalls[0], "tumors found 0.75 (wanted >= 0.90)");
  EXPECT_EQ(r.shortfalls[1], "false marks per case 0.67 (wanted <= 0.50)");
  EXPECT_EQ(r.shortfalls[2], "normal cases called normal 0.00 (wanted >= 0.50)");
  s.cases = {localisation_case(2, 2, 0, 40), localisation_case(1, 1, 0, 50)};
  EXPECT_TRUE(check_benchmark(b, s).met);  // no normal case: not held against the session
  // Scores survive the store's JSON.
  const SessionScores back = scores_from_json(to_json(s));
  EXPECT_EQ(back.found(), 3);
  EXPECT_DOUBLE_EQ(*back.time_per_case_s(), 45.0);
}

TEST(TrainingRules, ACaseFailsUnlessEveryTumorIsFoundWithinTheFalseMarkAllowance) {
  LevelBenchmark b;
  EXPECT_FALSE(case_failed(localisation_case(2, 2, 0, 10), b));
  EXPECT_TRUE(case_failed(localisation_case(2, 1, 0, 10), b));
  EXPECT_TRUE(case_failed(localisation_case(2, 2, 1, 10), b));
  b.false_marks_per_case_max = 1.5;  // a whole false mark allowed per case
  EXPECT_FALSE(case_failed(localisation_case(2, 2, 1, 10), b));
  EXPECT_TRUE(case_failed(localisation_case(0, 0, 1, 10), b));   // a normal case marked
  EXPECT_FALSE(case_failed(localisation_case(0, 0, 0, 10), b));  // "nothing there": right
  CaseResult unanswered;
  unanswered.tumors = 1;
  EXPECT_TRUE(case_failed(unanswered, b));
}

TEST(TrainingRules, PilotSkillRisesAtItsRateAndPredictsTheSessionsPerLevel) {
  const CurriculumPilot pilot{0.4, 0.08};
  EXPECT_DOUBLE_EQ(pilot_skill(pilot, 0), 0.4);
  EXPECT_NEAR(pilot_skill(pilot, 10), 1 - 0.6 * std::exp(-0.8), 1e-12);
  const Curriculum c = shipped();
  const auto first = predict_pilot_sessions(c, 200);
  ASSERT_EQ(first.size(), 5u);
  EXPECT_EQ(first[0], 1);
  for (std::size_t i = 1; i < first.size(); ++i) {
    ASSERT_TRUE(first[i].has_value()) << "level " << i + 1;
    EXPECT_GT(*first[i], *first[i - 1]);
  }
  Curriculum never = c;
  never.pilot.learning_rate_per_case = 0;
  EXPECT_FALSE(predict_pilot_sessions(never, 200)[1].has_value());
}

}  // namespace
}  // namespace palprig
