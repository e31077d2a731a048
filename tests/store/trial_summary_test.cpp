// `stats trials` aggregation on a store filled with known trials: counts per condition,
// participant and finger, practice left out, unanswered counted, response times, and the
// localisation view per tumor.
#include <gtest/gtest.h>

#include <cmath>
#include <map>

#include "sessions/session_setup.hpp"
#include "store/sqlite_trial_store.hpp"
#include "store/trial_summary.hpp"
#include "store/trial_summary_report.hpp"
#include "core/input_error.hpp"
#include "tests/support/support.hpp"

namespace palprig {
namespace {

using testing::ScratchDir;

// Commit every planned trial with a scripted answer: finger 1 always answered "tumor", fingers
// 2 and 3 answered correctly, the trial at position 5 timed out. Returns the plan used.
SessionPlan fill_session(TrialStore& store, const Protocol& p, const std::string& who, double rt_s) {
  SessionRequest request;
  request.participant_code = who;
  const OpenedSession s = open_session(store, p, request);
  std::vector<TrialRecord> records;
  for (const PlannedTrial& t : s.plan.trials) {
    TrialRecord r;
    r.planned = t;
    r.condition = p.conditions[static_cast<std::size_t>(t.condition)].name;
    r.mode = p.conditions[static_cast<std::size_t>(t.condition)].mode;
    const auto& c = p.combinations[static_cast<std::size_t>(t.combination)];
    r.combination_label = c.label;
    r.stimulus_kPa = c.pressure_kPa;
    r.truth = c.tumor;
    r.answered = t.position != 5;
    r.answer = {true, c.tumor[1], c.tumor[2]};
    r.finger_outcomes = score_discrimination(r.truth, r.answer);
    r.response_time_s = t.condition == 0 ? rt_s : 2 * rt_s;
    records.push_back(r);
  }
  store.commit_trials(s.session_id, records);
  return s.plan;
}

TEST(experiments_trial_summary, counts_measures_and_times) {
  ScratchDir dir;
  const Protocol p = load_protocol(testing::protocols_dir() / "discrimination_002.json");
  SqliteTrialStore store(dir / "t.db", TrialStore::Access::read_write);
  const SessionPlan plan_a = fill_session(store, p, "A", 4.0);
  const SessionPlan plan_b = fill_session(store, p, "B", 5.0);

  // Expected per condition, tallied straight from the plans and the scripted answers.
  std::map<std::string, ConfusionCounts> expected;
  std::map<std::string, int> expected_trials, expected_unanswered, rt_n;
  std::map<std::string, double> rt_sum;
  for (const SessionPlan* plan : {&plan_a, &plan_b}) {
    const double rt_s = plan == &plan_a ? 4.0 : 5.0;
    for (const PlannedTrial& t : plan->trials) {
      if (t.practice) continue;
      const std::string name = p.conditions[static_cast<std::size_t>(t.condition)].name;
      ++expected_trials[name];
      if (t.position == 5) {
        ++expected_unanswered[name];
        continue;
      }
      rt_sum[name] += t.condition == 0 ? rt_s : 2 * rt_s;
      ++rt_n[name];
      const auto& tumor = p.combinations[static_cast<std::size_t>(t.combination)].tumor;
      ConfusionCounts& c = expected[name];
      (tumor[0] ? c.tp : c.fp)++;  // finger 1: always "tumor"
      for (int f = 1; f < 3; ++f) (tumor[static_cast<std::size_t>(f)] ? c.tp : c.tn)++;
    }
  }

  SummaryOptions by_condition;
  by_condition.by = {SummaryKey::condition};
  const TrialSummary s = summarise_trials(store, by_condition);
  ASSERT_EQ(s.rows.size(), 2u);
  EXPECT_EQ(s.rows[0].key[0], "single-finger");  // rows sorted by key
  for (const SummaryRow& row : s.rows) {
    const std::string& name = row.key[0];
    EXPECT_EQ(row.trials, expected_trials[name]) << name;
    EXPECT_EQ(row.unanswered, expected_unanswered[name]) << name;
    EXPECT_EQ(row.counts.tp, expected[name].tp) << name;
    EXPECT_EQ(row.counts.fn, 0) << name;
    EXPECT_EQ(row.counts.tn, expected[name].tn) << name;
    EXPECT_EQ(row.counts.fp, expected[name].fp) << name;
    EXPECT_DOUBLE_EQ(row.measures.ppv.value, static_cast<double>(expected[name].tp) /
                                                 static_cast<double>(expected[name].tp + expected[name].fp));
    // Three-finger trials took 4 s (A) and 5 s (B), single-finger ones twice as long; the mean is
    // over answered trials, each counted once.
    EXPECT_NEAR(row.mean_rt_s, rt_sum[name] / rt_n[name], 1e-12) << name;
  }

  SummaryOptions by_finger;
  by_finger.by = {SummaryKey::finger};
  const TrialSummary f = summarise_trials(store, by_finger);
  ASSERT_EQ(f.rows.size(), 3u);
  EXPECT_EQ(f.rows[0].key[0], "1");
  EXPECT_EQ(f.rows[0].counts.tn, 0) << "finger 1 was always answered 'tumor'";
  EXPECT_EQ(f.rows[1].counts.fp + f.rows[1].counts.fn, 0) << "finger 2 was always right";
  EXPECT_DOUBLE_EQ(f.rows[1].measures.acc.value, 1.0);
  EXPECT_EQ(f.rows[2].trials, 56) << "each trial counts once per finger group";

  SummaryOptions with_practice = by_condition;
  with_practice.include_practice = true;
  std::int64_t trials_with_practice = 0;
  for (const auto& row : summarise_trials(store, with_practice).rows) trials_with_practice += row.trials;
  EXPECT_EQ(trials_with_practice, 2 * 32);

  const TrialSummary one = summarise_trials(store, SummaryOptions{});
  ASSERT_EQ(one.rows.size(), 1u);
  EXPECT_EQ(one.rows[0].trials, 56);
  EXPECT_TRUE(one.rows[0].key.empty());

  // The outputs carry the same numbers.
  const std::string csv = summary_csv(s);
  EXPECT_NE(csv.find("condition,trials,unanswered,TP,FN,TN,FP,Se,Se_lower"), std::string::npos);
  const auto json = summary_json(s, 0.95);
  EXPECT_EQ(json["rows"][0]["TP"].get<std::int64_t>(), s.rows[0].counts.tp);
  EXPECT_NE(summary_table(s).find("ACC [95% CI]"), std::string::npos);
}

TEST(experiments_trial_summary, localisation_is_scored_per_tumor) {
  ScratchDir dir;
  const Protocol p = load_protocol(testing::protocols_dir() / "localisation_002.json");
  SqliteTrialStore store(dir / "t.db", TrialStore::Access::read_write);
  // Paper 002: 9 participants found A 6 times, B 9 times, C 8 times.
  for (int i = 0; i < 9; ++i) {
    SessionRequest request;
    request.participant_code = "P" + std::to_string(i);
    const OpenedSession s = open_session(store, p, request);
    TrialRecord r;
    r.planned = s.plan.trials[0];
    r.condition = "three-finger";
    r.mode = PresentationMode::scene;
    r.answered = true;
    r.response_time_s = 60;
    const auto& t = p.localisation.cases.at(0).tumors;
    if (i < 6) r.marks.push_back({t[0].x_mm, t[0].y_mm});
    r.marks.push_back({t[1].x_mm + 3, t[1].y_mm});
    if (i != 4) r.marks.push_back({t[2].x_mm, t[2].y_mm - 2});
    if (i == 0) r.marks.push_back({5, 5});  // a false mark
    r.localisation = score_localisation(t, r.marks, p.localisation.tolerance_mm);
    store.commit_trial(s.session_id, r);
  }
  SummaryOptions by_tumor;
  by_tumor.by = {SummaryKey::tumor};
  const TrialSummary s = summarise_trials(store, by_tumor);
  // Keyed by case and tumor (these trials were stored without a case: their session's one
  // scene, phantom_abc); the false mark is the case's "elsewhere" row, not a tumor row "-".
  ASSERT_EQ(s.rows.size(), 4u);
  EXPECT_EQ(s.rows[0].key[0], "phantom_abc/A");
  EXPECT_EQ(s.rows[3].key[0], "phantom_abc/elsewhere");
  EXPECT_EQ(s.rows[3].counts.fp, 1);
  EXPECT_FALSE(s.rows[3].negatives_counted);  // no normal case: TN and Sp n/a
  EXPECT_EQ(s.rows[0].counts.tp, 6);
  EXPECT_EQ(s.rows[0].counts.fn, 3);
  EXPECT_NEAR(s.rows[0].measures.se.value * 100, 66.7, 0.05);
  EXPECT_NEAR(s.rows[1].measures.se.value * 100, 100.0, 0.05);
  EXPECT_NEAR(s.rows[2].measures.se.value * 100, 88.9, 0.05);
  EXPECT_NEAR(s.rows[0].measures.se.lower, 0.35420213558, 1e-10);  // Wilson of 6/9
}

TEST(experiments_trial_summary, unknown_grouping_word_is_refused) {
  EXPECT_EQ(parse_summary_keys("condition,finger").size(), 2u);
  EXPECT_EQ(parse_summary_keys("").size(), 0u);
  EXPECT_THROW(parse_summary_keys("condition,fingers"), InputError);
}

}  // namespace
}  // namespace palprig
