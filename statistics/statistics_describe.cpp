#include "statistics/statistics_describe.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "statistics/statistics_error.hpp"

namespace palprig::stats {

double quantile_sorted(std::span<const double> sorted, double p, QuantileRule rule) {
  if (sorted.empty()) throw StatisticsError("quantile of an empty sample");
  const double n = static_cast<double>(sorted.size());
  // h is the 0-based fractional position of the quantile among the order statistics.
  double h = 0;
  switch (rule) {
    case QuantileRule::r_type7: h = (n - 1.0) * p; break;
    case QuantileRule::r_type6: h = (n + 1.0) * p - 1.0; break;
  }
  h = std::clamp(h, 0.0, n - 1.0);
  const auto lo = static_cast<std::size_t>(std::floor(h));
  const std::size_t hi = std::min(lo + 1, sorted.size() - 1);
  const double frac = h - static_cast<double>(lo);
  return sorted[lo] + frac * (sorted[hi] - sorted[lo]);
}

MeanVariance mean_variance(std::span<const double> values) noexcept {
  MeanVariance mv;
  double m2 = 0;
  for (double x : values) {
    ++mv.n;
    const double delta = x - mv.mean;
    mv.mean += delta / static_cast<double>(mv.n);
    m2 += delta * (x - mv.mean);
  }
  mv.variance = mv.n > 1 ? m2 / static_cast<double>(mv.n - 1) : 0.0;
  return mv;
}

Description describe(std::span<const double> values, QuantileRule rule) {
  if (values.empty()) throw StatisticsError("no values to describe");
  for (double x : values) {
    if (!std::isfinite(x)) throw StatisticsError("a value is not a finite number");
  }
  std::vector<double> sorted(values.begin(), values.end());
  std::sort(sorted.begin(), sorted.end());
  const MeanVariance mv = mean_variance(values);

  Description d;
  d.n = sorted.size();
  d.mean = mv.mean;
  d.sd = d.n > 1 ? std::sqrt(mv.variance) : std::numeric_limits<double>::quiet_NaN();
  d.min = sorted.front();
  d.max = sorted.back();
  d.q1 = quantile_sorted(sorted, 0.25, rule);
  d.median = quantile_sorted(sorted, 0.5, rule);
  d.q3 = quantile_sorted(sorted, 0.75, rule);
  d.iqr = d.q3 - d.q1;
  return d;
}

}  // namespace palprig::stats
