#include "statistics/statistics_ttest.hpp"

#include <boost/math/distributions/students_t.hpp>
#include <algorithm>
#include <cmath>
#include <vector>

#include "statistics/statistics_describe.hpp"
#include "statistics/statistics_error.hpp"

namespace palprig::stats {

const char* to_string(TTestKind kind) noexcept {
  switch (kind) {
    case TTestKind::welch: return "Welch two-sample t-test";
    case TTestKind::student: return "Student two-sample t-test (pooled variance)";
    case TTestKind::paired: return "paired t-test";
    case TTestKind::one_sample: return "one-sample t-test";
  }
  return "t-test";
}

double two_sided_t_p(double t, double df) {
  if (std::isinf(t)) return 0.0;
  const boost::math::students_t_distribution<double> dist(df);
  // The complement keeps full relative precision far in the tail (p of order 1e-32 and below).
  return 2.0 * boost::math::cdf(boost::math::complement(dist, std::fabs(t)));
}

namespace {

// Fill t, p and the interval from estimate, standard error and df.
void finish(TTestResult& r) {
  if (!(r.standard_error > 0.0)) {
    throw StatisticsError("the data are constant: the standard error is 0 and t is undefined");
  }
  r.t = r.estimate / r.standard_error;
  r.p = two_sided_t_p(r.t, r.df);
  const boost::math::students_t_distribution<double> dist(r.df);
  const double t_crit = boost::math::quantile(dist, 1.0 - (1.0 - r.confidence) / 2.0);
  r.ci_lower = r.estimate - t_crit * r.standard_error;
  r.ci_upper = r.estimate + t_crit * r.standard_error;
}

// t, df and p do not depend on the units; the estimate, its standard error and interval scale
// with them. Computed on values divided by a power of two (exact), the test cannot overflow in
// its squares; only a result beyond the largest double remains, and that is refused.
void unscale(TTestResult& r, double scale) {
  for (double* x : {&r.mean_x, &r.mean_y, &r.estimate, &r.standard_error, &r.ci_lower, &r.ci_upper}) *x *= scale;
  for (double x : {r.mean_x, r.mean_y, r.estimate, r.standard_error, r.ci_lower, r.ci_upper}) {
    if (!std::isfinite(x)) {
      throw StatisticsError(
          "the values are too large: the difference of means or its interval exceeds the largest "
          "double (1.8e308); rescale the column, e.g. to other units");
    }
  }
}

void check_confidence(double confidence) {
  if (!(confidence > 0.0 && confidence < 1.0)) {
    throw StatisticsError("confidence must lie strictly between 0 and 1");
  }
}

}  // namespace

TTestResult two_sample_t_test_from_summary(double mean_x, double sd_x, std::size_t n_x, double mean_y, double sd_y,
                                           std::size_t n_y, bool equal_variance, double confidence) {
  check_confidence(confidence);
  if (n_x < 2 || n_y < 2) throw StatisticsError("a two-sample t-test needs at least 2 values per group");
  const double summary[] = {mean_x, sd_x, mean_y, sd_y};
  for (double v : summary) {
    if (!std::isfinite(v)) throw StatisticsError("a mean or sd is not a finite number");
  }
  const double scale = power_of_two_scale(summary);
  mean_x /= scale;
  mean_y /= scale;
  sd_x /= scale;
  sd_y /= scale;
  TTestResult r;
  r.kind = equal_variance ? TTestKind::student : TTestKind::welch;
  r.confidence = confidence;
  r.n_x = n_x;
  r.n_y = n_y;
  r.mean_x = mean_x;
  r.mean_y = mean_y;
  r.estimate = mean_x - mean_y;
  const double nx = static_cast<double>(n_x), ny = static_cast<double>(n_y);
  const double vx = sd_x * sd_x, vy = sd_y * sd_y;
  if (equal_variance) {
    r.df = nx + ny - 2.0;
    const double pooled = ((nx - 1.0) * vx + (ny - 1.0) * vy) / r.df;
    r.standard_error = std::sqrt(pooled * (1.0 / nx + 1.0 / ny));
  } else {
    const double ax = vx / nx, ay = vy / ny;
    r.standard_error = std::sqrt(ax + ay);
    // Welch-Satterthwaite degrees of freedom, with each share of the variance taken relative
    // to the sum (the squares of tiny shares would underflow).
    const double sx = ax / (ax + ay), sy = ay / (ax + ay);
    r.df = 1.0 / (sx * sx / (nx - 1.0) + sy * sy / (ny - 1.0));
  }
  finish(r);
  unscale(r, scale);
  return r;
}

TTestResult two_sample_t_test(std::span<const double> x, std::span<const double> y, bool equal_variance,
                              double confidence) {
  require_finite(x);
  require_finite(y);
  if (x.size() < 2 || y.size() < 2) {
    throw StatisticsError("a two-sample t-test needs at least 2 values per group");
  }
  const MeanVariance a = mean_variance(x), b = mean_variance(y);
  return two_sample_t_test_from_summary(a.mean, a.sd, a.n, b.mean, b.sd, b.n, equal_variance, confidence);
}

TTestResult one_sample_t_test(std::span<const double> x, double mu, double confidence) {
  check_confidence(confidence);
  require_finite(x);
  if (x.size() < 2) throw StatisticsError("a one-sample t-test needs at least 2 values");
  if (!std::isfinite(mu)) throw StatisticsError("the hypothesised mean is not a finite number");
  const MeanVariance a = mean_variance(x);
  const double parts[] = {a.mean, a.sd, mu};
  const double scale = power_of_two_scale(parts);
  TTestResult r;
  r.kind = TTestKind::one_sample;
  r.confidence = confidence;
  r.n_x = a.n;
  r.mean_x = a.mean / scale;
  r.mean_y = mu / scale;
  r.estimate = r.mean_x - r.mean_y;
  r.df = static_cast<double>(a.n) - 1.0;
  r.standard_error = a.sd / scale / std::sqrt(static_cast<double>(a.n));
  finish(r);
  unscale(r, scale);
  return r;
}

TTestResult paired_t_test(std::span<const double> x, std::span<const double> y, double confidence) {
  if (x.size() != y.size()) throw StatisticsError("a paired t-test needs two columns of equal length");
  require_finite(x);
  require_finite(y);
  // x - y of values near +-1e308 overflows: difference on a common power-of-two scale.
  const double scale = std::max(power_of_two_scale(x), power_of_two_scale(y));
  std::vector<double> differences(x.size());
  for (std::size_t i = 0; i < x.size(); ++i) differences[i] = x[i] / scale - y[i] / scale;
  TTestResult r = one_sample_t_test(differences, 0.0, confidence);
  unscale(r, scale);
  r.kind = TTestKind::paired;
  r.n_y = y.size();
  r.mean_x = mean_variance(x).mean;
  r.mean_y = mean_variance(y).mean;
  return r;
}

}  // namespace palprig::stats
