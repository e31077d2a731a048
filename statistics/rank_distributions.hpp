#pragma once
// Exact null distributions of the rank statistics for untied data (Boost 1.74 has none).
// Both are built by counting with additions only, so even far tail probabilities keep their
// relative precision; they match R's pwilcox and psignrank.
#include <cstddef>
#include <vector>

namespace palprig::stats {

// Mann-Whitney U for samples of sizes m and n: U counts the pairs (x_i, y_j) with x_i > y_j.
class MannWhitneyExact {
 public:
  MannWhitneyExact(std::size_t m, std::size_t n);
  double cdf(double u) const noexcept;         // P(U <= u)
  double upper_tail(double u) const noexcept;  // P(U >= u)
  std::size_t max_u() const noexcept { return counts_.size() - 1; }

 private:
  std::vector<double> cumulative_;  // P(U <= u) for u = 0..m*n
  std::vector<double> counts_;      // number of orderings giving U = u
};

// Wilcoxon signed-rank V (sum of the ranks of the positive differences) for n non-zero,
// untied differences.
class SignedRankExact {
 public:
  explicit SignedRankExact(std::size_t n);
  double cdf(double v) const noexcept;         // P(V <= v)
  double upper_tail(double v) const noexcept;  // P(V >= v)

 private:
  std::vector<double> cumulative_;
  std::vector<double> counts_;
};

// R's two-sided exact p: double the smaller tail on the side of the statistic, capped at 1.
template <class Distribution>
double exact_two_sided_p(const Distribution& dist, double statistic, double centre) {
  const double one_tail = statistic > centre ? dist.upper_tail(statistic) : dist.cdf(statistic);
  const double p = 2.0 * one_tail;
  return p < 1.0 ? p : 1.0;
}

}  // namespace palprig::stats
