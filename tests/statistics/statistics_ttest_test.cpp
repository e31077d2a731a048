// t-tests against independent values (statistics_oracles.py: mpmath incomplete beta) and the
// published figures of papers 002 and 000.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "statistics/statistics_error.hpp"
#include "statistics/statistics_ttest.hpp"

namespace palprig::stats {
namespace {

const std::vector<double> kX = {5.1, 4.9, 6.2, 5.8, 6.0, 5.5, 5.3};
const std::vector<double> kY = {4.2, 4.8, 4.5, 5.0, 4.1, 4.6};

TEST(experiments_ttest, student_matches_independent_values) {
  const TTestResult r = two_sample_t_test(kX, kY, /*equal_variance=*/true);
  EXPECT_EQ(r.kind, TTestKind::student);
  EXPECT_NEAR(r.t, 4.2872645411485274, 1e-12);
  EXPECT_DOUBLE_EQ(r.df, 11.0);
  EXPECT_NEAR(r.p, 0.0012830163137908882, 1e-14);
  EXPECT_NEAR(r.ci_lower, 0.49125699808841337, 1e-10);
  EXPECT_NEAR(r.ci_upper, 1.5277906209592057, 1e-10);
}

TEST(experiments_ttest, welch_matches_independent_values) {
  const TTestResult r = two_sample_t_test(kX, kY, /*equal_variance=*/false);
  EXPECT_EQ(r.kind, TTestKind::welch);
  EXPECT_NEAR(r.t, 4.4031188701488077, 1e-12);
  EXPECT_NEAR(r.df, 10.734521849964823, 1e-10);
  EXPECT_NEAR(r.p, 0.0011211547037753527, 1e-14);
  EXPECT_NEAR(r.ci_lower, 0.50336673196516215, 1e-10);
  EXPECT_NEAR(r.ci_upper, 1.5156808870824569, 1e-10);
}

TEST(experiments_ttest, paired_and_one_sample_match_independent_values) {
  const std::vector<double> before = {12.1, 14.3, 11.8, 13.5, 12.9, 15.0, 13.2, 12.4};
  const std::vector<double> after = {11.4, 13.9, 11.9, 12.6, 12.1, 14.2, 12.8, 12.0};
  const TTestResult paired = paired_t_test(before, after);
  EXPECT_NEAR(paired.t, 4.617672520411778, 1e-11);
  EXPECT_DOUBLE_EQ(paired.df, 7.0);
  EXPECT_NEAR(paired.p, 0.0024328194622708035, 1e-13);

  const TTestResult one = one_sample_t_test(kX, 5.0);
  EXPECT_NEAR(one.t, 2.9979245933178368, 1e-12);
  EXPECT_NEAR(one.p, 0.024072594394770685, 1e-13);
}

TEST(experiments_ttest, paper_002_response_times_from_rounded_summaries) {
  // 4.6 +/- 2.3 s (three fingers) vs 8.3 +/- 2.9 s (one finger), 168 trials each, Student's
  // test, p = 7.42e-32 on the raw data. The summaries are rounded to 0.1 s, so the published p
  // must lie between the p of the most and the least favourable rounding.
  const TTestResult at = two_sample_t_test_from_summary(4.6, 2.3, 168, 8.3, 2.9, 168, true);
  EXPECT_NEAR(at.p, 2.1921377335088088e-31, 1e-40);
  const double p_small = two_sample_t_test_from_summary(4.55, 2.25, 168, 8.35, 2.85, 168, true).p;
  const double p_large = two_sample_t_test_from_summary(4.65, 2.35, 168, 8.25, 2.95, 168, true).p;
  EXPECT_NEAR(p_small, 1.0865590931928693e-33, 1e-42);
  EXPECT_NEAR(p_large, 3.3705308059306371e-29, 1e-38);
  EXPECT_LT(p_small, 7.42e-32);
  EXPECT_GT(p_large, 7.42e-32);
  EXPECT_DOUBLE_EQ(at.df, 334.0);
  EXPECT_LT(at.t, 0.0);
}

TEST(experiments_ttest, paper_000_paired_t_table_3) {
  // Published t (rounded to the digits shown: half_step is half its last digit) and two-sided p
  // to 3 decimals: the reported p must lie within our p over the t rounding interval, widened
  // by the p rounding.
  struct Row {
    double t, half_step, df, p;
  };
  const Row rows[] = {{-2.615, 5e-4, 22, .016}, {-2.955, 5e-4, 22, .007}, {-1.779, 5e-4, 22, .089},
                      {-1.351, 5e-4, 22, .191}, {-3.7, 5e-2, 16, .002},   {-3.816, 5e-4, 16, .002},
                      {-0.347, 5e-4, 16, .733}, {-1.247, 5e-4, 16, .230}};
  for (const Row& row : rows) {
    const double p_low = two_sided_t_p(std::fabs(row.t) + row.half_step, row.df);
    const double p_high = two_sided_t_p(std::fabs(row.t) - row.half_step, row.df);
    EXPECT_LE(p_low - 0.0005, row.p) << row.t;
    EXPECT_GE(p_high + 0.0005, row.p) << row.t;
  }
  // And to full precision against mpmath.
  EXPECT_NEAR(two_sided_t_p(-2.615, 22), 0.015810820215038407, 1e-14);
  EXPECT_NEAR(two_sided_t_p(-1.351, 22), 0.1904273846140652, 1e-13);
  EXPECT_NEAR(two_sided_t_p(-3.7, 16), 0.0019423664304346924, 1e-14);
}

TEST(experiments_ttest, refuses_what_it_cannot_compute) {
  const std::vector<double> one = {1.0};
  const std::vector<double> constant = {2.0, 2.0, 2.0};
  EXPECT_THROW(two_sample_t_test(one, kY, false), StatisticsError);
  EXPECT_THROW(two_sample_t_test(constant, constant, true), StatisticsError);
  EXPECT_THROW(paired_t_test(kX, kY), StatisticsError);  // unequal lengths
  EXPECT_THROW(one_sample_t_test(constant, 1.0), StatisticsError);
  const std::vector<double> with_nan = {1.0, std::numeric_limits<double>::quiet_NaN()};
  EXPECT_THROW(one_sample_t_test(with_nan, 0.0), StatisticsError);
}

}  // namespace
}  // namespace palprig::stats
