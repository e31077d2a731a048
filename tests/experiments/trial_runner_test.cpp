// The trial runner state machine, driven by hand on a fake clock with a recording output.
#include <gtest/gtest.h>

#include <cmath>

#include "experiments/trial_runner.hpp"
#include "tests/support/recording_output.hpp"

namespace palprig {
namespace {

using testing::RecordingOutput;

class Collector final : public RunnerListener {
 public:
  void on_event(const RunnerEvent& e) override {
    if (e.kind == RunnerEvent::Kind::state_changed) states.push_back(e.state);
  }
  void on_trial_completed(const TrialRecord& t) override { trials.push_back(t); }
  std::vector<RunnerState> states;
  std::vector<TrialRecord> trials;
};

Protocol small_protocol() {
  auto doc = nlohmann::json::parse(R"({
    "version": 1, "name": "runner", "task": "discrimination", "levels_kPa": [0, 10, 30],
    "combinations": {"how_chosen": "test", "list_kPa": [[0, 30, 0], [10, 10, 10]]},
    "conditions": [{"name": "three", "mode": "simultaneous"}, {"name": "one", "mode": "sequential"}],
    "randomisation": {"scheme": "fixed"},
    "timing": {"max_present_s": 5, "sequential_step_s": 1, "sequential_gap_s": 0.5,
               "response_timeout_s": 3, "inter_trial_s": 1, "break_s": 2}
  })");
  return parse_protocol(doc, "runner.json", ".");
}

TEST(experiments_trial_runner, simultaneous_trial_answered_during_presentation) {
  const Protocol p = small_protocol();
  const SessionPlan plan = make_session_plan(p, 1, 1);
  RecordingOutput out;
  Collector c;
  TrialRunner r(p, plan, 0, out, c);
  EXPECT_EQ(r.state(), RunnerState::ready);
  r.advance(0.0);
  EXPECT_EQ(r.state(), RunnerState::ready);  // waits for the participant
  r.begin(1.0);
  EXPECT_EQ(r.state(), RunnerState::present);
  ASSERT_FALSE(out.calls.empty());
  EXPECT_EQ(out.calls.back().what, "hold");
  EXPECT_EQ(out.calls.back().kPa, (ChannelPressures{0, 30, 0}));
  for (double t = 1.0; t < 3.4; t += 0.1) r.advance(t);
  Response answer;
  answer.tumor_under = {false, true, true};
  EXPECT_TRUE(r.respond(answer, 3.5));
  EXPECT_EQ(r.state(), RunnerState::inter_trial);
  EXPECT_EQ(out.calls.back().what, "vent");
  ASSERT_EQ(c.trials.size(), 1u);
  const TrialRecord& t = c.trials[0];
  EXPECT_DOUBLE_EQ(t.response_time_s, 2.5);
  EXPECT_TRUE(t.answered);
  EXPECT_EQ(t.finger_outcomes[0], Outcome::tn);
  EXPECT_EQ(t.finger_outcomes[1], Outcome::tp);
  EXPECT_EQ(t.finger_outcomes[2], Outcome::fp);
  EXPECT_DOUBLE_EQ(t.felt_kPa[1], 30.0);
  EXPECT_FALSE(r.respond(answer, 3.6)) << "a second answer is ignored";
  // The inter-trial pause, then the next trial starts by itself.
  r.advance(4.4);
  EXPECT_EQ(r.state(), RunnerState::inter_trial);
  r.advance(4.5);
  EXPECT_EQ(r.state(), RunnerState::present);
  EXPECT_EQ(r.next_position(), 1);
  EXPECT_EQ(out.calls.back().kPa, (ChannelPressures{10, 10, 10}));
}

TEST(experiments_trial_runner, timeout_records_an_unanswered_trial) {
  const Protocol p = small_protocol();
  const SessionPlan plan = make_session_plan(p, 1, 1);
  RecordingOutput out;
  Collector c;
  TrialRunner r(p, plan, 0, out, c);
  r.begin(0.0);
  r.advance(5.0);  // max_present_s: the stimulus ends, the answer is still awaited
  EXPECT_EQ(r.state(), RunnerState::respond);
  EXPECT_EQ(out.calls.back().what, "vent");
  r.advance(7.9);
  EXPECT_EQ(r.state(), RunnerState::respond);
  r.advance(8.0);  // response_timeout_s after the stimulus ended
  EXPECT_EQ(r.state(), RunnerState::inter_trial);
  ASSERT_EQ(c.trials.size(), 1u);
  EXPECT_FALSE(c.trials[0].answered);
  EXPECT_TRUE(std::isnan(c.trials[0].response_time_s));
}

TEST(experiments_trial_runner, sequential_mode_presents_one_finger_at_a_time) {
  const Protocol p = small_protocol();
  SessionPlan plan = make_session_plan(p, 1, 1);
  // Jump to the first trial of the sequential condition.
  int start = 0;
  while (plan.trials[static_cast<std::size_t>(start)].condition != 1) ++start;
  RecordingOutput out;
  Collector c;
  TrialRunner r(p, plan, start, out, c);
  r.begin(0.0);
  auto held = [&] { return out.calls.back().kPa; };
  r.advance(0.5);
  EXPECT_EQ(r.active_fingers(), (FingerFlags{true, false, false}));
  EXPECT_EQ(held(), (ChannelPressures{0, 0, 0}));  // finger 1 of 0/30/0 carries 0 kPa
  r.advance(1.2);                                  // gap
  EXPECT_EQ(r.active_fingers(), (FingerFlags{false, false, false}));
  r.advance(1.6);
  EXPECT_EQ(r.active_fingers(), (FingerFlags{false, true, false}));
  EXPECT_EQ(held(), (ChannelPressures{0, 30, 0}));
  r.advance(3.2);
  EXPECT_EQ(r.active_fingers(), (FingerFlags{false, false, true}));
  EXPECT_EQ(r.state(), RunnerState::present);
  r.advance(4.0);  // 3 steps of 1 s + 2 gaps of 0.5 s
  EXPECT_EQ(r.state(), RunnerState::respond);
  Response answer;
  answer.tumor_under = {false, true, false};
  EXPECT_TRUE(r.respond(answer, 5.0));
  ASSERT_EQ(c.trials.size(), 1u);
  EXPECT_DOUBLE_EQ(c.trials[0].response_time_s, 5.0);
  EXPECT_DOUBLE_EQ(c.trials[0].felt_kPa[1], 30.0);  // finger 2 felt while it was on
  EXPECT_EQ(c.trials[0].mode, PresentationMode::sequential);
}

TEST(experiments_trial_runner, break_between_blocks_then_ready_then_done) {
  const Protocol p = small_protocol();
  const SessionPlan plan = make_session_plan(p, 1, 1);
  ASSERT_EQ(plan.trials.size(), 4u);
  ASSERT_TRUE(plan.trials[1].break_after);
  RecordingOutput out;
  Collector c;
  TrialRunner r(p, plan, 0, out, c);
  Response none;
  double t = 0;
  r.begin(t);
  r.respond(none, t += 1);
  r.advance(t += 1);  // next trial
  r.respond(none, t += 1);
  r.advance(t += 1);  // inter-trial over: break
  EXPECT_EQ(r.state(), RunnerState::rest);
  r.advance(t += 1.9);
  EXPECT_EQ(r.state(), RunnerState::rest);
  r.advance(t += 0.1);
  EXPECT_EQ(r.state(), RunnerState::ready);
  r.advance(t += 10);
  EXPECT_EQ(r.state(), RunnerState::ready);  // waits as long as the participant needs
  r.begin(t);
  r.advance(t += 4);  // the second block is sequential: answered after its last finger (4 s)
  r.respond(none, t += 0.1);
  r.advance(t += 1);
  r.advance(t += 4);
  r.respond(none, t += 0.1);
  r.advance(t += 1);
  EXPECT_EQ(r.state(), RunnerState::done);
  EXPECT_EQ(c.trials.size(), 4u);
  EXPECT_EQ(c.states.back(), RunnerState::done);
  EXPECT_EQ(r.current_trial(), nullptr);
}

TEST(experiments_trial_runner, resume_starts_at_the_given_position_and_abort_vents) {
  const Protocol p = small_protocol();
  const SessionPlan plan = make_session_plan(p, 1, 1);
  RecordingOutput out;
  Collector c;
  TrialRunner r(p, plan, 3, out, c);
  r.begin(0);
  EXPECT_EQ(r.current_trial()->position, 3);
  r.abort(1);
  EXPECT_EQ(r.state(), RunnerState::done);
  EXPECT_EQ(out.calls.back().what, "vent");
  EXPECT_TRUE(c.trials.empty()) << "an aborted trial is not recorded";
  TrialRunner finished(p, plan, 4, out, c);
  EXPECT_EQ(finished.state(), RunnerState::done);
}

TEST(experiments_trial_runner, pause_vents_and_holds_the_trial_in_progress) {
  const Protocol p = small_protocol();
  const SessionPlan plan = make_session_plan(p, 1, 1);
  RecordingOutput out;
  Collector c;
  TrialRunner r(p, plan, 0, out, c);
  r.begin(0);
  r.advance(0.5);
  ASSERT_EQ(r.state(), RunnerState::present);
  r.pause(0.6);
  EXPECT_EQ(r.state(), RunnerState::ready);
  EXPECT_EQ(out.calls.back().what, "vent");
  EXPECT_EQ(r.next_position(), 0) << "the interrupted trial is held";
  EXPECT_TRUE(c.trials.empty()) << "an interrupted trial is not recorded";
  r.advance(5.0);
  EXPECT_EQ(r.state(), RunnerState::ready) << "a paused session waits";
  r.begin(10.0);
  EXPECT_EQ(r.state(), RunnerState::present);
  EXPECT_EQ(out.calls.back().kPa, (ChannelPressures{0, 30, 0})) << "the held trial again from its start";
  ASSERT_TRUE(r.respond(Response{}, 11.0));
  ASSERT_EQ(c.trials.size(), 1u);
  EXPECT_DOUBLE_EQ(c.trials[0].response_time_s, 1.0) << "timed from the new onset";
  EXPECT_EQ(r.state(), RunnerState::inter_trial);
  r.pause(11.2);  // in the inter-trial pause: the committed trial is not repeated
  EXPECT_EQ(r.state(), RunnerState::ready);
  EXPECT_EQ(r.next_position(), 1);
  EXPECT_EQ(out.calls.back().what, "vent");
}

// A pause while the runner waits for the participant's go-ahead is acknowledged like any other
// (a front end enables Continue on that state event) and holds the same trial.
TEST(experiments_trial_runner, a_pause_while_waiting_for_ready_is_acknowledged) {
  const Protocol p = small_protocol();
  const SessionPlan plan = make_session_plan(p, 1, 1);
  RecordingOutput out;
  Collector c;
  TrialRunner r(p, plan, 0, out, c);
  ASSERT_EQ(r.state(), RunnerState::ready);
  const std::size_t states_before = c.states.size();
  r.pause(0.2);
  EXPECT_EQ(r.state(), RunnerState::ready);
  EXPECT_EQ(out.calls.back().what, "vent");
  ASSERT_EQ(c.states.size(), states_before + 1) << "the pause is announced";
  EXPECT_EQ(c.states.back(), RunnerState::ready);
  EXPECT_EQ(r.next_position(), 0);
}

}  // namespace
}  // namespace palprig
