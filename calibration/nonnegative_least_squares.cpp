#include "calibration/nonnegative_least_squares.hpp"

#include <vector>

namespace palprig {

NnlsResult solve_nonnegative_least_squares(const Eigen::MatrixXd& A_in, const Eigen::VectorXd& b_in,
                                           const Eigen::VectorXd* row_weights) {
  const Eigen::Index m = A_in.cols();
  Eigen::MatrixXd A = A_in;
  Eigen::VectorXd b = b_in;
  if (row_weights) {
    const Eigen::VectorXd s = row_weights->cwiseMax(0.0).cwiseSqrt();
    A = s.asDiagonal() * A;
    b = s.cwiseProduct(b);
  }
  Eigen::VectorXd scale(m);
  for (Eigen::Index j = 0; j < m; ++j) {
    const double norm = A.col(j).norm();
    scale[j] = norm > 0 ? 1.0 / norm : 0.0;
    A.col(j) *= scale[j];
  }

  NnlsResult out;
  Eigen::VectorXd w = Eigen::VectorXd::Zero(m);
  std::vector<bool> passive(static_cast<std::size_t>(m), false);
  const double tol = 1e-12 * std::max(1.0, b.norm());
  const int max_outer = static_cast<int>(3 * m + 10);

  // Unconstrained least squares on the passive columns (the others held at zero).
  auto solve_passive = [&](Eigen::VectorXd& s) {
    std::vector<Eigen::Index> cols;
    for (Eigen::Index j = 0; j < m; ++j)
      if (passive[std::size_t(j)]) cols.push_back(j);
    Eigen::MatrixXd Ap(A.rows(), Eigen::Index(cols.size()));
    for (std::size_t k = 0; k < cols.size(); ++k) Ap.col(Eigen::Index(k)) = A.col(cols[k]);
    const Eigen::VectorXd sp = Ap.colPivHouseholderQr().solve(b);
    s.setZero(m);
    for (std::size_t k = 0; k < cols.size(); ++k) s[cols[k]] = sp[Eigen::Index(k)];
  };

  out.converged = false;
  for (out.iterations = 0; out.iterations < max_outer; ++out.iterations) {
    const Eigen::VectorXd gradient = A.transpose() * (b - A * w);
    Eigen::Index best = -1;
    double best_g = tol;
    for (Eigen::Index j = 0; j < m; ++j)
      if (!passive[std::size_t(j)] && gradient[j] > best_g) {
        best_g = gradient[j];
        best = j;
      }
    if (best < 0) {
      out.converged = true;
      break;
    }
    passive[std::size_t(best)] = true;
    Eigen::VectorXd s;
    for (int inner = 0; inner < 3 * m + 10; ++inner) {
      solve_passive(s);
      bool feasible = true;
      for (Eigen::Index j = 0; j < m; ++j)
        if (passive[std::size_t(j)] && s[j] <= 0) feasible = false;
      if (feasible) break;
      // Step from w towards s as far as stays feasible; drop the columns that hit zero.
      double alpha = 1.0;
      for (Eigen::Index j = 0; j < m; ++j)
        if (passive[std::size_t(j)] && s[j] <= 0) alpha = std::min(alpha, w[j] / (w[j] - s[j]));
      w += alpha * (s - w);
      for (Eigen::Index j = 0; j < m; ++j)
        if (passive[std::size_t(j)] && w[j] <= 1e-15) {
          passive[std::size_t(j)] = false;
          w[j] = 0;
        }
    }
    for (Eigen::Index j = 0; j < m; ++j) w[j] = passive[std::size_t(j)] ? std::max(s[j], 0.0) : 0.0;
  }
  out.w = w.cwiseProduct(scale);
  return out;
}

}  // namespace palprig
