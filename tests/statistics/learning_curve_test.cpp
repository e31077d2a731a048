// A trainee's learning curve per measure (statistics/learning_curve.hpp).
#include "statistics/learning_curve.hpp"

#include <gtest/gtest.h>

namespace palprig::stats {
namespace {

TEST(LearningCurve, ProportionsCarryWilsonIntervalsAndSessionsWithoutCasesAreUndefined) {
  // 6 of 9 (paper 002's tumor A): 0.6667 [0.3542, 0.8794], as `stats proportion --k 6 --n 9`.
  const auto curve = proportion_curve({{6, 9}, {0, 0}, {4, 4}});
  ASSERT_EQ(curve.size(), 3u);
  EXPECT_EQ(curve[0].session, 1);
  EXPECT_TRUE(curve[0].defined);
  EXPECT_NEAR(curve[0].value, 6.0 / 9.0, 1e-12);
  EXPECT_NEAR(curve[0].lower, 0.354202, 1e-6);
  EXPECT_NEAR(curve[0].upper, 0.879416, 1e-6);
  EXPECT_FALSE(curve[1].defined);
  EXPECT_DOUBLE_EQ(curve[2].value, 1.0);
}

TEST(LearningCurve, MeansCarryStudentIntervals) {
  // 20, 30, 40 s: mean 30, sd 10, t(0.975, 2) = 4.302653: 30 +/- 24.8414.
  const auto curve = mean_curve({{20, 30, 40}, {}, {12}});
  EXPECT_NEAR(curve[0].value, 30.0, 1e-12);
  EXPECT_NEAR(curve[0].lower, 30.0 - 24.841377, 1e-5);
  EXPECT_NEAR(curve[0].upper, 30.0 + 24.841377, 1e-5);
  EXPECT_FALSE(curve[1].defined);
  EXPECT_TRUE(curve[2].defined);
  EXPECT_DOUBLE_EQ(curve[2].lower, 12.0);  // one value: no interval
}

TEST(LearningCurve, ProficiencyIsTheFirstRunOfConsecutiveSessionsMeetingTheBenchmark) {
  const auto curve = proportion_curve({{5, 10}, {9, 10}, {7, 10}, {9, 10}, {10, 10}, {9, 10}});
  EXPECT_EQ(first_run_meeting(curve, 0.9, Better::higher, 2), 4);
  EXPECT_EQ(first_run_meeting(curve, 0.9, Better::higher, 1), 2);
  EXPECT_EQ(first_run_meeting(curve, 0.9, Better::higher, 4), std::nullopt);
  EXPECT_EQ(first_run_meeting(curve, 0.6, Better::lower, 1), 1);
}

}  // namespace
}  // namespace palprig::stats
