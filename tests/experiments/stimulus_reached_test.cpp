// When the stimulus reached the fingers (TrialRecord::stimulus_reached_s): the first crossing of
// half a commanded level by a carrying finger's monitor, interpolated between the loop's samples,
// against a plant whose crossing time is known in closed form (a first-order lag); and a real
// simulated session on the simulated rig storing it.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "experiments/trial_runner.hpp"
#include "store/sqlite_trial_store.hpp"
#include "tests/support/process_support.hpp"
#include "tests/support/support.hpp"

namespace palprig {
namespace {

class ReachedCollector final : public RunnerListener {
 public:
  void on_trial_completed(const TrialRecord& t) override { trials.push_back(t); }
  std::vector<TrialRecord> trials;
};

// Each channel follows its target as a first-order lag of time constant tau_s from the moment
// the target changed: a step from 0 to L crosses L/2 at tau ln 2 after the command.
class LaggingOutput final : public StimulusOutput {
 public:
  explicit LaggingOutput(double tau_s) : tau_s_(tau_s) {}
  void hold(const ChannelPressures& target_kPa, double t_s) override { set(target_kPa, t_s); }
  void palpate(const Scene&, InputSource&, double) override {}
  void vent(double t_s) override { set({}, t_s); }
  ChannelPressures service(double t_s) override {
    ChannelPressures now{};
    for (std::size_t f = 0; f < kFingerCount; ++f) now[f] = value(f, t_s);
    return now;
  }
  std::string describe() const override { return "lagging"; }

 private:
  double value(std::size_t f, double t_s) const {
    const double dt = std::max(0.0, t_s - since_s_[f]);
    return target_[f] + (from_[f] - target_[f]) * std::exp(-dt / tau_s_);
  }
  void set(const ChannelPressures& target, double t_s) {
    for (std::size_t f = 0; f < kFingerCount; ++f) {
      if (target[f] == target_[f]) continue;
      from_[f] = value(f, t_s);
      target_[f] = target[f];
      since_s_[f] = t_s;
    }
  }
  double tau_s_;
  ChannelPressures target_{}, from_{};
  std::array<double, kFingerCount> since_s_{};
};

Protocol protocol_with(const char* combination, bool answer_during_stimulus = true) {
  auto doc = nlohmann::json::parse(R"({
    "version": 1, "name": "reached", "task": "discrimination", "levels_kPa": [0, 10, 30],
    "combinations": {"how_chosen": "test", "list_kPa": []},
    "conditions": [{"name": "three", "mode": "simultaneous"}, {"name": "one", "mode": "sequential"}],
    "randomisation": {"scheme": "fixed"},
    "timing": {"max_present_s": 5, "sequential_step_s": 1, "sequential_gap_s": 0.5,
               "response_timeout_s": 3, "inter_trial_s": 1}
  })");
  doc["combinations"]["list_kPa"] = nlohmann::json::array({nlohmann::json::parse(combination)});
  doc["timing"]["answer_during_stimulus"] = answer_during_stimulus;
  return parse_protocol(doc, "reached.json", ".");
}

int first_reached_of_condition(const SessionPlan& plan, int condition) {
  int start = 0;
  while (plan.trials[static_cast<std::size_t>(start)].condition != condition) ++start;
  return start;
}

// One trial of `condition` from onset 1 s, serviced every 5 ms (the session loop's period) up
// to `answer_s`, answered then.
TrialRecord run_one(const Protocol& p, int condition, double answer_s, double tau_s = 0.05) {
  const SessionPlan plan = make_session_plan(p, 1, 1);
  LaggingOutput out(tau_s);
  ReachedCollector c;
  TrialRunner r(p, plan, first_reached_of_condition(plan, condition), out, c);
  r.advance(0.995);  // a vented sample before the onset, as the loop gives
  r.begin(1.0);
  for (int i = 0; 1.0 + i * 0.005 < answer_s; ++i) r.advance(1.0 + i * 0.005);
  EXPECT_TRUE(r.respond(Response{{false, true, false}, {}, std::nullopt, std::nullopt}, answer_s));
  EXPECT_EQ(c.trials.size(), 1u);
  return c.trials.at(0);
}

TEST(experiments_stimulus_reached, simultaneous_reaches_half_the_level_at_tau_ln2) {
  const TrialRecord t = run_one(protocol_with("[10, 30, 10]"), 0, 2.0);
  EXPECT_DOUBLE_EQ(t.onset_s, 1.0);
  // Both carrying fingers cross half their level at the same moment on a linear plant.
  EXPECT_NEAR(t.stimulus_reached_s, 1.0 + 0.05 * std::log(2.0), 0.5e-3);
  EXPECT_NEAR(t.response_time_s, 1.0, 1e-12);
  EXPECT_NEAR(response_time_from_reached_s(t), 1.0 - 0.05 * std::log(2.0), 0.5e-3);
}

TEST(experiments_stimulus_reached, interpolation_beats_the_loop_period) {
  // A slower plant (tau 80 ms): the crossing falls between two 5 ms samples; the interpolated
  // time is within a fraction of a period of the exact one, where taking the sample would be up
  // to 5 ms late.
  const TrialRecord t = run_one(protocol_with("[30, 30, 30]"), 0, 2.0, 0.08);
  EXPECT_NEAR(t.stimulus_reached_s, 1.0 + 0.08 * std::log(2.0), 0.3e-3);
}

TEST(experiments_stimulus_reached, no_level_above_zero_is_never_reached) {
  const TrialRecord t = run_one(protocol_with("[0, 0, 0]"), 0, 2.0);
  EXPECT_TRUE(std::isnan(t.stimulus_reached_s)) << "0/0/0: nothing to reach, stored NULL";
  EXPECT_TRUE(std::isnan(response_time_from_reached_s(t)));
  EXPECT_NEAR(t.response_time_s, 1.0, 1e-12);
}

TEST(experiments_stimulus_reached, sequence_is_reached_by_the_first_finger_that_carries_a_level) {
  // Finger 1 carries 0 kPa; finger 2's step starts after step 1 s + gap 0.5 s.
  const TrialRecord t = run_one(protocol_with("[0, 30, 0]", false), 1, 6.0);
  EXPECT_NEAR(t.stimulus_reached_s, 1.0 + 1.5 + 0.05 * std::log(2.0), 0.5e-3);
  EXPECT_NEAR(response_time_from_reached_s(t), 6.0 - t.stimulus_reached_s, 1e-12);
}

TEST(experiments_stimulus_reached, an_answer_before_the_stimulus_arrived_has_no_reached_time) {
  // Answered 20 ms after the command; the plant reaches half at 35 ms.
  const TrialRecord t = run_one(protocol_with("[30, 30, 30]"), 0, 1.02);
  EXPECT_TRUE(std::isnan(t.stimulus_reached_s));
  EXPECT_NEAR(t.response_time_s, 0.02, 1e-12);
}

TEST(experiments_stimulus_reached, a_presentation_again_after_a_pause_is_timed_afresh) {
  const Protocol p = protocol_with("[30, 30, 30]");
  const SessionPlan plan = make_session_plan(p, 1, 1);
  LaggingOutput out(0.05);
  ReachedCollector c;
  TrialRunner r(p, plan, 0, out, c);
  r.begin(1.0);
  for (double t = 1.0; t < 1.5; t += 0.005) r.advance(t);
  r.pause(1.5);
  for (double t = 1.5; t < 3.0; t += 0.005) r.advance(t);  // vented
  r.begin(3.0);
  for (double t = 3.0; t < 4.0; t += 0.005) r.advance(t);
  ASSERT_TRUE(r.respond(Response{{true, true, true}, {}, std::nullopt, std::nullopt}, 4.0));
  ASSERT_EQ(c.trials.size(), 1u);
  EXPECT_DOUBLE_EQ(c.trials[0].onset_s, 3.0);
  EXPECT_NEAR(c.trials[0].stimulus_reached_s, 3.0 + 0.05 * std::log(2.0), 0.5e-3);
}

TEST(experiments_stimulus_reached, a_simulated_session_on_the_simulated_rig_stores_when_the_stimulus_arrived) {
  testing::ScratchDir dir;
  const auto db = (dir / "sim.db").string();
  const auto run = testing::run_palprig({"experiment", "run", "--protocol",
                                         (testing::protocols_dir() / "discrimination_002.json").string(),
                                         "--participant", "sim:4", "--db", db, "--quiet"});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  SqliteTrialStore reader(db, TrialStore::Access::read_only);
  const auto timing =
      nlohmann::json::parse(std::ifstream(testing::protocols_dir() / "discrimination_002.json"))["timing"];
  const double step_s = timing["sequential_step_s"].get<double>(), gap_s = timing["sequential_gap_s"].get<double>();
  int reached = 0, none_carried = 0;
  for (const StoredTrial& t : reader.read_trials(true)) {
    const bool carries =
        (t.stimulus_kPa[0].value_or(0) > 0 || t.stimulus_kPa[1].value_or(0) > 0 || t.stimulus_kPa[2].value_or(0) > 0);
    if (!carries) {
      ++none_carried;
      EXPECT_FALSE(t.stimulus_reached_s.has_value()) << t.position;
      continue;
    }
    if (!t.stimulus_reached_s) continue;  // answered before the stimulus arrived
    ++reached;
    // The simulated regulator lags the command (slew limit, 50 ms first-order lag and dead
    // time): half the level arrives tens of milliseconds after the finger's stimulus was
    // commanded on, not at it. In a sequence that is the first carrying finger's step.
    int first = 0;
    while (t.stimulus_kPa[static_cast<std::size_t>(first)].value_or(0) <= 0) ++first;
    const double commanded_s = t.onset_s + (t.mode == "sequential" ? first * (step_s + gap_s) : 0.0);
    const double lag_s = *t.stimulus_reached_s - commanded_s;
    EXPECT_GT(lag_s, 0.005) << t.position;
    EXPECT_LT(lag_s, 0.3) << t.position;
  }
  EXPECT_GT(reached, 10);
  EXPECT_GT(none_carried, 0) << "the protocol has 0/0/0 trials";
}

}  // namespace
}  // namespace palprig
