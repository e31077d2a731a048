// Over 400 lines: the symmetric and the asymmetric fit share their data checks, their evaluation
// cache and both stages; split, each half would repeat the other.
#include "calibration/hysteresis_fit.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <sstream>
#include <vector>

#include <ceres/ceres.h>

#include "calibration/line_fit.hpp"
#include "calibration/nonnegative_least_squares.hpp"
#include "core/input_error.hpp"

namespace palprig {

void simulate_hysteresis(PrandtlIshlinskii model, std::span<const double> input_kPa, std::span<double> output_kPa,
                         bool exhausting) {
  if (input_kPa.empty()) return;
  model.reset(input_kPa[0]);
  for (std::size_t k = 0; k < input_kPa.size() && k < output_kPa.size(); ++k)
    output_kPa[k] = exhausting ? model.apply_exhausting(input_kPa[k]) : model.apply(input_kPa[k]);
}

namespace {

// The room a play's falling band has at input x: the whole band, or near 0 kPa (exhausting) the
// input's distance from 0 (PrandtlIshlinskii::apply_exhausting with its bottom at 0 kPa).
double falling_room_kPa(double x_kPa, bool exhausting) {
  return exhausting ? std::max(x_kPa, 0.0) : std::numeric_limits<double>::infinity();
}

// The model's output and its derivatives at the current parameter values, for every sample.
// Ceres calls PrepareForEvaluation with the parameter blocks already holding the point to
// evaluate; the per-sample cost functions then only read from here.
class PlaySequenceCache final : public ceres::EvaluationCallback {
 public:
  PlaySequenceCache(std::span<const double> x, std::span<const double> y, std::size_t n, bool asymmetric,
                    bool exhausting)
      : x_(x), y_(y), asymmetric_(asymmetric), exhausting_(exhausting) {
    set_operators(n);
  }
  void set_operators(std::size_t n) {
    n_ = n;
    prediction_.resize(x_.size());
    dy_dw_.resize(x_.size() * n);
    dy_dd_.resize(x_.size() * n);
    dy_dfall_.resize(asymmetric_ ? x_.size() * n : 0);
    z_.resize(n);
    dz_dr_.resize(n);
    dz_dfall_.resize(n);
    r_.resize(n);
    dy_dr_.resize(n);
  }

  // Parameter storage the problem optimises: w0, w[n], d[n] (symmetric: threshold increments;
  // asymmetric: the rising thresholds themselves) and, asymmetric, fall[n] (falling thresholds).
  double w0 = 1.0;
  std::vector<double> w, d, fall;

  void PrepareForEvaluation(bool evaluate_jacobians, bool new_evaluation_point) override {
    if (!new_evaluation_point && (have_jacobians_ || !evaluate_jacobians)) return;
    compute(evaluate_jacobians);
  }

  double residual(std::size_t k) const { return prediction_[k] - y_[k]; }
  double input(std::size_t k) const { return x_[k]; }
  const double* dy_dw(std::size_t k) const { return &dy_dw_[k * n_]; }
  const double* dy_dd(std::size_t k) const { return &dy_dd_[k * n_]; }
  const double* dy_dfall(std::size_t k) const { return &dy_dfall_[k * n_]; }
  std::size_t operators() const { return n_; }
  bool asymmetric() const { return asymmetric_; }

  void compute(bool with_jacobians) {
    double r_sum = 0;
    for (std::size_t i = 0; i < n_; ++i) {
      r_sum += d[i];
      r_[i] = asymmetric_ ? d[i] : r_sum;
      z_[i] = x_[0];  // relaxed start
      dz_dr_[i] = 0;
      dz_dfall_[i] = 0;
    }
    for (std::size_t k = 0; k < x_.size(); ++k) {
      const double xk = x_[k];
      const double room = falling_room_kPa(xk, exhausting_);
      double y = w0 * xk;
      for (std::size_t i = 0; i < n_; ++i) {
        // play: z = clamp(z_prev, x - r+, x + r-); on a clamp the state follows x - r+ or x + r-.
        // Exhausting, the falling band is at most the room above 0 kPa, which no threshold moves.
        const double r_down_play = asymmetric_ ? fall[i] : r_[i];
        const bool narrowed = room < r_down_play;
        const double r_down = narrowed ? room : r_down_play;
        if (z_[i] < xk - r_[i]) {
          z_[i] = xk - r_[i];
          dz_dr_[i] = -1;
          dz_dfall_[i] = 0;
        } else if (z_[i] > xk + r_down) {
          z_[i] = xk + r_down;
          dz_dr_[i] = asymmetric_ || narrowed ? 0 : 1;
          dz_dfall_[i] = narrowed ? 0 : 1;
        }
        y += w[i] * z_[i];
      }
      prediction_[k] = y;
      if (with_jacobians) {
        for (std::size_t i = 0; i < n_; ++i) {
          dy_dw_[k * n_ + i] = z_[i];
          dy_dr_[i] = w[i] * dz_dr_[i];
          if (asymmetric_) {
            dy_dd_[k * n_ + i] = dy_dr_[i];  // d holds the rising thresholds themselves
            dy_dfall_[k * n_ + i] = w[i] * dz_dfall_[i];
          }
        }
        if (asymmetric_) continue;
        // r_i = d_1 + ... + d_i, so dy/dd_j = sum over i >= j of dy/dr_i.
        double suffix = 0;
        for (std::size_t i = n_; i-- > 0;) {
          suffix += dy_dr_[i];
          dy_dd_[k * n_ + i] = suffix;
        }
      }
    }
    have_jacobians_ = with_jacobians;
  }

 private:
  std::span<const double> x_, y_;
  bool asymmetric_, exhausting_;
  std::size_t n_;
  std::vector<double> prediction_, dy_dw_, dy_dd_, dy_dfall_;
  std::vector<double> z_, dz_dr_, dz_dfall_, r_, dy_dr_;  // scratch for one pass
  bool have_jacobians_ = false;
};

// One sample's residual; values come from the shared cache.
class PlaySampleCost final : public ceres::CostFunction {
 public:
  PlaySampleCost(const PlaySequenceCache& cache, std::size_t k) : cache_(cache), k_(k) {
    set_num_residuals(1);
    mutable_parameter_block_sizes()->push_back(1);
    mutable_parameter_block_sizes()->push_back(static_cast<int>(cache.operators()));
    mutable_parameter_block_sizes()->push_back(static_cast<int>(cache.operators()));
    if (cache.asymmetric()) mutable_parameter_block_sizes()->push_back(static_cast<int>(cache.operators()));
  }
  bool Evaluate(double const* const*, double* residuals, double** jacobians) const override {
    residuals[0] = cache_.residual(k_);
    if (jacobians) {
      const std::size_t n = cache_.operators();
      if (jacobians[0]) jacobians[0][0] = cache_.input(k_);
      if (jacobians[1]) std::copy_n(cache_.dy_dw(k_), n, jacobians[1]);
      if (jacobians[2]) std::copy_n(cache_.dy_dd(k_), n, jacobians[2]);
      if (cache_.asymmetric() && jacobians[3]) std::copy_n(cache_.dy_dfall(k_), n, jacobians[3]);
    }
    return true;
  }

 private:
  const PlaySequenceCache& cache_;
  std::size_t k_;
};

ceres::LossFunction* make_loss(const HysteresisFitOptions& o) {
  switch (o.loss) {
    case RobustLoss::huber: return new ceres::HuberLoss(o.loss_scale_kPa);
    case RobustLoss::cauchy: return new ceres::CauchyLoss(o.loss_scale_kPa);
    case RobustLoss::none: break;
  }
  return nullptr;
}

std::size_t count_reversals(std::span<const double> x) {
  std::size_t reversals = 0;
  int direction = 0;
  for (std::size_t k = 1; k < x.size(); ++k) {
    const double dx = x[k] - x[k - 1];
    const int s = dx > 0 ? 1 : dx < 0 ? -1 : 0;
    if (s != 0 && direction != 0 && s != direction) ++reversals;
    if (s != 0) direction = s;
  }
  return reversals;
}

}  // namespace

HysteresisFit fit_hysteresis(std::span<const double> x, std::span<const double> y, const HysteresisFitOptions& o,
                             const std::string& file, const std::string& what) {
  const std::size_t n = o.operator_count;
  if (n == 0 || n > kMaxPlayOperators)
    throw InputError(file, what, "between 1 and " + std::to_string(kMaxPlayOperators) + " play operators");
  // Ceres checks its own arguments by aborting: everything it will see is checked here first.
  if (!(o.min_linear_weight > 0) || !std::isfinite(o.min_linear_weight))
    throw InputError("hysteresis fit", "min_linear_weight", "a positive linear weight floor");
  if (!(o.min_threshold_step_kPa > 0) || !std::isfinite(o.min_threshold_step_kPa))
    throw InputError("hysteresis fit", "min_threshold_step_kPa", "a positive threshold step");
  if (!(o.max_threshold_kPa >= 0) || !std::isfinite(o.max_threshold_kPa))
    throw InputError("max_threshold_kPa", std::to_string(o.max_threshold_kPa),
                     "a threshold >= 0 kPa (0: from the data)");
  if (o.loss != RobustLoss::none && (!(o.loss_scale_kPa > 0) || !std::isfinite(o.loss_scale_kPa)))
    throw InputError("loss_scale_kPa", std::to_string(o.loss_scale_kPa), "a positive scale in kPa");
  if (o.max_iterations < 1) throw InputError("hysteresis fit", "max_iterations", "at least 1 iteration");
  if (x.size() != y.size()) throw InputError(file, what, "as many inputs as outputs");
  const std::size_t parameters = 1 + (o.asymmetric ? 3 : 2) * n;
  if (x.size() < 4 * parameters)
    throw InputError(file, what,
                     "at least " + std::to_string(4 * parameters) + " quasi-static samples for " + std::to_string(n) +
                         " play operators, got " + std::to_string(x.size()) +
                         " (record more holds or use fewer operators)");
  for (std::size_t k = 0; k < x.size(); ++k)
    if (!std::isfinite(x[k]) || !std::isfinite(y[k]))
      throw InputError(file, what, "finite samples (sample " + std::to_string(k + 1) + " is NaN or infinite)");
  const auto [x_lo, x_hi] = std::minmax_element(x.begin(), x.end());
  const double x_range = *x_hi - *x_lo;
  if (!(x_range > 1e-6))
    throw InputError(file, what, "an input that moves (it stays at " + std::to_string(*x_lo) + " kPa)");
  if (count_reversals(x) == 0)
    throw InputError(file, what,
                     "an input that reverses at least once (inflation and deflation), so hysteresis can be seen");

  // Starting point from a straight line: slope shared between the linear part and the plays;
  // the residual band around it says how wide the loops are.
  const LineFit line = fit_line(x, y, file, what);
  if (!(line.slope > 0))
    throw InputError(file, what,
                     "an output that rises with the input (the fitted slope is " + std::to_string(line.slope) + ")");
  double band_lo = 0, band_hi = 0;
  for (std::size_t k = 0; k < x.size(); ++k) {
    const double r = y[k] - line.at(x[k]);
    band_lo = std::min(band_lo, r);
    band_hi = std::max(band_hi, r);
  }
  double r_max = o.max_threshold_kPa;
  if (!(r_max > 0)) r_max = std::clamp(2.5 * 0.5 * (band_hi - band_lo) / line.slope, 0.02 * x_range, 0.5 * x_range);
  r_max = std::max(r_max, o.min_threshold_step_kPa * double(n));

  HysteresisFit fit;
  fit.samples = x.size();
  const auto t0 = std::chrono::steady_clock::now();

  // Stage 1: thresholds on a grid, weights by exact non-negative least squares (reweighted
  // for a robust loss). w0 = min_linear_weight + v with v >= 0 keeps w0's bound. Asymmetric:
  // every rising threshold of the grid with every falling one (n x n candidate plays).
  std::vector<double> grid(n);
  for (std::size_t i = 0; i < n; ++i) grid[i] = r_max * double(i + 1) / double(n);
  // Asymmetric: a grid twice as fine (at most 16 levels) for each threshold of a pair, since
  // only n of its pairs go on to Ceres and they should start near where the data wants them.
  std::vector<double> grid_rise, grid_fall;  // per candidate column
  if (o.asymmetric) {
    const std::size_t m = std::min<std::size_t>(2 * n, 16);
    for (std::size_t i = 0; i < m; ++i)
      for (std::size_t j = 0; j < m; ++j) {
        grid_rise.push_back(r_max * double(i + 1) / double(m));
        grid_fall.push_back(r_max * double(j + 1) / double(m));
      }
  } else {
    grid_rise = grid_fall = grid;
  }
  const std::size_t columns = grid_rise.size();
  Eigen::MatrixXd A(Eigen::Index(x.size()), Eigen::Index(columns + 1));
  Eigen::VectorXd b(Eigen::Index(x.size()));
  {
    std::vector<double> z(columns, x[0]);  // relaxed start
    for (std::size_t k = 0; k < x.size(); ++k) {
      const auto row = Eigen::Index(k);
      A(row, 0) = x[k];
      const double room = falling_room_kPa(x[k], o.exhausting);
      for (std::size_t i = 0; i < columns; ++i) {
        z[i] = std::max(x[k] - grid_rise[i], std::min(x[k] + std::min(grid_fall[i], room), z[i]));
        A(row, Eigen::Index(i + 1)) = z[i];
      }
      b[row] = y[k] - o.min_linear_weight * x[k];
    }
  }
  NnlsResult stage1 = solve_nonnegative_least_squares(A, b);
  if (o.loss != RobustLoss::none) {
    Eigen::VectorXd row_weights(b.size());
    for (int pass = 0; pass < 20; ++pass) {
      const Eigen::VectorXd e = A * stage1.w - b;
      for (Eigen::Index k = 0; k < e.size(); ++k) {
        const double u = std::abs(e[k]) / o.loss_scale_kPa;
        row_weights[k] = o.loss == RobustLoss::huber ? (u <= 1 ? 1.0 : 1.0 / u) : 1.0 / (1.0 + u * u);
      }
      const NnlsResult next = solve_nonnegative_least_squares(A, b, &row_weights);
      const double change = (next.w - stage1.w).norm();
      stage1 = next;
      if (change <= 1e-9 * std::max(1.0, stage1.w.norm())) break;
    }
  }
  fit.iterations = stage1.iterations;
  fit.converged = stage1.converged;

  // Keep the operators the data uses; unused ones only make stage 2 ill-conditioned.
  PlaySequenceCache cache(x, y, 0, o.asymmetric, o.exhausting);
  cache.w0 = o.min_linear_weight + stage1.w[0];
  double total_slope = cache.w0;
  for (std::size_t i = 0; i < columns; ++i) total_slope += stage1.w[Eigen::Index(i + 1)];
  std::vector<std::size_t> used;
  for (std::size_t i = 0; i < columns; ++i)
    if (stage1.w[Eigen::Index(i + 1)] > 1e-6 * total_slope) used.push_back(i);
  if (used.size() > n) {
    // Asymmetric: at most n plays go on (the heaviest), so the data still has 4 samples per
    // parameter; Ceres moves their thresholds to take over what the dropped ones did.
    std::stable_sort(used.begin(), used.end(), [&](std::size_t a, std::size_t c) {
      return stage1.w[Eigen::Index(a + 1)] > stage1.w[Eigen::Index(c + 1)];
    });
    used.resize(n);
    std::sort(used.begin(), used.end());
  }
  std::vector<double> kept_r;
  for (std::size_t i : used) {
    cache.w.push_back(stage1.w[Eigen::Index(i + 1)]);
    kept_r.push_back(grid_rise[i]);
    if (o.asymmetric) {
      cache.d.push_back(grid_rise[i]);
      cache.fall.push_back(grid_fall[i]);
    }
  }
  if (!o.asymmetric)
    for (std::size_t i = 0; i < kept_r.size(); ++i) cache.d.push_back(kept_r[i] - (i ? kept_r[i - 1] : 0.0));
  cache.set_operators(kept_r.size());
  fit.stage1_rms_error_kPa = std::sqrt((A * stage1.w - b).squaredNorm() / double(x.size()));

  // Stage 2 (Ceres): thresholds and weights together, bounded, with the robust loss.
  if (o.refine_thresholds && !kept_r.empty() && fit.converged) {
    const std::size_t p = kept_r.size();
    const std::vector<double> w_start = cache.w, d_start = cache.d, fall_start = cache.fall;
    const double w0_start = cache.w0;
    ceres::Problem::Options po;
    po.evaluation_callback = &cache;
    ceres::Problem problem(po);
    for (std::size_t k = 0; k < x.size(); ++k) {
      if (o.asymmetric)
        problem.AddResidualBlock(new PlaySampleCost(cache, k), make_loss(o), &cache.w0, cache.w.data(), cache.d.data(),
                                 cache.fall.data());
      else
        problem.AddResidualBlock(new PlaySampleCost(cache, k), make_loss(o), &cache.w0, cache.w.data(), cache.d.data());
    }
    // Stage 1's active set carries over: a linear weight stage 1 left on its bound stays there
    // (the exact solution says the data wants less), so the bound is not active in stage 2,
    // where Ceres' projected steps would crawl along it.
    if (stage1.w[0] <= 0.0)
      problem.SetParameterBlockConstant(&cache.w0);
    else
      problem.SetParameterLowerBound(&cache.w0, 0, o.min_linear_weight);
    for (std::size_t i = 0; i < p; ++i) {
      problem.SetParameterLowerBound(cache.w.data(), static_cast<int>(i), 0.0);
      problem.SetParameterLowerBound(cache.d.data(), static_cast<int>(i), o.min_threshold_step_kPa);
      problem.SetParameterUpperBound(cache.d.data(), static_cast<int>(i), x_range);
      if (o.asymmetric) {
        problem.SetParameterLowerBound(cache.fall.data(), static_cast<int>(i), o.min_threshold_step_kPa);
        problem.SetParameterUpperBound(cache.fall.data(), static_cast<int>(i), x_range);
      }
    }
    // The cost moves over the kinks of the play operators and, with noise, along flat valleys
    // (thresholds trade off against each other): Ceres' default stops (relative cost change
    // 1e-6, step 1e-8) end the refinement there instead of creeping for hundreds of steps.
    ceres::Solver::Options so;
    so.linear_solver_type = ceres::DENSE_QR;
    so.max_num_iterations = o.max_iterations;
    so.num_threads = std::max(o.threads, 1);
    so.logging_type = ceres::SILENT;
    ceres::Solver::Summary summary;
    ceres::Solve(so, &problem, &summary);
    fit.iterations += static_cast<int>(summary.iterations.size());
    fit.solver_report = summary.BriefReport();
    fit.converged = summary.termination_type == ceres::CONVERGENCE;
    fit.thresholds_refined = fit.converged && summary.final_cost <= summary.initial_cost;
    if (!fit.thresholds_refined) {  // keep stage 1's exact solution
      cache.w = w_start;
      cache.d = d_start;
      cache.fall = fall_start;
      cache.w0 = w0_start;
    }
  } else if (!o.refine_thresholds) {
    fit.solver_report = "thresholds fixed on the grid (no refinement asked)";
  }
  fit.solve_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

  PrandtlIshlinskii& m = fit.model;
  m.linear_weight = cache.w0;
  m.operator_count = cache.w.size();
  m.asymmetric = o.asymmetric;
  double r_sum = 0;
  for (std::size_t i = 0; i < m.operator_count; ++i) {
    r_sum += cache.d[i];
    m.thresholds_kPa[i] = o.asymmetric ? cache.d[i] : r_sum;
    if (o.asymmetric) m.falling_thresholds_kPa[i] = cache.fall[i];
    m.weights[i] = std::max(cache.w[i], 0.0);  // bounds hold; this only removes -0.0
  }
  m.reset(0.0);

  std::vector<double> predicted(x.size());
  simulate_hysteresis(m, x, predicted, o.exhausting);
  double ss = 0;
  for (std::size_t k = 0; k < x.size(); ++k) {
    const double e = predicted[k] - y[k];
    ss += e * e;
    fit.max_abs_error_kPa = std::max(fit.max_abs_error_kPa, std::abs(e));
  }
  fit.rms_error_kPa = std::sqrt(ss / double(x.size()));
  fit.r_squared = r_squared_against(y, predicted);
  if (!m.valid()) {
    fit.converged = false;
    fit.solver_report += " (result is not an invertible model)";
  }
  return fit;
}

}  // namespace palprig
