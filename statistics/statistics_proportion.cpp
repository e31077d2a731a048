#include "statistics/statistics_proportion.hpp"

#include <boost/math/distributions/normal.hpp>
#include <cmath>
#include <string>

#include "statistics/statistics_error.hpp"

namespace palprig::stats {

double two_sided_z(double confidence) {
  if (!(confidence > 0.0 && confidence < 1.0)) {
    throw StatisticsError("confidence must lie strictly between 0 and 1, got " + std::to_string(confidence));
  }
  const boost::math::normal_distribution<double> standard;
  return boost::math::quantile(standard, 1.0 - (1.0 - confidence) / 2.0);
}

WilsonInterval wilson_interval(std::int64_t k, std::int64_t n, double confidence) {
  if (n <= 0) throw StatisticsError("a proportion needs n > 0");
  if (k < 0 || k > n) throw StatisticsError("a proportion needs 0 <= k <= n");
  const double z = two_sided_z(confidence);
  const double nn = static_cast<double>(n);
  const double p = static_cast<double>(k) / nn;
  const double z2 = z * z;
  const double denominator = 1.0 + z2 / nn;
  const double centre = (p + z2 / (2.0 * nn)) / denominator;
  const double half = z * std::sqrt(p * (1.0 - p) / nn + z2 / (4.0 * nn * nn)) / denominator;

  WilsonInterval w;
  w.k = k;
  w.n = n;
  w.confidence = confidence;
  w.p = p;
  // Rounding can push a bound a hair past p at k = 0 or k = n; the interval always holds p.
  w.lower = std::fmin(std::fmax(centre - half, 0.0), p);
  w.upper = std::fmax(std::fmin(centre + half, 1.0), p);
  return w;
}

ProportionComparison compare_proportions(std::int64_t k1, std::int64_t n1, std::int64_t k2, std::int64_t n2,
                                         double confidence) {
  ProportionComparison c;
  c.first = wilson_interval(k1, n1, confidence);
  c.second = wilson_interval(k2, n2, confidence);
  const WilsonInterval& a = c.first;
  const WilsonInterval& b = c.second;
  c.difference = a.p - b.p;

  // Eq. 10 uses the bounds that face each other: the larger proportion's lower bound and the
  // smaller one's upper bound.
  const WilsonInterval& larger = a.p >= b.p ? a : b;
  const WilsonInterval& smaller = a.p >= b.p ? b : a;
  c.combined_interval = std::hypot(larger.lower - larger.p, smaller.upper - smaller.p);
  c.significant = std::fabs(c.difference) > c.combined_interval;

  // Newcombe's hybrid score interval for p1 - p2.
  c.newcombe_lower = c.difference - std::hypot(a.p - a.lower, b.upper - b.p);
  c.newcombe_upper = c.difference + std::hypot(a.upper - a.p, b.p - b.lower);
  return c;
}

}  // namespace palprig::stats
