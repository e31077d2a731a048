// Scoring (paper 002): per-finger TP/FN/TN/FP, localisation hits within outline + tolerance,
// and the measures with Wilson intervals.
#include <gtest/gtest.h>

#include <cmath>

#include "statistics/diagnostic_measures.hpp"
#include "study/scoring.hpp"

namespace palprig {
namespace {

TEST(experiments_scoring, each_finger_value_is_scored_on_its_own) {
  const auto o = score_discrimination({false, true, true}, {true, true, false});
  EXPECT_EQ(o[0], Outcome::fp);
  EXPECT_EQ(o[1], Outcome::tp);
  EXPECT_EQ(o[2], Outcome::fn);
  const auto none = score_discrimination({false, false, false}, {false, false, false});
  for (Outcome x : none) EXPECT_EQ(x, Outcome::tn);
  for (Outcome x : {Outcome::tp, Outcome::fn, Outcome::tn, Outcome::fp})
    EXPECT_EQ(outcome_from_string(to_string(x)), x);
  EXPECT_FALSE(outcome_from_string("XX").has_value());
}

TEST(experiments_scoring, localisation_hit_is_within_outline_plus_tolerance) {
  const std::vector<TumorTruth> tumors = {{"A", 40, 40, 4}, {"B", 110, 50, 10}};
  // 8.9 mm from A: inside 4 + 5; 9.1 mm: outside. One mark far from everything.
  const std::vector<Mark> marks = {{48.9, 40}, {110, 60.5}, {0, 0}};
  const LocalisationScore s = score_localisation(tumors, marks, 5.0);
  ASSERT_EQ(s.tumors.size(), 2u);
  EXPECT_TRUE(s.tumors[0].hit);
  EXPECT_NEAR(s.tumors[0].nearest_mark_mm, 8.9, 1e-9);
  EXPECT_TRUE(s.tumors[1].hit);
  EXPECT_EQ(s.false_marks, 1);
  EXPECT_EQ(s.mark_tumor, (std::vector<int>{0, 1, -1}));

  const LocalisationScore tight = score_localisation(tumors, {{49.1, 40}}, 5.0);
  EXPECT_FALSE(tight.tumors[0].hit);
  EXPECT_EQ(tight.false_marks, 1);
  const LocalisationScore nothing = score_localisation(tumors, {}, 5.0);
  EXPECT_FALSE(nothing.tumors[1].hit);
  EXPECT_LT(nothing.tumors[1].nearest_mark_mm, 0.0);
}

TEST(experiments_scoring, measures_follow_paper_002_equations) {
  ConfusionCounts c;
  c.tp = 157;
  c.fn = 11;
  c.tn = 331;
  c.fp = 5;
  const DiagnosticMeasures d = diagnostic_measures(c);
  EXPECT_DOUBLE_EQ(d.se.value, 157.0 / 168.0);
  EXPECT_DOUBLE_EQ(d.sp.value, 331.0 / 336.0);
  EXPECT_DOUBLE_EQ(d.ppv.value, 157.0 / 162.0);
  EXPECT_DOUBLE_EQ(d.acc.value, 488.0 / 504.0);
  // ACC of 488/504 carries the Wilson interval of statistics_oracles.py.
  EXPECT_NEAR(d.acc.lower, 0.949057614167, 1e-11);
  EXPECT_NEAR(d.acc.upper, 0.980366307023, 1e-11);

  ConfusionCounts only_negatives;
  only_negatives.tn = 4;
  const DiagnosticMeasures n = diagnostic_measures(only_negatives);
  EXPECT_FALSE(n.se.defined);
  EXPECT_FALSE(n.ppv.defined);
  EXPECT_TRUE(n.sp.defined);
  EXPECT_DOUBLE_EQ(n.sp.value, 1.0);
}

}  // namespace
}  // namespace palprig
