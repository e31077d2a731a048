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

double power_of_two_scale(std::span<const double> values) noexcept {
  double largest = 0;
  for (double x : values) largest = std::max(largest, std::fabs(x));
  if (!(largest > 0) || !std::isfinite(largest)) return 1.0;
  return std::ldexp(1.0, std::ilogb(largest));
}

MeanVariance mean_variance(std::span<const double> values) noexcept {
  const double scale = power_of_two_scale(values);
  MeanVariance mv;
  double mean = 0, m2 = 0;
  for (double value : values) {
    const double x = value / scale;
    ++mv.n;
    const double delta = x - mean;
    mean += delta / static_cast<double>(mv.n);
    m2 += delta * (x - mean);
  }
  const double variance = mv.n > 1 ? m2 / static_cast<double>(mv.n - 1) : 0.0;
  mv.mean = mean * scale;
  mv.sd = std::sqrt(variance) * scale;
  mv.variance = variance * scale * scale;  // +inf past the largest double; sd stays exact
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
  d.sd = d.n > 1 ? mv.sd : std::numeric_limits<double>::quiet_NaN();
  d.min = sorted.front();
  d.max = sorted.back();
  d.q1 = quantile_sorted(sorted, 0.25, rule);
  d.median = quantile_sorted(sorted, 0.5, rule);
  d.q3 = quantile_sorted(sorted, 0.75, rule);
  d.iqr = d.q3 - d.q1;
  // Quartiles interpolate between neighbours: a spread beyond the largest double (values near
  // +-1e308) has no finite IQR, and a NaN would be printed as if it were a result.
  if (!std::isfinite(d.q1) || !std::isfinite(d.q3) || !std::isfinite(d.median) || !std::isfinite(d.iqr)) {
    throw StatisticsError(
        "the values are too large: their spread (IQR) exceeds the largest double (1.8e308); "
        "rescale the column, e.g. to other units");
  }
  return d;
}

}  // namespace palprig::stats
