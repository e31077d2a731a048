#include "calibration/exhaust_lag_fit.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <ceres/ceres.h>

namespace palprig::dynamics_runs {

namespace {

double value_of(double v) { return v; }
template <int N>
double value_of(const ceres::Jet<double, N>& v) {
  return v.a;
}

template <typename S>
struct ExhaustParams {
  S dead_time_s, tau_fill, tau_exhaust, factor_at_0, scale_kPa;
};

// The directional FOPDT of dynamics_fit.cpp with the exhaust lag taken at the model's present
// output, over every run; sink(j, residual) for each sample but each run's first. The dead
// time's whole samples are taken from its value (the split moves on a set of measure zero), its
// fraction carries the derivative; the fill/exhaust switch likewise.
template <typename S, typename Sink>
void run_exhaust_model(const Prepared& p, const ExhaustParams<S>& q, Sink&& sink) {
  const double T = p.period_s;
  const double whole = std::floor(value_of(q.dead_time_s) / T + 1e-12);
  const auto d = static_cast<std::size_t>(std::max(0.0, whole));
  S theta = q.dead_time_s - double(d) * T;
  if (value_of(theta) < 0) theta = S(0.0);
  if (value_of(theta) > T) theta = S(T);
  using std::exp;
  const S a_fill = exp(-T / q.tau_fill), e_fill = exp(-(T - theta) / q.tau_fill);
  const bool pressure_dependent = value_of(q.factor_at_0) != 1.0;
  const S exhaust_far_a = exp(-T / q.tau_exhaust), exhaust_far_e = exp(-(T - theta) / q.tau_exhaust);
  std::size_t j = 0;
  for (const Run& r : p.runs) {
    S y = S(r.m[0]);
    auto x_at = [&](std::size_t k, std::size_t back) { return k >= back ? r.x[k - back] : r.x[0]; };
    for (std::size_t k = 0; k + 1 < r.x.size(); ++k) {
      const double x1 = x_at(k, d), x2 = x_at(k, d + 1);
      S a, e;
      if (x1 >= value_of(y)) {
        a = a_fill, e = e_fill;
      } else if (!pressure_dependent) {
        a = exhaust_far_a, e = exhaust_far_e;
      } else {
        const S y_above_0 = value_of(y) > 0 ? y : S(0.0);
        const S tau = q.tau_exhaust * (1.0 + (q.factor_at_0 - 1.0) * q.scale_kPa / (y_above_0 + q.scale_kPa));
        a = exp(-T / tau);
        e = exp(-(T - theta) / tau);
      }
      y = a * y + (1.0 - e) * x1 + (e - a) * x2;
      sink(j, y - r.m[k + 1]);
      ++j;
    }
  }
}

// Parameter blocks: (dead time, fill lag, exhaust lag) and (F, s). weights: 0 leaves a sample
// out of the fit (a held-out block), empty: all in.
class ExhaustLagCost final : public ceres::CostFunction {
 public:
  ExhaustLagCost(const Prepared& p, const std::vector<double>& weights) : p_(p), w_(weights) {
    set_num_residuals(static_cast<int>(p.residuals));
    mutable_parameter_block_sizes()->push_back(3);
    mutable_parameter_block_sizes()->push_back(2);
  }
  bool Evaluate(double const* const* q, double* residuals, double** jacobians) const override {
    for (int i = 0; i < 3; ++i)
      if (!std::isfinite(q[0][i])) return false;
    if (!(q[0][0] >= 0) || !(q[0][1] > 0) || !(q[0][2] > 0) || !(q[1][0] >= 1) || !(q[1][1] > 0) ||
        !std::isfinite(q[1][0]) || !std::isfinite(q[1][1]))
      return false;
    auto weight = [&](std::size_t j) { return w_.empty() ? 1.0 : w_[j]; };
    if (!jacobians || (!jacobians[0] && !jacobians[1])) {
      run_exhaust_model(p_, ExhaustParams<double>{q[0][0], q[0][1], q[0][2], q[1][0], q[1][1]},
                        [&](std::size_t j, double r) { residuals[j] = weight(j) * r; });
      return true;
    }
    using J = ceres::Jet<double, 5>;
    const ExhaustParams<J> jq{J(q[0][0], 0), J(q[0][1], 1), J(q[0][2], 2), J(q[1][0], 3), J(q[1][1], 4)};
    run_exhaust_model(p_, jq, [&](std::size_t j, const J& r) {
      const double w = weight(j);
      residuals[j] = w * r.a;
      if (jacobians[0])
        for (int i = 0; i < 3; ++i) jacobians[0][3 * j + i] = w * r.v[i];
      if (jacobians[1])
        for (int i = 0; i < 2; ++i) jacobians[1][2 * j + i] = w * r.v[3 + i];
    });
    return true;
  }

 private:
  const Prepared& p_;
  const std::vector<double>& w_;
};

struct Solved {
  ExhaustLagModel model;
  bool converged = false;
  int iterations = 0;
  std::string report;
};

// One Ceres solve; pressure false keeps F = 1 (stage 3's model refitted).
Solved solve_exhaust(const Prepared& p, const ExhaustLagModel& start, bool pressure, const std::vector<double>& weights,
                     const ExhaustLagOptions& o) {
  double a[3] = {start.dead_time_s, start.fill_time_constant_s, start.exhaust_time_constant_s};
  double b[2] = {pressure ? start.factor_at_0 : 1.0, start.scale_kPa};
  ceres::Problem problem;
  problem.AddResidualBlock(new ExhaustLagCost(p, weights), nullptr, a, b);
  problem.SetParameterLowerBound(a, 0, 0.0);
  problem.SetParameterUpperBound(a, 0, o.max_dead_time_s);
  for (int i : {1, 2}) {
    problem.SetParameterLowerBound(a, i, o.min_time_constant_s);
    problem.SetParameterUpperBound(a, i, o.max_time_constant_s);
  }
  if (pressure) {
    problem.SetParameterLowerBound(b, 0, 1.0);
    problem.SetParameterUpperBound(b, 0, o.max_factor_at_0);
    problem.SetParameterLowerBound(b, 1, o.min_scale_kPa);
    problem.SetParameterUpperBound(b, 1, o.max_scale_kPa);
  } else {
    problem.SetParameterBlockConstant(b);
  }
  ceres::Solver::Options so;
  so.max_num_iterations = o.max_iterations;
  so.linear_solver_type = ceres::DENSE_QR;
  so.logging_type = ceres::SILENT;
  ceres::Solver::Summary summary;
  ceres::Solve(so, &problem, &summary);
  Solved s;
  s.model = {a[0], a[1], a[2], b[0], b[1]};
  s.converged = summary.termination_type == ceres::CONVERGENCE;
  s.iterations = static_cast<int>(summary.iterations.size());
  s.report = summary.BriefReport();
  return s;
}

double sum_of_squares(const Prepared& p, const ExhaustLagModel& m, std::vector<double>& buffer) {
  exhaust_lag_residuals(p, m, buffer);
  double s = 0;
  for (double r : buffer) s += r * r;
  return std::isfinite(s) ? s : std::numeric_limits<double>::infinity();
}

}  // namespace

void exhaust_lag_residuals(const Prepared& p, const ExhaustLagModel& m, std::vector<double>& residuals) {
  residuals.resize(p.residuals);
  run_exhaust_model(p,
                    ExhaustParams<double>{m.dead_time_s, m.fill_time_constant_s, m.exhaust_time_constant_s,
                                          m.factor_at_0, m.scale_kPa},
                    [&](std::size_t j, double r) { residuals[j] = r; });
}

ExhaustLagFit fit_exhaust_lag(const Prepared& p, const ExhaustLagModel& start, const ExhaustLagOptions& o) {
  ExhaustLagFit fit;
  std::vector<double> buffer;
  // Starting point: a few (F, s) pairs, the far exhaust lag scaled so that the lag in the middle
  // of a 0-60 kPa range stays stage 3's (which averaged over the levels the steps visited).
  ExhaustLagModel best = start;
  best.factor_at_0 = 1.0;
  double best_ss = std::numeric_limits<double>::infinity();
  for (double f : {1.5, 2.5, 4.0})
    for (double s : {2.0, 5.0, 10.0, 20.0}) {
      ExhaustLagModel m = start;
      m.factor_at_0 = f;
      m.scale_kPa = s;
      m.exhaust_time_constant_s = std::clamp(start.exhaust_time_constant_s / (1 + (f - 1) * s / (30 + s)),
                                             o.min_time_constant_s, o.max_time_constant_s);
      const double ss = sum_of_squares(p, m, buffer);
      if (ss < best_ss) best_ss = ss, best = m;
    }
  const std::vector<double> all;
  const Solved whole = solve_exhaust(p, best, true, all, o);
  fit.model = whole.model;
  fit.converged = whole.converged;
  fit.iterations = whole.iterations;
  fit.solver_report = whole.report;
  fit.rms_residual_kPa = std::sqrt(sum_of_squares(p, fit.model, buffer) / double(p.residuals));
  if (!fit.converged) return fit;

  // Cross-validation: blocks of block_s in turn to the folds; each fold held out, both models
  // refitted on the rest (from their whole-data points) and run over it.
  const int folds = std::max(2, o.folds);
  const auto block = static_cast<std::size_t>(std::max(1.0, std::round(o.block_s / p.period_s)));
  std::vector<int> fold_of(p.residuals);
  for (std::size_t j = 0; j < p.residuals; ++j) fold_of[j] = static_cast<int>((j / block) % std::size_t(folds));
  double base_ss = 0, pressure_ss = 0;
  std::vector<double> weights(p.residuals);
  ExhaustLagModel baseline_start = start;
  baseline_start.factor_at_0 = 1.0;
  for (int k = 0; k < folds; ++k) {
    for (std::size_t j = 0; j < p.residuals; ++j) weights[j] = fold_of[j] == k ? 0.0 : 1.0;
    const Solved base = solve_exhaust(p, baseline_start, false, weights, o);
    const Solved pressure = solve_exhaust(p, fit.model, true, weights, o);
    fit.iterations += base.iterations + pressure.iterations;
    for (const auto& [m, ss] : {std::pair{base.model, &base_ss}, std::pair{pressure.model, &pressure_ss}}) {
      exhaust_lag_residuals(p, m, buffer);
      for (std::size_t j = 0; j < p.residuals; ++j)
        if (fold_of[j] == k) *ss += buffer[j] * buffer[j];
    }
  }
  fit.baseline_held_out_rms_kPa = std::sqrt(base_ss / double(p.residuals));
  fit.held_out_rms_kPa = std::sqrt(pressure_ss / double(p.residuals));
  fit.kept = std::isfinite(pressure_ss) && fit.model.factor_at_0 > 1.0 &&
             fit.held_out_rms_kPa <= (1 - o.min_held_out_gain) * fit.baseline_held_out_rms_kPa;
  return fit;
}

}  // namespace palprig::dynamics_runs
