// The exact non-negative least-squares solver against an independent oracle: the best of
// every feasible unconstrained solution over all subsets of active columns (the optimum of a
// convex problem is one of them).
#include <gtest/gtest.h>

#include <random>

#include "calibration/nonnegative_least_squares.hpp"

using namespace palprig;

namespace {

double cost(const Eigen::MatrixXd& A, const Eigen::VectorXd& b, const Eigen::VectorXd& w) {
  return (A * w - b).squaredNorm();
}

Eigen::VectorXd brute_force(const Eigen::MatrixXd& A, const Eigen::VectorXd& b) {
  const int m = int(A.cols());
  Eigen::VectorXd best = Eigen::VectorXd::Zero(m);
  double best_cost = cost(A, b, best);
  for (int mask = 1; mask < (1 << m); ++mask) {
    std::vector<int> cols;
    for (int j = 0; j < m; ++j)
      if (mask & (1 << j)) cols.push_back(j);
    Eigen::MatrixXd As(A.rows(), Eigen::Index(cols.size()));
    for (std::size_t k = 0; k < cols.size(); ++k) As.col(Eigen::Index(k)) = A.col(cols[k]);
    const Eigen::VectorXd s = As.colPivHouseholderQr().solve(b);
    if ((s.array() < 0).any()) continue;
    Eigen::VectorXd w = Eigen::VectorXd::Zero(m);
    for (std::size_t k = 0; k < cols.size(); ++k) w[cols[k]] = s[Eigen::Index(k)];
    if (cost(A, b, w) < best_cost) {
      best_cost = cost(A, b, w);
      best = w;
    }
  }
  return best;
}

}  // namespace

TEST(NonnegativeLeastSquares, MatchesTheSubsetOracleOnRandomProblems) {
  std::mt19937 rng(42);
  std::normal_distribution<double> g(0, 1);
  for (int trial = 0; trial < 40; ++trial) {
    const int rows = 30, cols = 2 + trial % 5;
    Eigen::MatrixXd A(rows, cols);
    Eigen::VectorXd b(rows);
    for (int i = 0; i < rows; ++i) {
      b[i] = g(rng);
      for (int j = 0; j < cols; ++j) A(i, j) = g(rng) + (j % 2 ? 0.5 : 0.0);
    }
    const NnlsResult r = solve_nonnegative_least_squares(A, b);
    ASSERT_TRUE(r.converged);
    const Eigen::VectorXd oracle = brute_force(A, b);
    EXPECT_TRUE((r.w.array() >= 0).all());
    EXPECT_NEAR(cost(A, b, r.w), cost(A, b, oracle), 1e-9 * (1 + cost(A, b, oracle))) << "trial " << trial;
    EXPECT_LT((r.w - oracle).norm(), 1e-6) << "trial " << trial;
  }
}

TEST(NonnegativeLeastSquares, RowWeightsActAsRepeatedRows) {
  // Weighting a row by 3 is the same as having it three times.
  Eigen::MatrixXd A(4, 2);
  A << 1, 0, 1, 1, 0, 1, 2, 1;
  Eigen::VectorXd b(4);
  b << 1, 2, 0.5, 4;
  Eigen::VectorXd weights(4);
  weights << 1, 3, 1, 1;
  Eigen::MatrixXd A3(6, 2);
  A3 << 1, 0, 1, 1, 1, 1, 1, 1, 0, 1, 2, 1;
  Eigen::VectorXd b3(6);
  b3 << 1, 2, 2, 2, 0.5, 4;
  const NnlsResult weighted = solve_nonnegative_least_squares(A, b, &weights);
  const NnlsResult repeated = solve_nonnegative_least_squares(A3, b3);
  EXPECT_LT((weighted.w - repeated.w).norm(), 1e-12);
}
