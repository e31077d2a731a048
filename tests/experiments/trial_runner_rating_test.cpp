// The runner's stimulus end (the after-stimulus response time) and the confidence rating,
// driven by hand on a fake clock with a recording output.
#include <gtest/gtest.h>

#include <cmath>

#include "experiments/trial_runner.hpp"
#include "tests/support/recording_output.hpp"

namespace palprig {
namespace {

using testing::RecordingOutput;

class RatingCollector final : public RunnerListener {
 public:
  void on_trial_completed(const TrialRecord& t) override { trials.push_back(t); }
  std::vector<TrialRecord> trials;
};

// Onsets at 1 s; simultaneous: 5 s at most; sequential: 3 x 1 s + 2 x 0.5 s = 4 s.
Protocol rated_protocol(bool with_confidence) {
  auto doc = nlohmann::json::parse(R"({
    "version": 1, "name": "rated", "task": "discrimination", "levels_kPa": [0, 30],
    "combinations": {"how_chosen": "test", "list_kPa": [[0, 30, 0]]},
    "conditions": [{"name": "three", "mode": "simultaneous"}, {"name": "one", "mode": "sequential"}],
    "randomisation": {"scheme": "fixed"},
    "timing": {"max_present_s": 5, "sequential_step_s": 1, "sequential_gap_s": 0.5,
               "response_timeout_s": 3, "inter_trial_s": 1}
  })");
  if (with_confidence) doc["confidence"] = {{"levels", 4}, {"labels", {"guess", "unsure", "fairly sure", "sure"}}};
  return parse_protocol(doc, "rated.json", ".");
}

int first_rated_of_condition(const SessionPlan& plan, int condition) {
  int start = 0;
  while (plan.trials[static_cast<std::size_t>(start)].condition != condition) ++start;
  return start;
}

// Runs one trial of `condition` from onset 1 s, answers at `answer_s` (advancing in 10 ms steps
// up to it), returns what the runner recorded.
TrialRecord run_one(const Protocol& p, int condition, double answer_s, const Response& answer) {
  const SessionPlan plan = make_session_plan(p, 1, 1);
  RecordingOutput out;
  RatingCollector c;
  TrialRunner r(p, plan, first_rated_of_condition(plan, condition), out, c);
  r.begin(1.0);
  for (double t = 1.0; t < answer_s; t += 0.01) r.advance(t);
  EXPECT_TRUE(r.respond(answer, answer_s));
  EXPECT_EQ(c.trials.size(), 1u);
  return c.trials.at(0);
}

TEST(experiments_trial_runner_rating, simultaneous_stimulus_ends_at_onset_plus_max_present) {
  const Protocol p = rated_protocol(false);
  const TrialRecord t = run_one(p, 0, 7.5, Response{{false, true, false}, {}, std::nullopt, std::nullopt});
  EXPECT_DOUBLE_EQ(t.onset_s, 1.0);
  EXPECT_DOUBLE_EQ(t.stimulus_end_s, 1.0 + 5.0);
  EXPECT_DOUBLE_EQ(t.response_time_s, 6.5);  // paper 002's measure, from onset
  EXPECT_NEAR(response_time_after_stimulus_s(t), 1.5, 1e-12);
  EXPECT_FALSE(t.confidence.has_value()) << "not asked: stored NULL";
}

TEST(experiments_trial_runner_rating, sequential_stimulus_ends_after_the_whole_sequence) {
  const Protocol p = rated_protocol(false);
  const TrialRecord t = run_one(p, 1, 6.25, Response{{false, true, false}, {}, std::nullopt, std::nullopt});
  EXPECT_EQ(t.mode, PresentationMode::sequential);
  EXPECT_DOUBLE_EQ(t.stimulus_end_s, 1.0 + 4.0);
  EXPECT_NEAR(response_time_after_stimulus_s(t), 1.25, 1e-12);
  EXPECT_NEAR(t.response_time_s, 5.25, 1e-12);
}

TEST(experiments_trial_runner_rating, coarse_steps_record_the_planned_end_not_the_late_pass) {
  const Protocol p = rated_protocol(false);
  const SessionPlan plan = make_session_plan(p, 1, 1);
  RecordingOutput out;
  RatingCollector c;
  TrialRunner r(p, plan, 0, out, c);
  r.begin(1.0);
  r.advance(6.8);  // noticed 0.8 s late
  ASSERT_EQ(r.state(), RunnerState::respond);
  ASSERT_TRUE(r.respond(Response{{false, true, false}, {}, std::nullopt, std::nullopt}, 7.0));
  EXPECT_DOUBLE_EQ(c.trials.at(0).stimulus_end_s, 6.0);
  EXPECT_NEAR(response_time_after_stimulus_s(c.trials.at(0)), 1.0, 1e-12);
}

TEST(experiments_trial_runner_rating, an_answer_during_the_stimulus_ends_it_and_gives_zero) {
  const Protocol p = rated_protocol(false);
  const TrialRecord t =
      run_one(p, 0, 2.5, Response{{false, true, false}, {}, std::nullopt, std::nullopt});  // simultaneous
  EXPECT_DOUBLE_EQ(t.stimulus_end_s, 2.5);
  EXPECT_DOUBLE_EQ(response_time_after_stimulus_s(t), 0.0);
  EXPECT_DOUBLE_EQ(t.response_time_s, 1.5);
}

// A sequence is answered after its last finger; a fixed-length simultaneous stimulus
// (timing.answer_during_stimulus false) after max_present_s. Both runner and GUI follow
// answers_during_presentation.
TEST(experiments_trial_runner_rating, answers_are_taken_during_the_stimulus_only_where_the_protocol_says) {
  Protocol p = rated_protocol(false);
  EXPECT_TRUE(answers_during_presentation(p, PresentationMode::simultaneous));
  EXPECT_FALSE(answers_during_presentation(p, PresentationMode::sequential));
  EXPECT_TRUE(answers_during_presentation(p, PresentationMode::scene));
  for (bool during : {true, false}) {
    p.timing.answer_during_stimulus = during;
    for (int condition : {0, 1}) {
      const SessionPlan plan = make_session_plan(p, 1, 1);
      RecordingOutput out;
      RatingCollector c;
      TrialRunner r(p, plan, first_rated_of_condition(plan, condition), out, c);
      r.begin(1.0);
      r.advance(2.0);
      ASSERT_EQ(r.state(), RunnerState::present);
      const bool taken = condition == 0 && during;
      EXPECT_EQ(r.takes_answers(), taken) << "condition " << condition << " during " << during;
      EXPECT_EQ(r.respond(Response{}, 2.0), taken);
      if (taken) continue;
      EXPECT_TRUE(c.trials.empty());
      r.advance(1.0 + 5.0 + 0.01);  // past either stimulus: respond
      ASSERT_EQ(r.state(), RunnerState::respond);
      EXPECT_TRUE(r.takes_answers());
      EXPECT_TRUE(r.respond(Response{}, 7.0));
      ASSERT_EQ(c.trials.size(), 1u);
    }
  }
}

TEST(experiments_trial_runner_rating, unanswered_trial_has_no_after_stimulus_time) {
  const Protocol p = rated_protocol(true);
  const SessionPlan plan = make_session_plan(p, 1, 1);
  RecordingOutput out;
  RatingCollector c;
  TrialRunner r(p, plan, 0, out, c);
  r.begin(0.0);
  for (double t = 0.0; t <= 8.5; t += 0.1) r.advance(t);  // 5 s stimulus + 3 s timeout
  ASSERT_EQ(c.trials.size(), 1u);
  EXPECT_FALSE(c.trials[0].answered);
  EXPECT_DOUBLE_EQ(c.trials[0].stimulus_end_s, 5.0);
  EXPECT_TRUE(std::isnan(response_time_after_stimulus_s(c.trials[0])));
  EXPECT_FALSE(c.trials[0].confidence.has_value());
}

TEST(experiments_trial_runner_rating, confidence_passes_through) {
  const Protocol p = rated_protocol(true);
  for (int rating = 1; rating <= 4; ++rating) {
    const TrialRecord t = run_one(p, 0, 7.0, Response{{false, true, false}, {}, rating, std::nullopt});
    ASSERT_TRUE(t.confidence.has_value());
    EXPECT_EQ(*t.confidence, rating);
  }
}

TEST(experiments_trial_runner_rating, out_of_range_confidence_is_refused_and_never_stored) {
  const Protocol p = rated_protocol(true);
  const SessionPlan plan = make_session_plan(p, 1, 1);
  RecordingOutput out;
  RatingCollector c;
  TrialRunner r(p, plan, 0, out, c);
  r.begin(0.0);
  r.advance(6.0);
  for (int bad : {0, 5, -1, 99}) {
    EXPECT_FALSE(r.respond(Response{{false, true, false}, {}, bad, std::nullopt}, 6.5)) << bad;
    EXPECT_EQ(r.state(), RunnerState::respond) << "the trial still awaits a valid answer";
  }
  EXPECT_TRUE(c.trials.empty());
  EXPECT_TRUE(r.respond(Response{{false, true, false}, {}, 3, std::nullopt}, 7.0));
  ASSERT_EQ(c.trials.size(), 1u);
  EXPECT_EQ(c.trials[0].confidence, 3);
}

TEST(experiments_trial_runner_rating, a_rating_the_protocol_does_not_ask_for_is_refused) {
  const Protocol p = rated_protocol(false);
  const SessionPlan plan = make_session_plan(p, 1, 1);
  RecordingOutput out;
  RatingCollector c;
  TrialRunner r(p, plan, 0, out, c);
  r.begin(0.0);
  EXPECT_FALSE(r.respond(Response{{false, true, false}, {}, 2, std::nullopt}, 1.0));
  EXPECT_TRUE(c.trials.empty());
}

TEST(experiments_trial_runner_rating, protocol_confidence_field_is_checked) {
  auto base = nlohmann::json::parse(R"({
    "version": 1, "name": "rated", "task": "discrimination", "levels_kPa": [0, 30],
    "combinations": {"how_chosen": "test", "list_kPa": [[0, 30, 0]]},
    "conditions": [{"name": "three", "mode": "simultaneous"}]})");
  const auto refused = [&](const nlohmann::json& confidence, const std::string& field) {
    auto doc = base;
    doc["confidence"] = confidence;
    try {
      parse_protocol(doc, "rated.json", ".");
      ADD_FAILURE() << "accepted " << confidence.dump();
    } catch (const InputError& e) {
      EXPECT_EQ(e.file(), "rated.json");
      EXPECT_NE(e.where().find(field), std::string::npos) << e.what();
    }
  };
  refused({{"levels", 1}}, "confidence.levels");
  refused({{"levels", 10}}, "confidence.levels");
  refused({{"levels", 3}, {"labels", {"a", "b"}}}, "confidence.labels");
  refused({{"levels", 2}, {"labels", {"a", ""}}}, "confidence.labels[1]");
  refused({{"levels", 2}, {"scale", 5}}, "confidence");
  EXPECT_FALSE(parse_protocol(base, "rated.json", ".").confidence.asked());
  auto ok = base;
  ok["confidence"] = {{"levels", 3}};
  const Protocol p = parse_protocol(ok, "rated.json", ".");
  EXPECT_EQ(p.confidence.levels, 3);
  EXPECT_TRUE(p.confidence.labels.empty());
}

}  // namespace
}  // namespace palprig

namespace palprig {
namespace {

// The rating comes after the finger answer: the response time ends with the finger answer
// (Response::given_at_s), and the response timeout waits while the rating is awaited
// (hold_timeout), so a finger answer given in time is never lost to a slow rating.
TEST(experiments_trial_runner_rating, a_slow_rating_neither_lengthens_the_response_time_nor_loses_the_answer) {
  const Protocol p = rated_protocol(true);
  const SessionPlan plan = make_session_plan(p, 1, 1);
  RecordingOutput out;
  RatingCollector c;
  TrialRunner r(p, plan, first_rated_of_condition(plan, 1), out, c);  // sequential: 4 s, then respond
  r.begin(0.0);
  r.advance(4.0);
  ASSERT_EQ(r.state(), RunnerState::respond);
  // Finger answer at 5 s; the rating takes until 12 s, past the 3 s response timeout.
  r.hold_timeout(true);
  for (double t = 5.0; t < 12.0; t += 0.5) r.advance(t);
  EXPECT_EQ(r.state(), RunnerState::respond) << "no timeout while the rating is awaited";
  r.hold_timeout(false);
  Response answer{{false, true, false}, {}, 3, std::nullopt};
  answer.given_at_s = 5.0;
  ASSERT_TRUE(r.respond(answer, 12.0));
  ASSERT_EQ(c.trials.size(), 1u);
  EXPECT_DOUBLE_EQ(c.trials[0].response_time_s, 5.0);
  EXPECT_DOUBLE_EQ(response_time_after_stimulus_s(c.trials[0]), 1.0);
  EXPECT_EQ(c.trials[0].confidence, 3);
  // A given_at_s before this presentation's onset (a stale clock) is clamped to the onset.
  TrialRunner again(p, plan, first_rated_of_condition(plan, 0), out, c);
  again.begin(20.0);
  Response early;
  early.given_at_s = 1.0;
  early.confidence = 1;
  ASSERT_TRUE(again.respond(early, 21.0));
  EXPECT_DOUBLE_EQ(c.trials.back().response_time_s, 0.0);
}

}  // namespace
}  // namespace palprig
