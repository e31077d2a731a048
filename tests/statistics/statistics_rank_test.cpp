// Mann-Whitney U and Wilcoxon signed-rank tests. Oracles: statistics_oracles.py (exact p by
// enumerating every assignment or by exact integer Gaussian-binomial polynomials; normal p by
// mpmath), R's wilcox.test documentation example, and the figures of papers 000 and 003.
#include <gtest/gtest.h>

#include <vector>

#include "statistics/rank_distributions.hpp"
#include "statistics/statistics_error.hpp"
#include "statistics/statistics_rank_tests.hpp"

namespace palprig::stats {
namespace {

TEST(experiments_ranks, average_ranks_and_tie_term) {
  const std::vector<double> v = {3, 1, 4, 1, 5, 9, 2, 6, 5, 3};
  const Ranking r = rank_average(v);
  const std::vector<double> expected = {4.5, 1.5, 6, 1.5, 7.5, 10, 3, 9, 7.5, 4.5};
  EXPECT_EQ(r.ranks, expected);
  EXPECT_TRUE(r.has_ties);
  EXPECT_DOUBLE_EQ(r.tie_term, 3 * 6.0);  // three pairs, each 2^3 - 2
}

TEST(experiments_ranks, exact_distributions_sum_to_one_and_are_symmetric) {
  const MannWhitneyExact u(4, 5);
  EXPECT_DOUBLE_EQ(u.cdf(20), 1.0);
  EXPECT_NEAR(u.cdf(0), 1.0 / 126.0, 1e-15);  // C(9,4) = 126 orderings, one with U = 0
  for (int k = 0; k <= 20; ++k) EXPECT_NEAR(u.cdf(k), u.upper_tail(20 - k), 1e-15);
  const SignedRankExact v(9);
  EXPECT_NEAR(v.cdf(0), 1.0 / 512.0, 1e-15);
  EXPECT_NEAR(v.upper_tail(45), 1.0 / 512.0, 1e-15);
  EXPECT_DOUBLE_EQ(v.cdf(45), 1.0);
}

TEST(experiments_mann_whitney, small_untied_sample_uses_the_exact_distribution) {
  const std::vector<double> a = {1.1, 2.2, 3.3, 4.4};
  const std::vector<double> b = {5.5, 6.6, 2.5, 7.7, 0.5};
  const MannWhitneyResult r = mann_whitney(a, b);
  EXPECT_TRUE(r.exact);
  EXPECT_DOUBLE_EQ(r.u1, 6.0);
  EXPECT_DOUBLE_EQ(r.u2, 14.0);
  EXPECT_DOUBLE_EQ(r.u, 6.0);
  EXPECT_NEAR(r.p, 26.0 / 63.0, 1e-14);  // enumeration of all 126 assignments
}

TEST(experiments_mann_whitney, paper_000_groups_of_17_and_23_with_u_106) {
  // Paper 000: U = 106.0, p < .05, r = Z / sqrt(N) = -.39 (groups of 23 and 17). Untied data
  // with exactly that U: the smaller group holds ranks 1..12, 27, 37..40 of 40.
  std::vector<double> g2, g1;
  for (int rank = 1; rank <= 40; ++rank) {
    const bool in_g2 = rank <= 12 || rank == 27 || rank >= 37;
    (in_g2 ? g2 : g1).push_back(rank * 0.5);
  }
  ASSERT_EQ(g2.size(), 17u);
  ASSERT_EQ(g1.size(), 23u);
  const MannWhitneyResult r = mann_whitney(g2, g1);
  EXPECT_DOUBLE_EQ(r.u, 106.0);
  EXPECT_DOUBLE_EQ(r.u1, 106.0);
  EXPECT_TRUE(r.exact);  // both groups under 50, no ties: R's rule
  EXPECT_NEAR(r.p, 0.013678055253489948, 1e-13);
  EXPECT_LT(r.p, 0.05);
  EXPECT_NEAR(r.z, -2.4350076087702242, 1e-12);
  EXPECT_NEAR(r.effect_r, -0.38500850817770525, 1e-12);
  EXPECT_NEAR(r.effect_r, -0.39, 0.005);

  RankOptions spss;  // SPSS: normal approximation without continuity correction
  spss.method = RankMethod::normal;
  spss.continuity_correction = false;
  const MannWhitneyResult s = mann_whitney(g2, g1, spss);
  EXPECT_FALSE(s.exact);
  EXPECT_NEAR(s.z, -2.4486874267970232, 1e-12);
  EXPECT_NEAR(s.effect_r, -0.38717147732477101, 1e-12);
  EXPECT_NEAR(s.effect_r, -0.39, 0.005);
}

TEST(experiments_mann_whitney, ties_use_the_corrected_normal_approximation) {
  const std::vector<double> a = {1, 2, 2, 3, 4};
  const std::vector<double> b = {3, 3, 4, 5, 5, 5};
  const MannWhitneyResult r = mann_whitney(a, b);
  EXPECT_FALSE(r.exact);
  EXPECT_TRUE(r.ties);
  EXPECT_DOUBLE_EQ(r.u1, 3.5);
  EXPECT_NEAR(r.z, -2.0555770054650897, 1e-12);
  EXPECT_NEAR(r.p, 0.039823306111970543, 1e-13);
  EXPECT_NEAR(r.effect_r, -0.61977978680091216, 1e-12);
  RankOptions exact;
  exact.method = RankMethod::exact;
  EXPECT_THROW(mann_whitney(a, b, exact), StatisticsError);
}

TEST(experiments_mann_whitney, refuses_empty_groups_and_all_tied_data) {
  const std::vector<double> a = {1, 2};
  const std::vector<double> empty;
  const std::vector<double> same = {4, 4, 4};
  EXPECT_THROW(mann_whitney(a, empty), StatisticsError);
  EXPECT_THROW(mann_whitney(same, same), StatisticsError);
}

TEST(experiments_wilcoxon, paired_example_of_r_wilcox_test_is_exact) {
  // R's ?wilcox.test: Hollander & Wolfe's depression scale, V = 40 (one-sided p 0.01953).
  const std::vector<double> x = {1.83, 0.50, 1.62, 2.48, 1.68, 1.88, 1.55, 3.06, 1.30};
  const std::vector<double> y = {0.878, 0.647, 0.598, 2.05, 1.06, 1.29, 1.06, 3.14, 1.29};
  const SignedRankResult r = wilcoxon_signed_rank_paired(x, y);
  EXPECT_TRUE(r.exact);
  EXPECT_DOUBLE_EQ(r.v, 40.0);
  EXPECT_NEAR(r.p, 0.0390625, 1e-15);  // 2 * 10 / 512, by enumeration
  EXPECT_EQ(r.n_used, 9u);
}

TEST(experiments_wilcoxon, likert_item_against_the_neutral_point) {
  // Paper 003, item 6: median 4.00 (IQR 4.00;4.00), p = 0.003 on ten surgeons' 5-point
  // answers against the neutral 3. Nine 4s and one 3 reproduce it: the 3 is a zero difference
  // (dropped), the nine ties force the normal approximation.
  const std::vector<double> answers = {3, 4, 4, 4, 4, 4, 4, 4, 4, 4};
  const SignedRankResult r = wilcoxon_signed_rank(answers, 3.0);
  EXPECT_FALSE(r.exact);
  EXPECT_EQ(r.zeros, 1u);
  EXPECT_EQ(r.n_used, 9u);
  EXPECT_DOUBLE_EQ(r.v, 45.0);
  EXPECT_NEAR(r.z, 2.9333333333333333, 1e-12);
  EXPECT_NEAR(r.p, 0.0033534364549463227, 1e-13);
  EXPECT_NEAR(r.p, 0.003, 0.0005);
  EXPECT_DOUBLE_EQ(r.median_difference, 1.0);

  RankOptions spss;
  spss.continuity_correction = false;
  const SignedRankResult s = wilcoxon_signed_rank(answers, 3.0, spss);
  EXPECT_NEAR(s.z, 3.0, 1e-12);
  EXPECT_NEAR(s.p, 0.0026997960632601891, 1e-13);
  EXPECT_NEAR(s.p, 0.003, 0.0005);
}

TEST(experiments_wilcoxon, refuses_all_zero_differences) {
  const std::vector<double> neutral = {3, 3, 3};
  EXPECT_THROW(wilcoxon_signed_rank(neutral, 3.0), StatisticsError);
  const std::vector<double> x = {1, 2};
  const std::vector<double> y = {1};
  EXPECT_THROW(wilcoxon_signed_rank_paired(x, y), StatisticsError);
}

}  // namespace
}  // namespace palprig::stats
