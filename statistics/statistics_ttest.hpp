#pragma once
// t-tests, two-sided, with a confidence interval for the mean difference.
//
// Conventions (the same numbers as R's t.test and scipy.stats):
//   welch        two independent samples, unequal variances, Welch-Satterthwaite df:
//                R t.test(x, y) default; scipy ttest_ind(equal_var=False)
//   student      two independent samples, pooled variance, df = n1 + n2 - 2:
//                R t.test(var.equal = TRUE); scipy ttest_ind default; paper 002's response times
//   paired       the one-sample test of the differences x - y: R t.test(paired = TRUE);
//                scipy ttest_rel
//   one_sample   against a hypothesised mean: R t.test(x, mu = m); scipy ttest_1samp
// Boost 1.74 offers only the one-sample test; the two-sample and paired tests are written here
// on Boost's Student t distribution, which takes the non-integer Welch df.
#include <span>
#include <string>

namespace palprig::stats {

enum class TTestKind { welch, student, paired, one_sample };

const char* to_string(TTestKind kind) noexcept;

struct TTestResult {
  TTestKind kind = TTestKind::welch;
  double t = 0;
  double df = 0;
  double p = 1;         // two-sided
  double estimate = 0;  // mean(x) - mean(y), the mean difference, or mean(x) - mu
  double standard_error = 0;
  double confidence = 0.95;
  double ci_lower = 0, ci_upper = 0;  // interval for the estimate
  double mean_x = 0, mean_y = 0;      // mean_y is mu for one_sample
  std::size_t n_x = 0, n_y = 0;
};

// Two independent samples. Each needs at least 2 values; throws StatisticsError when both are
// constant (the test statistic is undefined, as R reports "data are essentially constant").
TTestResult two_sample_t_test(std::span<const double> x, std::span<const double> y, bool equal_variance,
                              double confidence = 0.95);

// Paired samples of equal length >= 2.
TTestResult paired_t_test(std::span<const double> x, std::span<const double> y, double confidence = 0.95);

TTestResult one_sample_t_test(std::span<const double> x, double mu, double confidence = 0.95);

// The same test from summary figures (mean, sd, n per group), for checking published results.
TTestResult two_sample_t_test_from_summary(double mean_x, double sd_x, std::size_t n_x, double mean_y, double sd_y,
                                           std::size_t n_y, bool equal_variance, double confidence = 0.95);

// Two-sided p of a t statistic with df degrees of freedom (df may be fractional).
double two_sided_t_p(double t, double df);

}  // namespace palprig::stats
