#include "calibration/dynamics_fit.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>

#include <ceres/ceres.h>

#include "core/input_error.hpp"

namespace palprig {

namespace {

// Evenly spaced runs of samples: the model restarts at each run's first sample.
struct Run {
  std::vector<double> x;  // the hysteresis model's output for the commands
  std::vector<double> m;  // monitor
  std::vector<SweepSegment> segment;
};

struct Prepared {
  double period_s = 0;
  std::vector<Run> runs;
  std::size_t residuals = 0;
};

Prepared prepare(std::span<const DynamicsSample> s, const PrandtlIshlinskii* hysteresis, const std::string& file,
                 const std::string& what) {
  Prepared p;
  std::vector<double> gaps;
  for (std::size_t k = 1; k < s.size(); ++k)
    if (s[k].t_s > s[k - 1].t_s) gaps.push_back(s[k].t_s - s[k - 1].t_s);
  if (gaps.empty()) throw InputError(file, what, "step and chirp rows over time (at least 200 samples)");
  const auto middle = gaps.begin() + static_cast<std::ptrdiff_t>(gaps.size() / 2);
  std::nth_element(gaps.begin(), middle, gaps.end());
  p.period_s = *middle;
  PrandtlIshlinskii h = hysteresis ? *hysteresis : PrandtlIshlinskii{};
  for (std::size_t k = 0; k < s.size(); ++k) {
    if (!std::isfinite(s[k].monitor_kPa) || !std::isfinite(s[k].command_kPa))
      throw InputError(file, "line " + std::to_string(s[k].line), "a monitor reading for the dynamics fit of " + what);
    const bool new_run = k == 0 || std::abs((s[k].t_s - s[k - 1].t_s) - p.period_s) > 0.25 * p.period_s;
    if (new_run) {
      if (!p.runs.empty() && p.runs.back().x.size() < 2) p.runs.pop_back();
      p.runs.emplace_back();
      h.reset(s[k].command_kPa);
    }
    Run& r = p.runs.back();
    r.x.push_back(h.is_identity() ? s[k].command_kPa : h.apply(s[k].command_kPa));
    r.m.push_back(s[k].monitor_kPa);
    r.segment.push_back(s[k].segment);
  }
  if (!p.runs.empty() && p.runs.back().x.size() < 2) p.runs.pop_back();
  double cmin = 1e300, cmax = -1e300, mmin = 1e300, mmax = -1e300;
  for (const Run& r : p.runs) {
    p.residuals += r.x.size() - 1;
    for (std::size_t k = 0; k < r.x.size(); ++k) {
      cmin = std::min(cmin, r.x[k]), cmax = std::max(cmax, r.x[k]);
      mmin = std::min(mmin, r.m[k]), mmax = std::max(mmax, r.m[k]);
    }
  }
  if (p.residuals < 200)
    throw InputError(file, what,
                     "at least 200 evenly spaced step and chirp samples to identify the regulator's dynamics, got " +
                         std::to_string(p.residuals) + " (calibrate sweep --excitation ...,step,chirp)");
  if (!(cmax - cmin >= 1.0)) throw InputError(file, what, "step and chirp commands that move by at least 1 kPa");
  if (!(mmax - mmin >= 0.5))
    throw InputError(file, what, "a monitor that answers the step and chirp commands (it moved less than 0.5 kPa)");
  return p;
}

// The discretised FOPDT over every run; with sensitivities when jac is given (rows of 2:
// d/dL, d/dtau). Residuals model - monitor, each run's first sample left out.
void evaluate(const Prepared& p, double dead_time_s, double tau, double* residuals, double* jac) {
  const double T = p.period_s;
  const double whole = std::floor(dead_time_s / T + 1e-12);
  const auto d = static_cast<std::size_t>(std::max(0.0, whole));
  const double theta = std::clamp(dead_time_s - double(d) * T, 0.0, T);
  const double a = std::exp(-T / tau), e = std::exp(-(T - theta) / tau);
  const double b1 = 1 - e, b2 = e - a;
  const double da_dtau = a * T / (tau * tau), de_dtau = e * (T - theta) / (tau * tau), de_dtheta = e / tau;
  std::size_t j = 0;
  for (const Run& r : p.runs) {
    double y = r.m[0], sl = 0, st = 0;
    auto x_at = [&](std::size_t k, std::size_t back) { return k >= back ? r.x[k - back] : r.x[0]; };
    for (std::size_t k = 0; k + 1 < r.x.size(); ++k) {
      const double x1 = x_at(k, d), x2 = x_at(k, d + 1);
      if (jac) {
        const double nsl = a * sl - de_dtheta * x1 + de_dtheta * x2;
        const double nst = a * st + da_dtau * y - de_dtau * x1 + (de_dtau - da_dtau) * x2;
        sl = nsl;
        st = nst;
        jac[2 * j] = sl;
        jac[2 * j + 1] = st;
      }
      y = a * y + b1 * x1 + b2 * x2;
      residuals[j] = y - r.m[k + 1];
      ++j;
    }
  }
}

// The same with a lag of its own while exhausting: each step uses tau_f when the input felt is
// at or above the output (filling), else tau_e. Sensitivities in rows of 3 (d/dL, d/dtau_f,
// d/dtau_e); the switch itself is not differentiated (it moves on a set of measure zero).
void evaluate_directional(const Prepared& p, double dead_time_s, double tau_f, double tau_e, double* residuals,
                          double* jac) {
  const double T = p.period_s;
  const double whole = std::floor(dead_time_s / T + 1e-12);
  const auto d = static_cast<std::size_t>(std::max(0.0, whole));
  const double theta = std::clamp(dead_time_s - double(d) * T, 0.0, T);
  struct Coef {
    double a, e, da, de, de_dtheta;
  };
  auto coef = [&](double tau) {
    const double a = std::exp(-T / tau), e = std::exp(-(T - theta) / tau);
    return Coef{a, e, a * T / (tau * tau), e * (T - theta) / (tau * tau), e / tau};
  };
  const Coef fill = coef(tau_f), exhaust = coef(tau_e);
  std::size_t j = 0;
  for (const Run& r : p.runs) {
    double y = r.m[0], sl = 0, sf = 0, se = 0;
    auto x_at = [&](std::size_t k, std::size_t back) { return k >= back ? r.x[k - back] : r.x[0]; };
    for (std::size_t k = 0; k + 1 < r.x.size(); ++k) {
      const double x1 = x_at(k, d), x2 = x_at(k, d + 1);
      const bool filling = x1 >= y;
      const Coef& c = filling ? fill : exhaust;
      if (jac) {
        const double own = c.da * y - c.de * x1 + (c.de - c.da) * x2;
        sl = c.a * sl - c.de_dtheta * x1 + c.de_dtheta * x2;
        sf = c.a * sf + (filling ? own : 0.0);
        se = c.a * se + (filling ? 0.0 : own);
        jac[3 * j] = sl;
        jac[3 * j + 1] = sf;
        jac[3 * j + 2] = se;
      }
      y = c.a * y + (1 - c.e) * x1 + (c.e - c.a) * x2;
      residuals[j] = y - r.m[k + 1];
      ++j;
    }
  }
}

double sse_directional(const Prepared& p, double dead_time_s, double tau_f, double tau_e, std::vector<double>& buffer) {
  buffer.resize(p.residuals);
  evaluate_directional(p, dead_time_s, tau_f, tau_e, buffer.data(), nullptr);
  double s = 0;
  for (double r : buffer) s += r * r;
  return s;
}

class DirectionalCost final : public ceres::CostFunction {
 public:
  explicit DirectionalCost(const Prepared& p) : p_(p) {
    set_num_residuals(static_cast<int>(p.residuals));
    mutable_parameter_block_sizes()->push_back(3);
  }
  bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override {
    const double L = parameters[0][0], tf = parameters[0][1], te = parameters[0][2];
    if (!(tf > 0) || !(te > 0) || !(L >= 0) || !std::isfinite(L) || !std::isfinite(tf) || !std::isfinite(te))
      return false;
    evaluate_directional(p_, L, tf, te, residuals, jacobians && jacobians[0] ? jacobians[0] : nullptr);
    return true;
  }

 private:
  const Prepared& p_;
};

double sse(const Prepared& p, double dead_time_s, double tau, std::vector<double>& buffer) {
  buffer.resize(p.residuals);
  evaluate(p, dead_time_s, tau, buffer.data(), nullptr);
  double s = 0;
  for (double r : buffer) s += r * r;
  return s;
}

class FopdtCost final : public ceres::CostFunction {
 public:
  explicit FopdtCost(const Prepared& p) : p_(p) {
    set_num_residuals(static_cast<int>(p.residuals));
    mutable_parameter_block_sizes()->push_back(2);
  }
  bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override {
    const double L = parameters[0][0], tau = parameters[0][1];
    if (!(tau > 0) || !(L >= 0) || !std::isfinite(L) || !std::isfinite(tau)) return false;
    evaluate(p_, L, tau, residuals, jacobians && jacobians[0] ? jacobians[0] : nullptr);
    return true;
  }

 private:
  const Prepared& p_;
};

// Golden-section search of the lag (on a log scale) for one dead time.
double best_tau(const Prepared& p, double dead_time_s, const DynamicsFitOptions& o, std::vector<double>& buffer,
                double& best_sse) {
  double lo = std::log(o.min_time_constant_s), hi = std::log(o.max_time_constant_s);
  const double g = 0.5 * (std::sqrt(5.0) - 1);
  double c = hi - g * (hi - lo), d = lo + g * (hi - lo);
  double fc = sse(p, dead_time_s, std::exp(c), buffer), fd = sse(p, dead_time_s, std::exp(d), buffer);
  for (int i = 0; i < 40; ++i) {
    if (fc < fd) {
      hi = d, d = c, fd = fc;
      c = hi - g * (hi - lo);
      fc = sse(p, dead_time_s, std::exp(c), buffer);
    } else {
      lo = c, c = d, fc = fd;
      d = lo + g * (hi - lo);
      fd = sse(p, dead_time_s, std::exp(d), buffer);
    }
  }
  best_sse = std::min(fc, fd);
  return std::exp(fc < fd ? c : d);
}

}  // namespace

std::vector<double> simulate_dynamics(std::span<const DynamicsSample> samples, const PrandtlIshlinskii* hysteresis,
                                      double dead_time_s, double time_constant_s, double exhaust_time_constant_s) {
  const Prepared p = prepare(samples, hysteresis, "(simulation)", "samples");
  std::vector<double> r(p.residuals);
  if (exhaust_time_constant_s > 0)
    evaluate_directional(p, dead_time_s, time_constant_s, exhaust_time_constant_s, r.data(), nullptr);
  else
    evaluate(p, dead_time_s, time_constant_s, r.data(), nullptr);
  std::vector<double> out;
  out.reserve(samples.size());
  std::size_t j = 0;
  for (const Run& run : p.runs) {
    out.push_back(run.m[0]);
    for (std::size_t k = 1; k < run.m.size(); ++k) out.push_back(run.m[k] + r[j++]);
  }
  return out;
}

DynamicsFit fit_dynamics(std::span<const DynamicsSample> samples, const PrandtlIshlinskii* hysteresis,
                         const DynamicsFitOptions& o, const std::string& file, const std::string& what) {
  const auto started = std::chrono::steady_clock::now();
  const Prepared p = prepare(samples, hysteresis, file, what);
  DynamicsFit fit;
  fit.rate_hz = 1.0 / p.period_s;
  fit.samples = p.residuals;

  // Stage 1: whole-sample dead times (every sample up to 50 ms, then coarser), the lag by search.
  std::vector<double> buffer;
  double best = 1e300, best_L = 0, best_tau_s = 0.05;
  const double T = p.period_s;
  for (double L = 0; L <= o.max_dead_time_s + 1e-12; L += (L < 0.05 ? T : 5 * T)) {
    double s = 0;
    const double tau = best_tau(p, L, o, buffer, s);
    if (s < best) best = s, best_L = L, best_tau_s = tau;
  }
  fit.grid_rms_residual_kPa = std::sqrt(best / double(p.residuals));

  // Stage 2: Ceres refines both, the dead time as a real number.
  double params[2] = {best_L, best_tau_s};
  ceres::Problem problem;
  problem.AddResidualBlock(new FopdtCost(p), nullptr, params);
  problem.SetParameterLowerBound(params, 0, 0.0);
  problem.SetParameterUpperBound(params, 0, o.max_dead_time_s);
  problem.SetParameterLowerBound(params, 1, o.min_time_constant_s);
  problem.SetParameterUpperBound(params, 1, o.max_time_constant_s);
  ceres::Solver::Options so;
  so.max_num_iterations = o.max_iterations;
  so.linear_solver_type = ceres::DENSE_QR;
  so.logging_type = ceres::SILENT;
  ceres::Solver::Summary summary;
  ceres::Solve(so, &problem, &summary);
  fit.converged = summary.termination_type == ceres::CONVERGENCE;
  fit.iterations = static_cast<int>(summary.iterations.size());
  fit.solver_report = summary.BriefReport();
  const double refined = sse(p, params[0], params[1], buffer);
  if (refined <= best && std::isfinite(refined)) {
    fit.dead_time_s = params[0];
    fit.time_constant_s = params[1];
  } else {
    fit.dead_time_s = best_L;
    fit.time_constant_s = best_tau_s;
  }

  fit.exhaust_time_constant_s = fit.time_constant_s;
  const double one_lag_sse = sse(p, fit.dead_time_s, fit.time_constant_s, buffer);
  fit.one_lag_rms_residual_kPa = std::sqrt(one_lag_sse / double(p.residuals));

  // Stage 3: separate fill and exhaust lags from the one-lag point; kept when they pay.
  if (o.directional) {
    double q[3] = {fit.dead_time_s, fit.time_constant_s, fit.time_constant_s};
    ceres::Problem directional;
    directional.AddResidualBlock(new DirectionalCost(p), nullptr, q);
    directional.SetParameterLowerBound(q, 0, 0.0);
    directional.SetParameterUpperBound(q, 0, o.max_dead_time_s);
    for (int i : {1, 2}) {
      directional.SetParameterLowerBound(q, i, o.min_time_constant_s);
      directional.SetParameterUpperBound(q, i, o.max_time_constant_s);
    }
    ceres::Solver::Summary s3;
    ceres::Solve(so, &directional, &s3);
    fit.iterations += static_cast<int>(s3.iterations.size());
    const double two_lag_sse = sse_directional(p, q[0], q[1], q[2], buffer);
    const double keep = (1 - o.min_directional_gain) * (1 - o.min_directional_gain);
    if (s3.termination_type == ceres::CONVERGENCE && std::isfinite(two_lag_sse) && two_lag_sse <= keep * one_lag_sse) {
      fit.directional = true;
      fit.dead_time_s = q[0];
      fit.time_constant_s = q[1];
      fit.exhaust_time_constant_s = q[2];
      fit.solver_report = s3.BriefReport();
    }
  }

  // Quality: R^2 of the monitor overall and per segment, residual RMS and maximum.
  std::vector<double> r(p.residuals);
  if (fit.directional)
    evaluate_directional(p, fit.dead_time_s, fit.time_constant_s, fit.exhaust_time_constant_s, r.data(), nullptr);
  else
    evaluate(p, fit.dead_time_s, fit.time_constant_s, r.data(), nullptr);
  struct Acc {
    std::size_t n = 0;
    double ss = 0, sum = 0, sum2 = 0, max_abs = 0;
  };
  Acc all;
  std::vector<std::pair<SweepSegment, Acc>> per;
  std::size_t j = 0;
  for (const Run& run : p.runs)
    for (std::size_t k = 1; k < run.m.size(); ++k, ++j) {
      auto it = std::find_if(per.begin(), per.end(), [&](const auto& a) { return a.first == run.segment[k]; });
      if (it == per.end()) it = per.insert(per.end(), {run.segment[k], Acc{}});
      for (Acc* a : {&all, &it->second}) {
        ++a->n;
        a->ss += r[j] * r[j];
        a->sum += run.m[k];
        a->sum2 += run.m[k] * run.m[k];
        a->max_abs = std::max(a->max_abs, std::abs(r[j]));
      }
    }
  auto r2 = [](const Acc& a) {
    const double tot = a.sum2 - a.sum * a.sum / double(a.n);
    return tot > 0 ? 1.0 - a.ss / tot : 0.0;
  };
  fit.r_squared = r2(all);
  fit.rms_residual_kPa = std::sqrt(all.ss / double(all.n));
  fit.max_residual_kPa = all.max_abs;
  for (const auto& [segment, a] : per)
    fit.segments.push_back({segment, a.n, r2(a), std::sqrt(a.ss / double(a.n)), a.max_abs});
  fit.solve_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  return fit;
}

}  // namespace palprig
