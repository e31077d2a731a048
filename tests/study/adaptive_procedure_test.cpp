// Staircases, QUEST and their interleaving: the rules step by step, exact resume from the
// stored state, and recovery of a model observer's analytic threshold over 20 seeded observers.
#include <gtest/gtest.h>

#include <cmath>
#include <numeric>

#include <boost/math/distributions/normal.hpp>

#include "study/adaptive_track.hpp"
#include "study/random_source.hpp"
#include "study/threshold_protocol.hpp"
#include "core/input_error.hpp"
#include "tests/support/support.hpp"

namespace palprig {
namespace {

double phi(double z) { return 0.5 * std::erfc(-z / std::sqrt(2.0)); }
double phi_inv(double p) { return boost::math::quantile(boost::math::normal_distribution<>(), p); }

TEST(experiments_staircase, one_up_three_down_steps_and_reversals) {
  StaircaseSettings s;
  s.up = 1;
  s.down = 3;
  s.start_kPa = 4.0;
  s.step_up_kPa = s.step_down_kPa = 1.0;
  s.halve_at_reversals = {2};
  s.min_step_kPa = 0.1;
  s.stop_reversals = 4;
  Staircase st(s);
  // Two correct: no move yet; the third goes down one step.
  EXPECT_FALSE(st.record(true));
  EXPECT_FALSE(st.record(true));
  EXPECT_DOUBLE_EQ(st.next_level_kPa(), 4.0);
  EXPECT_FALSE(st.record(true));
  EXPECT_DOUBLE_EQ(st.next_level_kPa(), 3.0);
  // One wrong: up (a reversal at 3 kPa, the level whose answer turned the track).
  EXPECT_TRUE(st.record(false));
  EXPECT_DOUBLE_EQ(st.next_level_kPa(), 4.0);
  ASSERT_EQ(st.state().reversals_kPa.size(), 1u);
  EXPECT_DOUBLE_EQ(st.state().reversals_kPa[0], 3.0);
  // Three correct: down again, second reversal at 4 kPa halves the steps: 4 - 0.5.
  st.record(true);
  st.record(true);
  EXPECT_TRUE(st.record(true));
  EXPECT_DOUBLE_EQ(st.next_level_kPa(), 3.5);
  EXPECT_EQ(st.state().halvings, 1);
  EXPECT_FALSE(st.finished());
  EXPECT_TRUE(st.record(false));  // third reversal at 3.5 -> 4.0
  st.record(true);
  st.record(true);
  EXPECT_TRUE(st.record(true));  // fourth reversal: stop
  EXPECT_TRUE(st.finished());
  EXPECT_DOUBLE_EQ(st.threshold_kPa(), (3.0 + 4.0 + 3.5 + 4.0) / 4);
}

TEST(experiments_staircase, target_probabilities_of_levitt_and_kaernbach) {
  StaircaseSettings s;
  s.up = 1;
  s.down = 2;
  EXPECT_NEAR(staircase_target_probability(s), 0.70711, 1e-5);
  s.down = 3;
  EXPECT_NEAR(staircase_target_probability(s), 0.79370, 1e-5);
  // Kaernbach's weighted 1-up/1-down: step_down / step_up = 1/3 converges on 75 %.
  s.down = 1;
  s.step_up_kPa = 3.0;
  s.step_down_kPa = 1.0;
  EXPECT_NEAR(staircase_target_probability(s), 0.75, 1e-12);
}

TEST(experiments_staircase, clamps_and_stops_after_max_trials) {
  StaircaseSettings s;
  s.start_kPa = 1.0;
  s.min_kPa = 0.5;
  s.max_kPa = 2.0;
  s.step_up_kPa = s.step_down_kPa = 1.0;
  s.max_trials = 5;
  Staircase st(s);
  for (int i = 0; i < 5; ++i) st.record(false);
  EXPECT_DOUBLE_EQ(st.next_level_kPa(), 2.0);
  EXPECT_TRUE(st.finished());
}

TEST(experiments_quest, posterior_moves_towards_the_answers_and_narrows) {
  QuestSettings q;
  q.prior_threshold_kPa = 2.0;
  Quest quest(q);
  const double first = quest.next_level_kPa();
  EXPECT_NEAR(first, 2.0, 0.05);
  EXPECT_NEAR(quest.probability_correct(2.0, 2.0), 0.82, 1e-12);
  const double sd0 = quest.estimate().sd_log10;
  for (int i = 0; i < 5; ++i) quest.record(quest.next_level_kPa(), false);
  EXPECT_GT(quest.next_level_kPa(), first);  // wrong answers: the threshold is higher
  for (int i = 0; i < 20; ++i) quest.record(quest.next_level_kPa(), true);
  const QuestEstimate e = quest.estimate();
  EXPECT_LT(e.sd_log10, sd0);
  EXPECT_LT(e.ci_low_kPa, e.threshold_kPa);
  EXPECT_GT(e.ci_high_kPa, e.threshold_kPa);
}

TEST(experiments_adaptive_track, state_round_trip_resumes_the_same_track) {
  for (AdaptiveProcedure procedure : {AdaptiveProcedure::staircase, AdaptiveProcedure::quest}) {
    TrackSpec spec;
    spec.procedure = procedure;
    spec.quest.max_trials = 40;
    AdaptiveTrack whole(spec), first(spec);
    RandomSource answers(5);
    std::vector<bool> sequence;
    sequence.reserve(40);
    for (int i = 0; i < 40; ++i) sequence.push_back(answers.uniform() < 0.8);
    for (int i = 0; i < 15; ++i) {
      whole.record(whole.next_level_kPa(), sequence[static_cast<std::size_t>(i)]);
      first.record(first.next_level_kPa(), sequence[static_cast<std::size_t>(i)]);
    }
    // "Kill" after 15 trials: a new track from the stored JSON text.
    AdaptiveTrack resumed(spec);
    resumed.restore(nlohmann::json::parse(first.state_json().dump()));
    for (int i = 15; i < 40; ++i) {
      ASSERT_DOUBLE_EQ(resumed.next_level_kPa(), whole.next_level_kPa()) << "trial " << i;
      whole.record(whole.next_level_kPa(), sequence[static_cast<std::size_t>(i)]);
      resumed.record(resumed.next_level_kPa(), sequence[static_cast<std::size_t>(i)]);
    }
    EXPECT_DOUBLE_EQ(resumed.estimate().threshold_kPa, whole.estimate().threshold_kPa);
  }
}

TEST(experiments_adaptive_track, interleaving_uses_every_open_track_and_skips_finished_ones) {
  TrackSpec a, b;
  a.name = "a";
  b.name = "b";
  a.staircase.max_trials = 3;
  std::vector<AdaptiveTrack> tracks{AdaptiveTrack(a), AdaptiveTrack(b)};
  int to_a = 0;
  for (int position = 0; position < 40; ++position) {
    const int i = choose_track(tracks, 99, position);
    ASSERT_GE(i, 0);
    EXPECT_EQ(i, choose_track(tracks, 99, position));  // the same draw on resume
    if (i == 0) ++to_a;
    tracks[static_cast<std::size_t>(i)].record(tracks[static_cast<std::size_t>(i)].next_level_kPa(), true);
  }
  EXPECT_EQ(to_a, 3);  // track a finished after its 3 trials; all the rest went to b
}

// A 2AFC observer with Gaussian noise on the difference: P(correct) = Phi(level / s).
struct TwoAfcObserver {
  double s_kPa;
  RandomSource random;
  bool answer(double level) { return random.uniform() < phi(level / s_kPa); }
};

double mean_estimate(const TrackSpec& spec, double s_kPa, int observers, double* trials_out = nullptr) {
  double sum = 0, trials = 0;
  for (int seed = 1; seed <= observers; ++seed) {
    AdaptiveTrack track(spec);
    TwoAfcObserver obs{s_kPa, RandomSource(static_cast<std::uint64_t>(seed) * 7919)};
    while (!track.finished()) {
      const double level = track.next_level_kPa();
      track.record(level, obs.answer(level));
    }
    sum += track.estimate().threshold_kPa;
    trials += track.trials();
  }
  if (trials_out) *trials_out = trials / observers;
  return sum / observers;
}

TrackSpec recovery_staircase() {
  TrackSpec spec;
  spec.procedure = AdaptiveProcedure::staircase;
  spec.staircase.up = 1;
  spec.staircase.down = 3;
  spec.staircase.start_kPa = 4.0;
  spec.staircase.step_up_kPa = spec.staircase.step_down_kPa = 0.8;
  spec.staircase.halve_at_reversals = {2};
  spec.staircase.min_step_kPa = 0.1;
  spec.staircase.stop_reversals = 20;
  spec.staircase.threshold_reversals = 14;
  spec.staircase.max_trials = 200;
  spec.staircase.max_kPa = 12;
  return spec;
}

TrackSpec recovery_quest() {
  TrackSpec spec;
  spec.procedure = AdaptiveProcedure::quest;
  spec.quest.prior_threshold_kPa = 2.0;
  spec.quest.max_trials = 60;
  spec.quest.max_kPa = 12;
  return spec;
}

TEST(experiments_adaptive_recovery, staircase_and_quest_find_the_analytic_threshold) {
  const double s = 0.8 * std::sqrt(2.0);  // one finger, noise 0.8 kPa
  const double staircase_truth = s * phi_inv(staircase_target_probability(recovery_staircase().staircase));
  const double quest_truth = s * phi_inv(recovery_quest().quest.p_threshold);
  const double st = mean_estimate(recovery_staircase(), s, 20);
  const double qu = mean_estimate(recovery_quest(), s, 20);
  EXPECT_NEAR(st / staircase_truth, 1.0, 0.10) << st << " vs " << staircase_truth;
  EXPECT_NEAR(qu / quest_truth, 1.0, 0.10) << qu << " vs " << quest_truth;
  // Doubling the noise doubles the estimate.
  EXPECT_NEAR(mean_estimate(recovery_staircase(), 2 * s, 20) / st, 2.0, 0.30);
  EXPECT_NEAR(mean_estimate(recovery_quest(), 2 * s, 20) / qu, 2.0, 0.30);
}

TEST(experiments_threshold_protocol, shipped_files_load_and_bad_fields_are_named) {
  const auto a = load_threshold_protocol(testing::protocols_dir() / "threshold_1up3down.json");
  EXPECT_EQ(a.tracks.size(), 2u);
  EXPECT_EQ(a.tracks[0].procedure, AdaptiveProcedure::staircase);
  const auto b = load_threshold_protocol(testing::protocols_dir() / "threshold_quest.json");
  EXPECT_EQ(b.tracks[1].procedure, AdaptiveProcedure::quest);
  EXPECT_EQ(b.tracks[1].fingers, FingerSet::three);

  nlohmann::json doc = a.snapshot;
  doc["tracks"][0]["staircase"]["stepup_kPa"] = 1;
  try {
    parse_threshold_protocol(doc, "p.json");
    FAIL() << "typo accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("tracks[0].staircase"), std::string::npos) << e.what();
  }
  doc = a.snapshot;
  doc["threshold"]["reference_kPa"] = 95;
  EXPECT_THROW(parse_threshold_protocol(doc, "p.json"), InputError);
  doc = a.snapshot;
  doc["tracks"][1]["name"] = doc["tracks"][0]["name"];
  EXPECT_THROW(parse_threshold_protocol(doc, "p.json"), InputError);
}

}  // namespace
}  // namespace palprig
