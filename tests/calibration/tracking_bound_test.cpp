// The least tracking error a regulator allows (calibration/tracking_bound.hpp) against a hand
// solution, the exhaust constraint it must keep, and an independent oracle: the same problem
// written as non-negative least squares (pressure = the decayed sum of non-negative fills, the
// first one the starting pressure) and solved by Lawson-Hanson (calibration/nonnegative_least_squares).
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "calibration/nonnegative_least_squares.hpp"
#include "calibration/tracking_bound.hpp"
#include "core/error.hpp"

using namespace palprig;

namespace {

TrackingBound solve(const std::vector<double>& t, const std::vector<double>& r,
                    const std::vector<std::uint8_t>& counted, double tau, std::vector<double>* best = nullptr) {
  return least_tracking_error(t, r, counted, tau, best);
}

// The same minimum by NNLS over the fills c_j >= 0: p_k = sum_{j <= k} exp(-(t_k - t_j) / tau) c_j.
double oracle(const std::vector<double>& t, const std::vector<double>& r, const std::vector<std::uint8_t>& counted,
              double tau) {
  std::vector<std::size_t> rows;
  for (std::size_t k = 0; k < t.size(); ++k)
    if (counted[k]) rows.push_back(k);
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(Eigen::Index(rows.size()), Eigen::Index(t.size()));
  Eigen::VectorXd b(Eigen::Index(rows.size()));
  for (std::size_t i = 0; i < rows.size(); ++i) {
    for (std::size_t j = 0; j <= rows[i]; ++j)
      A(Eigen::Index(i), Eigen::Index(j)) = std::exp(-(t[rows[i]] - t[j]) / tau);
    b(Eigen::Index(i)) = r[rows[i]];
  }
  const NnlsResult s = solve_nonnegative_least_squares(A, b);
  EXPECT_TRUE(s.converged);
  return (A * s.w - b).squaredNorm();
}

TEST(TrackingBound, AFallFasterThanTheExhaustIsSplitAsByHand) {
  // Two samples one second apart, a lag that halves the pressure in that second: from 4 kPa to
  // 0 the best is 3.2 then 1.6 (minimise (p - 4)^2 + (p / 2)^2), 3.2 kPa^2 in all.
  const double tau = 1.0 / std::log(2.0);
  std::vector<double> best;
  const TrackingBound b = solve({0.0, 1.0}, {4.0, 0.0}, {1, 1}, tau, &best);
  EXPECT_NEAR(b.sum_squared_kPa2, 3.2, 1e-12);
  EXPECT_EQ(b.samples, 2u);
  EXPECT_NEAR(best[0], 3.2, 1e-12);
  EXPECT_NEAR(best[1], 1.6, 1e-12);
  EXPECT_NEAR(b.rms_kPa(), std::sqrt(1.6), 1e-12);
}

TEST(TrackingBound, ATargetTheExhaustCanFollowIsReachedExactly) {
  // Rising steps and a fall slower than the lag (tau 50 ms, the target decaying with 200 ms).
  std::vector<double> t, r;
  std::vector<std::uint8_t> counted;
  for (int k = 0; k < 600; ++k) {
    t.push_back(k * 0.001);
    r.push_back(k < 100 ? 0.0 : k < 300 ? 10.0 : 10.0 * std::exp(-(k - 300) * 0.001 / 0.2));
    counted.push_back(1);
  }
  std::vector<double> best;
  const TrackingBound b = solve(t, r, counted, 0.05, &best);
  EXPECT_NEAR(b.sum_squared_kPa2, 0.0, 1e-18);
  for (std::size_t k = 0; k < r.size(); ++k) EXPECT_NEAR(best[k], r[k], 1e-12);
}

TEST(TrackingBound, KeepsTheExhaustConstraintAndMatchesNonNegativeLeastSquares) {
  std::mt19937 rng(20261207);
  std::uniform_real_distribution<double> level(0.0, 20.0), gap(0.0005, 0.004), coin(0.0, 1.0);
  for (int trial = 0; trial < 40; ++trial) {
    const std::size_t n = 10 + std::size_t(trial);
    std::vector<double> t, r;
    std::vector<std::uint8_t> counted;
    double now = 0, held = level(rng);
    for (std::size_t k = 0; k < n; ++k) {
      if (coin(rng) < 0.2) held = coin(rng) < 0.4 ? 0.0 : level(rng);  // steps, many down to 0 kPa
      t.push_back(now);
      r.push_back(held);
      counted.push_back(coin(rng) < 0.85 ? 1 : 0);  // some samples take no part in the sum
      now += gap(rng);
    }
    counted[0] = 1;
    const double tau = 0.003 + 0.02 * coin(rng);
    std::vector<double> best;
    const TrackingBound b = solve(t, r, counted, tau, &best);
    const double o = oracle(t, r, counted, tau);
    EXPECT_NEAR(b.sum_squared_kPa2, o, 1e-9 * (1.0 + o)) << "trial " << trial;
    // The pressures it found are reachable: between two counted samples they fall no faster
    // than the exhaust lets them.
    std::size_t last = 0;
    for (std::size_t k = 1; k < n; ++k) {
      if (!counted[k]) continue;
      EXPECT_GE(best[k], best[last] * std::exp(-(t[k] - t[last]) / tau) - 1e-12) << "trial " << trial << " k " << k;
      last = k;
    }
  }
}

TEST(TrackingBound, UncountedSamplesTakeTimeButNotError) {
  // The middle sample is not counted: the fall from 4 to 0 kPa has two seconds, a quarter.
  const double tau = 1.0 / std::log(2.0);
  const TrackingBound b = solve({0.0, 1.0, 2.0}, {4.0, 100.0, 0.0}, {1, 0, 1}, tau);
  EXPECT_EQ(b.samples, 2u);
  // minimise (p - 4)^2 + (p / 4)^2: p = 4 / (1 + 1/16), error 16 / 17.
  EXPECT_NEAR(b.sum_squared_kPa2, 16.0 / 17.0, 1e-12);
}

TEST(TrackingBound, PooledAddsChannels) {
  const TrackingBound a{2.0, 4}, c{6.0, 4};
  const std::vector<TrackingBound> both{a, c};
  const TrackingBound all = pooled(both);
  EXPECT_DOUBLE_EQ(all.sum_squared_kPa2, 8.0);
  EXPECT_EQ(all.samples, 8u);
  EXPECT_DOUBLE_EQ(all.rms_kPa(), 1.0);
}

TEST(TrackingBound, RefusesInputItCannotBound) {
  EXPECT_THROW(solve({0.0, 1.0}, {1.0}, {1, 1}, 0.05), Error);
  EXPECT_THROW(solve({0.0, 0.0}, {1.0, 1.0}, {1, 1}, 0.05), Error);
  EXPECT_THROW(solve({0.0, 1.0}, {1.0, NAN}, {1, 1}, 0.05), Error);
  EXPECT_THROW(solve({0.0, 1.0}, {1.0, 1.0}, {1, 1}, 0.0), Error);
}

}  // namespace
