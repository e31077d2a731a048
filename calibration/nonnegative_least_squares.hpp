#pragma once
// Lawson-Hanson active-set solver for  min ||A w - b||  subject to  w >= 0.
// The hysteresis fit's first stage is exactly this problem (PI weights on a fixed threshold
// grid); an exact finite-step solver beats a general bounded minimiser on these nearly
// collinear columns, and gives Ceres' nonlinear stage a start at the true optimum.
#include <Eigen/Dense>

namespace palprig {

struct NnlsResult {
  Eigen::VectorXd w;
  int iterations = 0;
  bool converged = false;  // false only if the iteration cap was hit
};

// Columns are scaled to unit norm internally. `row_weights` (optional, >= 0) weight each row's
// squared residual (used for iteratively reweighted robust fits).
NnlsResult solve_nonnegative_least_squares(const Eigen::MatrixXd& A, const Eigen::VectorXd& b,
                                           const Eigen::VectorXd* row_weights = nullptr);

}  // namespace palprig
