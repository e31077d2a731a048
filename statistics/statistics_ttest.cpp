#include "statistics/statistics_ttest.hpp"

#include <boost/math/distributions/students_t.hpp>
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

void require_finite(std::span<const double> values) {
  for (double v : values) {
    if (!std::isfinite(v)) throw StatisticsError("a value is not a finite number");
  }
}

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

void check_confidence(double confidence) {
  if (!(confidence > 0.0 && confidence < 1.0)) {
    throw StatisticsError("confidence must lie strictly between 0 and 1");
  }
}

}  // namespace

TTestResult two_sample_t_test_from_summary(double mean_x, double sd_x, std::size_t n_x, double mean_y,
                                           double sd_y, std::size_t n_y, bool equal_variance,
                                           double confidence) {
  check_confidence(confidence);
  if (n_x < 2 || n_y < 2) throw StatisticsError("a two-sample t-test needs at least 2 values per group");
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
    // Welch-Satterthwaite degrees of freedom.
    r.df = (ax + ay) * (ax + ay) / (ax * ax / (nx - 1.0) + ay * ay / (ny - 1.0));
  }
  finish(r);
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
  return two_sample_t_test_from_summary(a.mean, std::sqrt(a.variance), a.n, b.mean, std::sqrt(b.variance),
                                        b.n, equal_variance, confidence);
}

TTestResult one_sample_t_test(std::span<const double> x, double mu, double confidence) {
  check_confidence(confidence);
  require_finite(x);
  if (x.size() < 2) throw StatisticsError("a one-sample t-test needs at least 2 values");
  const MeanVariance a = mean_variance(x);
  TTestResult r;
  r.kind = TTestKind::one_sample;
  r.confidence = confidence;
  r.n_x = a.n;
  r.mean_x = a.mean;
  r.mean_y = mu;
  r.estimate = a.mean - mu;
  r.df = static_cast<double>(a.n) - 1.0;
  r.standard_error = std::sqrt(a.variance / static_cast<double>(a.n));
  finish(r);
  return r;
}

TTestResult paired_t_test(std::span<const double> x, std::span<const double> y, double confidence) {
  if (x.size() != y.size()) throw StatisticsError("a paired t-test needs two columns of equal length");
  std::vector<double> differences(x.size());
  for (std::size_t i = 0; i < x.size(); ++i) differences[i] = x[i] - y[i];
  TTestResult r = one_sample_t_test(differences, 0.0, confidence);
  r.kind = TTestKind::paired;
  r.n_y = y.size();
  r.mean_x = mean_variance(x).mean;
  r.mean_y = mean_variance(y).mean;
  return r;
}

}  // namespace palprig::stats
