// The CUSUM and LC-CUSUM charts of a trainee's cases (statistics/learning_cusum.hpp):
// the values and signal points of a sequence worked by hand from the published formulas, and the
// decision limits checked by Monte Carlo against the run lengths they promise.
#include "statistics/learning_cusum.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "statistics/statistics_error.hpp"

namespace palprig::stats {
namespace {

// Worked by hand (a calculator, not this library) for p0 = 0.1, p1 = 0.3:
//   CUSUM (Page; Biau et al. 2007): failure ln(0.3/0.1) = 1.098612, success ln(0.7/0.9) = -0.251314
//   LC-CUSUM (Biau et al. 2008):    success ln(0.9/0.7) = 0.251314, failure ln(0.1/0.3) = -1.098612
constexpr CusumRates kRates{0.1, 0.3};

TEST(LearningCusum, WeightsAreThePublishedLogLikelihoodRatios) {
  const CusumWeights c = cusum_weights(CusumChart::monitoring, kRates);
  EXPECT_NEAR(c.failure, 1.098612, 1e-6);
  EXPECT_NEAR(c.success, -0.251314, 1e-6);
  const CusumWeights lc = cusum_weights(CusumChart::learning, kRates);
  EXPECT_NEAR(lc.success, 0.251314, 1e-6);
  EXPECT_NEAR(lc.failure, -1.098612, 1e-6);
}

TEST(LearningCusum, BernoulliCusumEqualsTheHandComputedSequenceAndRestartsAfterEachAlarm) {
  // F S S F F | S F F | F S S S with h = 2: C_t = max(0, C_{t-1} + W_t), alarm when C_t >= 2.
  const std::vector<bool> failures{true, false, false, true, true, false, true, true, true, false, false, false};
  const double expected[] = {1.098612, 0.847298, 0.595983, 1.694596, 2.793208, 0.0,
                             1.098612, 2.197225, 1.098612, 0.847298, 0.595983, 0.344669};
  const auto points = cusum_series(CusumChart::monitoring, kRates, 2.0, failures);
  ASSERT_EQ(points.size(), failures.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    EXPECT_EQ(points[i].case_number, static_cast<int>(i + 1));
    EXPECT_NEAR(points[i].value, expected[i], 1e-6) << "case " << i + 1;
    EXPECT_EQ(points[i].signal, i == 4 || i == 7) << "case " << i + 1;
  }
}

TEST(LearningCusum, LcCusumEqualsTheHandComputedSequenceAndDeclaresCompetenceOnce) {
  // F S S S F then ten successes with h = 1.5: S_t = max(0, S_{t-1} + W_t); competence is declared
  // at the first S_t >= 1.5 (case 11), the chart goes on without another signal.
  std::vector<bool> failures(15, false);
  failures[0] = failures[4] = true;
  const double expected[] = {0.0,      0.251314, 0.502629, 0.753943, 0.0,      0.251314, 0.502629, 0.753943,
                             1.005258, 1.256572, 1.507887, 1.759201, 2.010515, 2.261830, 2.513144};
  const auto points = cusum_series(CusumChart::learning, kRates, 1.5, failures);
  ASSERT_EQ(points.size(), failures.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    EXPECT_NEAR(points[i].value, expected[i], 1e-6) << "case " << i + 1;
    EXPECT_EQ(points[i].signal, i == 10) << "case " << i + 1;
  }
}

TEST(LearningCusum, RatesAndErrorsOutsideTheirRangesAreRefused) {
  EXPECT_THROW(cusum_weights(CusumChart::learning, {0.3, 0.1}), StatisticsError);
  EXPECT_THROW(cusum_weights(CusumChart::learning, {0.0, 0.1}), StatisticsError);
  EXPECT_THROW(cusum_limit(CusumChart::learning, kRates, {0.0, 0.2, 50}), StatisticsError);
  EXPECT_THROW(cusum_limit(CusumChart::learning, kRates, {0.05, 0.2, 0}), StatisticsError);
}

// The chart's first signal (run length) for a trainee failing at `rate`, capped at `cap`
// (cap + 1: no signal within it).
int simulated_run_length(CusumChart chart, double limit, double rate, int cap, std::mt19937_64& rng) {
  std::bernoulli_distribution fail(rate);
  std::vector<bool> cases;
  cases.reserve(static_cast<std::size_t>(cap));
  for (int i = 0; i < cap; ++i) cases.push_back(fail(rng));
  for (const CusumPoint& p : cusum_series(chart, kRates, limit, cases)) {
    if (p.signal) return p.case_number;
  }
  return cap + 1;
}

// Monte Carlo with the chart's own arithmetic (cusum_series): the share of false signals within
// the horizon, the share of true ones, and the mean cases to a true signal agree with what the
// limit promises within four standard errors.
void check_limit_by_simulation(CusumChart chart, double good_rate, double bad_rate) {
  const CusumErrors errors{0.05, 0.2, 60};
  const CusumLimit limit = cusum_limit(chart, kRates, errors);
  SCOPED_TRACE(std::string(to_string(chart)) + " h = " + std::to_string(limit.limit));
  EXPECT_LE(limit.false_signal_within, errors.alpha);
  // The smallest such limit (to the 0.01 it is quoted to): one step lower breaks alpha.
  const std::vector<double> lower = run_length_cdf(chart, kRates, limit.limit - 0.01, bad_rate, errors.horizon_cases);
  EXPECT_GT(lower.back(), errors.alpha);
  ASSERT_TRUE(limit.mean_cases_to_true_signal.has_value());
  ASSERT_TRUE(limit.cases_for_power.has_value());

  std::mt19937_64 rng(20260427);
  constexpr int kRuns = 20000;
  int false_within = 0, true_within = 0, by_power = 0;
  double sum = 0, sum2 = 0;
  for (int i = 0; i < kRuns; ++i) {
    false_within +=
        simulated_run_length(chart, limit.limit, bad_rate, errors.horizon_cases, rng) <= errors.horizon_cases;
    const int rl = simulated_run_length(chart, limit.limit, good_rate, 1500, rng);
    ASSERT_LE(rl, 1500);
    true_within += rl <= errors.horizon_cases;
    by_power += rl <= *limit.cases_for_power;
    sum += rl;
    sum2 += static_cast<double>(rl) * rl;
  }
  const auto share_se = [](double p) { return std::sqrt(p * (1 - p) / kRuns); };
  EXPECT_NEAR(false_within / double(kRuns), limit.false_signal_within, 4 * share_se(limit.false_signal_within) + 1e-4);
  EXPECT_NEAR(true_within / double(kRuns), limit.true_signal_within, 4 * share_se(limit.true_signal_within));
  const double mean = sum / kRuns, sd = std::sqrt(sum2 / kRuns - mean * mean);
  EXPECT_NEAR(mean, *limit.mean_cases_to_true_signal, 4 * sd / std::sqrt(double(kRuns)));
  // Within cases_for_power a true signal came in at least 1 - beta of the runs (the quantile).
  EXPECT_GE(by_power / double(kRuns), 1 - errors.beta - 4 * share_se(1 - errors.beta));
}

TEST(LearningCusum, LcCusumLimitGivesByMonteCarloTheRunLengthsItPromises) {
  // A false signal: declaring competent a trainee failing at p1; a true one: competence at p0.
  check_limit_by_simulation(CusumChart::learning, kRates.acceptable_failure, kRates.unacceptable_failure);
}

TEST(LearningCusum, BernoulliCusumLimitGivesByMonteCarloTheRunLengthsItPromises) {
  // A false alarm: a trainee at p0; a true alarm: one whose failure rate rose to p1.
  check_limit_by_simulation(CusumChart::monitoring, kRates.unacceptable_failure, kRates.acceptable_failure);
}

TEST(LearningCusum, WaldLimitIsReportedBesideTheComputedOne) {
  const CusumLimit l = cusum_limit(CusumChart::learning, kRates, {0.05, 0.2, 100});
  EXPECT_NEAR(l.wald_limit, std::log(0.8 / 0.05), 1e-12);  // ln 16 = 2.77, the literature's usual value
  EXPECT_GT(l.limit, 0.0);
}

TEST(LearningCusum, RunLengthDistributionIsExactForASingleCase) {
  // One case: the LC-CUSUM signals at case 1 only with a success whose weight reaches h.
  const double up = std::log(0.9 / 0.7);
  EXPECT_NEAR(run_length_cdf(CusumChart::learning, kRates, up - 1e-9, 0.2, 1).at(0), 0.8, 1e-12);
  EXPECT_NEAR(run_length_cdf(CusumChart::learning, kRates, up + 1e-9, 0.2, 1).at(0), 0.0, 1e-12);
  // Two cases with h between one and two successes: only two successes in a row.
  EXPECT_NEAR(run_length_cdf(CusumChart::learning, kRates, 1.5 * up, 0.2, 2).at(1), 0.64, 1e-12);
}

}  // namespace
}  // namespace palprig::stats
