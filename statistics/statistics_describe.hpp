#pragma once
// Descriptive statistics of one sample: n, mean, sd, quartiles, IQR.
//
// Quantiles follow Hyndman & Fan's types. The default is type 7 (linear interpolation between
// order statistics at (n-1)p), the default of R's quantile() and numpy.percentile; type 6
// ((n+1)p, SPSS's "weighted average") is offered because the questionnaire papers (003) report
// SPSS quartiles.
#include <span>

namespace palprig::stats {

enum class QuantileRule { r_type6 = 6, r_type7 = 7 };

struct Description {
  std::size_t n = 0;
  double mean = 0;
  double sd = 0;  // sample standard deviation (n - 1 denominator); NaN when n < 2
  double min = 0, q1 = 0, median = 0, q3 = 0, max = 0;
  double iqr = 0;  // q3 - q1
};

// The p-quantile (0 <= p <= 1) of an ascending sorted sample. Throws StatisticsError when empty.
double quantile_sorted(std::span<const double> sorted, double p, QuantileRule rule = QuantileRule::r_type7);

// Throws StatisticsError when the sample is empty or holds a non-finite value.
Description describe(std::span<const double> values, QuantileRule rule = QuantileRule::r_type7);

// Mean and sample variance in one pass (Welford's update, stable for large offsets), on values
// divided by a power of two near the largest magnitude, so that values near the largest double
// (1e200, +-1e308) neither overflow the squares nor the differences.
struct MeanVariance {
  std::size_t n = 0;
  double mean = 0;
  double variance = 0;  // n - 1 denominator; 0 when n < 2; +inf when it exceeds the largest double
  double sd = 0;        // sqrt(variance), finite even when variance is not
};
MeanVariance mean_variance(std::span<const double> values) noexcept;

// 2^k with 2^k <= max |value| < 2^(k+1); 1 when every value is 0 (or there is none). Dividing
// by it is exact, and brings every finite value into [-2, 2].
double power_of_two_scale(std::span<const double> values) noexcept;

}  // namespace palprig::stats
