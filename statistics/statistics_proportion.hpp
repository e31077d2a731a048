#pragma once
// Proportions: Wilson score intervals and the comparison of two proportions of paper 002.
//
// Wilson (1927), paper 002 eq. 9, without continuity correction: the interval of statsmodels'
// proportion_confint(method="wilson") and of R's prop.test(correct = FALSE).
//
// Two proportions, paper 002 eq. 10 (after Wallis 2013): with p1 > p2, P1 the lower Wilson bound
// of p1 and P2 the upper Wilson bound of p2,
//     CI = sqrt((P1 - p1)^2 + (P2 - p2)^2),  significant when |p1 - p2| > CI.
// The same Wilson bounds give Newcombe's (1998, method 10) hybrid score interval for p1 - p2,
// reported alongside: the difference is significant exactly when that interval excludes 0.
// Boost 1.74 has neither interval; both are written here on Boost's normal quantile.
#include <cstdint>

namespace palprig::stats {

struct WilsonInterval {
  std::int64_t k = 0, n = 0;
  double confidence = 0.95;
  double p = 0;  // k / n
  double lower = 0, upper = 0;
};

// Throws StatisticsError unless 0 <= k <= n, n > 0 and 0 < confidence < 1.
WilsonInterval wilson_interval(std::int64_t k, std::int64_t n, double confidence = 0.95);

// The two-sided standard normal quantile z for a confidence level (0.95 -> 1.959964).
double two_sided_z(double confidence);

struct ProportionComparison {
  WilsonInterval first, second;
  double difference = 0;                          // p1 - p2
  double combined_interval = 0;                   // paper 002 eq. 10
  bool significant = false;                       // |p1 - p2| > combined_interval
  double newcombe_lower = 0, newcombe_upper = 0;  // interval for p1 - p2
};

ProportionComparison compare_proportions(std::int64_t k1, std::int64_t n1, std::int64_t k2, std::int64_t n2,
                                         double confidence = 0.95);

}  // namespace palprig::stats
