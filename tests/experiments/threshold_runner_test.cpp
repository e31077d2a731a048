// The threshold session's trial mechanics on a recording output (the fingers feel exactly what
// is held): which fingers and pressures each interval carries, 2AFC interval order, yes/no
// scoring, unanswered trials leaving the track alone, and a stop venting at once.
#include <gtest/gtest.h>

#include <atomic>
#include <optional>
#include <set>

#include "experiments/threshold_session.hpp"
#include "tests/support/recording_output.hpp"

namespace palprig {
namespace {

// Answers from the held pressures it felt: 2AFC picks the interval felt stronger, yes/no says
// yes when the second was stronger; `silent` never answers.
class ScriptedParticipant final : public ThresholdParticipant {
 public:
  explicit ScriptedParticipant(bool silent = false) : silent_(silent) {}
  bool ready(double) override { return true; }
  void trial_started(const ThresholdTrialInfo& t, double) override {
    info = t;
    felt_ = {};
  }
  void interval_started(int, double) override {}
  void feel(int interval, const FeltSample& s) override {
    for (std::size_t f = 0; f < kFingerCount; ++f)
      felt_[static_cast<std::size_t>(interval)] = std::max(felt_[static_cast<std::size_t>(interval)], s.felt_kPa[f]);
  }
  std::optional<int> answer(double) override {
    if (silent_) return std::nullopt;
    return felt_[1] > felt_[0] ? 1 : 0;
  }
  ThresholdTrialInfo info;

 private:
  bool silent_;
  std::array<double, 2> felt_{};
};

ThresholdProtocol protocol(ThresholdMethod method) {
  ThresholdProtocol p = load_threshold_protocol(testing::protocols_dir() / "threshold_1up3down.json");
  p.method = method;
  p.timing = {0.2, 0.1, 0.5, 0.05};
  for (auto& t : p.tracks) t.staircase.max_trials = 12;
  return p;
}

TEST(experiments_threshold_runner, intervals_carry_reference_and_increment_on_the_tracks_fingers) {
  for (ThresholdMethod method : {ThresholdMethod::two_afc, ThresholdMethod::yes_no}) {
    const ThresholdProtocol p = protocol(method);
    std::vector<AdaptiveTrack> tracks;
    for (const auto& s : p.tracks) tracks.emplace_back(s);
    testing::RecordingOutput output;
    ScriptedParticipant participant;
    SimulatedClock clock;
    ThresholdSessionOptions o;
    o.seed = 7;
    std::vector<ThresholdTrialRecord> records;
    o.on_trial = [&](const ThresholdTrialRecord& r) { records.push_back(r); };
    const auto result = run_threshold_session(p, tracks, output, participant, clock, o);
    ASSERT_TRUE(result.completed);
    ASSERT_EQ(records.size(), 24u);
    std::set<int> signal_intervals;
    for (const auto& r : records) {
      signal_intervals.insert(r.signal_interval);
      EXPECT_TRUE(r.answered);
      EXPECT_TRUE(r.correct) << "a noiseless participant always finds the increment";
      if (method == ThresholdMethod::yes_no) {
        EXPECT_EQ(r.signal_interval, 1);
      }
      EXPECT_NEAR(r.felt_kPa[static_cast<std::size_t>(r.signal_interval)], p.reference_kPa + r.level_kPa, 1e-9);
      EXPECT_NEAR(r.felt_kPa[static_cast<std::size_t>(1 - r.signal_interval)], p.reference_kPa, 1e-9);
    }
    if (method == ThresholdMethod::two_afc) {
      EXPECT_EQ(signal_intervals.size(), 2u);
    }
    // Every hold: only the track's fingers pressurised, never above reference + max level.
    int one_finger_holds = 0;
    for (const auto& c : output.calls) {
      if (c.what != "hold") continue;
      const bool only_finger2 = c.kPa[0] == 0 && c.kPa[1] > 0 && c.kPa[2] == 0;
      const bool all = c.kPa[0] > 0 && c.kPa[1] == c.kPa[0] && c.kPa[2] == c.kPa[0];
      EXPECT_TRUE(only_finger2 || all);
      one_finger_holds += only_finger2 ? 1 : 0;
      for (double v : c.kPa) EXPECT_LE(v, p.max_pressure_kPa());
    }
    EXPECT_EQ(one_finger_holds, 24);  // 12 one-finger trials x 2 intervals
    EXPECT_EQ(output.calls.back().what, "vent");
    // Always correct: each track went down 4 times (12 trials / 3) from 2 kPa by 0.5 kPa.
    for (const auto& t : tracks) EXPECT_NEAR(t.next_level_kPa(), 0.0, 1e-9);
  }
}

TEST(experiments_threshold_runner, unanswered_trials_leave_the_track_and_a_stop_vents) {
  const ThresholdProtocol p = protocol(ThresholdMethod::two_afc);
  std::vector<AdaptiveTrack> tracks;
  for (const auto& s : p.tracks) tracks.emplace_back(s);
  testing::RecordingOutput output;
  ScriptedParticipant silent(true);
  SimulatedClock clock;
  RunControl stop;
  ThresholdSessionOptions o;
  o.control = &stop;
  std::vector<ThresholdTrialRecord> records;
  o.on_trial = [&](const ThresholdTrialRecord& r) {
    records.push_back(r);
    if (records.size() == 5) stop.request_stop();
  };
  const auto result = run_threshold_session(p, tracks, output, silent, clock, o);
  EXPECT_TRUE(result.stopped);
  ASSERT_EQ(records.size(), 5u);
  for (const auto& r : records) {
    EXPECT_FALSE(r.answered);
    EXPECT_DOUBLE_EQ(r.level_kPa, 2.0);  // the start level again and again
  }
  for (const auto& t : tracks) EXPECT_EQ(t.trials(), 0);
  EXPECT_EQ(output.calls.back().what, "vent");
}

}  // namespace
}  // namespace palprig
