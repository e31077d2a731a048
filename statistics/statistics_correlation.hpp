#pragma once
// Pearson's product-moment correlation with the t test of r = 0 (df = n - 2, two-sided) and
// the Fisher z confidence interval: the numbers of R's cor.test(method = "pearson") and the
// r, p of scipy.stats.pearsonr.
#include <cstddef>
#include <span>

namespace palprig::stats {

struct PearsonResult {
  std::size_t n = 0;
  double r = 0;
  double t = 0;
  double df = 0;
  double p = 1;
  double confidence = 0.95;
  double ci_lower = 0, ci_upper = 0;  // NaN when n <= 3 (the Fisher interval needs n > 3)
};

// Throws StatisticsError when the columns differ in length, hold fewer than 3 pairs, a value
// is not finite, or a column is constant (r is undefined).
PearsonResult pearson(std::span<const double> x, std::span<const double> y, double confidence = 0.95);

// The t test of a published r with n pairs (for checking reported correlations).
PearsonResult pearson_from_r(double r, std::size_t n, double confidence = 0.95);

}  // namespace palprig::stats
