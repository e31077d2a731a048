// describe() and Pearson's r against statistics_oracles.py and paper 000's correlation table.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "statistics/statistics_correlation.hpp"
#include "statistics/statistics_describe.hpp"
#include "statistics/statistics_error.hpp"

namespace palprig::stats {
namespace {

TEST(experiments_describe, type_7_quartiles_like_r_and_numpy) {
  const std::vector<double> v = {12, 4, 2, 9, 5, 4, 7, 10};
  const Description d = describe(v);
  EXPECT_EQ(d.n, 8u);
  EXPECT_DOUBLE_EQ(d.mean, 6.625);
  EXPECT_NEAR(d.sd, 3.4615231989895514, 1e-14);
  EXPECT_DOUBLE_EQ(d.q1, 4.0);
  EXPECT_DOUBLE_EQ(d.median, 6.0);
  EXPECT_DOUBLE_EQ(d.q3, 9.25);
  EXPECT_DOUBLE_EQ(d.iqr, 5.25);
  EXPECT_DOUBLE_EQ(d.min, 2.0);
  EXPECT_DOUBLE_EQ(d.max, 12.0);
}

TEST(experiments_describe, type_6_quartiles_like_spss) {
  const std::vector<double> v = {12, 4, 2, 9, 5, 4, 7, 10};
  const Description d = describe(v, QuantileRule::r_type6);
  EXPECT_DOUBLE_EQ(d.q1, 4.0);
  EXPECT_DOUBLE_EQ(d.median, 6.0);
  EXPECT_DOUBLE_EQ(d.q3, 9.75);
  // Paper 003 item 1 style: median 3.50 (3.00;4.00) from ten 5-point answers.
  const std::vector<double> likert = {2, 3, 3, 3, 3, 4, 4, 4, 4, 5};
  const Description l = describe(likert, QuantileRule::r_type6);
  EXPECT_DOUBLE_EQ(l.median, 3.5);
  EXPECT_DOUBLE_EQ(l.q1, 3.0);
  EXPECT_DOUBLE_EQ(l.q3, 4.0);
}

TEST(experiments_describe, single_value_and_refusals) {
  const std::vector<double> one = {7.5};
  const Description d = describe(one);
  EXPECT_DOUBLE_EQ(d.median, 7.5);
  EXPECT_DOUBLE_EQ(d.iqr, 0.0);
  EXPECT_TRUE(std::isnan(d.sd));
  const std::vector<double> empty;
  EXPECT_THROW(describe(empty), StatisticsError);
  const std::vector<double> inf = {1.0, INFINITY};
  EXPECT_THROW(describe(inf), StatisticsError);
}

TEST(experiments_pearson, matches_independent_values) {
  const std::vector<double> x = {1, 2, 3, 4, 5, 6};
  const std::vector<double> y = {2.1, 3.9, 6.2, 7.8, 10.1, 12.2};
  const PearsonResult r = pearson(x, y);
  EXPECT_NEAR(r.r, 0.99910493248081797, 1e-14);
  EXPECT_NEAR(r.t, 47.23842450802101, 1e-9);
  EXPECT_DOUBLE_EQ(r.df, 4.0);
  EXPECT_NEAR(r.p, 1.2013602560215735e-6, 1e-15);
  EXPECT_NEAR(r.ci_lower, 0.99142828430379825, 1e-12);
  EXPECT_NEAR(r.ci_upper, 0.99990685767036873, 1e-12);

  const std::vector<double> noisy = {3.0, 1.0, 4.0, 1.5, 5.0, 2.0};
  const PearsonResult n = pearson(x, noisy);
  EXPECT_NEAR(n.r, 0.1560797945143416, 1e-14);
  EXPECT_NEAR(n.t, 0.31603274424928059, 1e-12);
  EXPECT_NEAR(n.p, 0.76778143053760966, 1e-12);
  EXPECT_NEAR(n.ci_lower, -0.75055273637012202, 1e-12);
  EXPECT_NEAR(n.ci_upper, 0.85885176490741603, 1e-12);
}

TEST(experiments_pearson, paper_000_table_4_p_values_from_rounded_r) {
  // Published r to 2 decimals and p to 3: the reported p must lie within our p for r +/- 0.005,
  // widened by the p rounding.
  struct Row {
    double r;
    std::size_t n;
    double p;
  };
  const Row rows[] = {{-0.32, 40, .044}, {0.32, 38, .048}, {-0.37, 38, .021}, {0.32, 38, .047}, {0.48, 38, .002},
                      {0.34, 38, .037},  {0.37, 38, .023}, {0.45, 49, .001},  {0.36, 38, .026}};
  for (const Row& row : rows) {
    const double magnitude = std::fabs(row.r);
    const double p_low = pearson_from_r(magnitude + 0.005, row.n).p;
    const double p_high = pearson_from_r(magnitude - 0.005, row.n).p;
    EXPECT_LE(p_low - 0.0005, row.p) << row.r << " n " << row.n;
    EXPECT_GE(p_high + 0.0005, row.p) << row.r << " n " << row.n;
  }
}

TEST(experiments_pearson, refuses_constant_columns_and_short_data) {
  const std::vector<double> x = {1, 2, 3};
  const std::vector<double> constant = {5, 5, 5};
  const std::vector<double> two = {1, 2};
  EXPECT_THROW(pearson(x, constant), StatisticsError);
  EXPECT_THROW(pearson(two, two), StatisticsError);
  EXPECT_THROW(pearson(x, two), StatisticsError);
}

}  // namespace
}  // namespace palprig::stats
