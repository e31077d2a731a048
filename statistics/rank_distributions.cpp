#include "statistics/rank_distributions.hpp"

#include <cmath>
#include <utility>

namespace palprig::stats {

namespace {

// Cumulative sums normalised by the total count.
std::vector<double> cumulate(const std::vector<double>& counts) {
  double total = 0;
  for (double c : counts) total += c;
  std::vector<double> cumulative(counts.size());
  double running = 0;
  for (std::size_t i = 0; i < counts.size(); ++i) {
    running += counts[i];
    cumulative[i] = running / total;
  }
  return cumulative;
}

// P(S <= s) from a table over the integers 0..max (s may be fractional: floor it).
double table_cdf(const std::vector<double>& cumulative, double s) noexcept {
  if (s < 0) return 0.0;
  const double f = std::floor(s);
  if (f >= static_cast<double>(cumulative.size() - 1)) return 1.0;
  return cumulative[static_cast<std::size_t>(f)];
}

// P(S >= s) = sum of the counts from ceil(s) upwards, summed directly (not 1 - cdf) so that
// small upper tails stay exact.
double table_upper(const std::vector<double>& counts, double s) noexcept {
  const double c = std::ceil(s);
  if (c <= 0) return 1.0;
  if (c > static_cast<double>(counts.size() - 1)) return 0.0;
  double total = 0, tail = 0;
  for (std::size_t i = 0; i < counts.size(); ++i) {
    total += counts[i];
    if (static_cast<double>(i) >= c) tail += counts[i];
  }
  return tail / total;
}

}  // namespace

MannWhitneyExact::MannWhitneyExact(std::size_t m, std::size_t n) {
  // U for sizes (m, n) has the same distribution as for (n, m): keep the fewer rows.
  if (n < m) std::swap(m, n);
  // f(u; i, j): orderings of i x's and j y's with U = u. Looking at the largest observation:
  //   f(u; i, j) = f(u - j; i - 1, j) + f(u; i, j - 1)   (it is an x beating all j y's, or a y).
  // Sweep j = 0..n keeping one row per i; updating i upwards in place uses the new row i - 1
  // (same j) and the old row i (previous j), exactly the recurrence.
  const std::size_t max_u = m * n;
  std::vector<std::vector<double>> rows(m + 1, std::vector<double>(max_u + 1, 0.0));
  for (auto& row : rows) row[0] = 1.0;  // j = 0: U = 0 for any i
  for (std::size_t j = 1; j <= n; ++j) {
    for (std::size_t i = 1; i <= m; ++i) {
      for (std::size_t u = max_u + 1; u-- > j;) rows[i][u] += rows[i - 1][u - j];
    }
  }
  counts_ = rows[m];
  cumulative_ = cumulate(counts_);
}

double MannWhitneyExact::cdf(double u) const noexcept { return table_cdf(cumulative_, u); }
double MannWhitneyExact::upper_tail(double u) const noexcept { return table_upper(counts_, u); }

SignedRankExact::SignedRankExact(std::size_t n) {
  // Subsets of the ranks 1..n by their sum: a 0/1 knapsack count.
  const std::size_t max_v = n * (n + 1) / 2;
  counts_.assign(max_v + 1, 0.0);
  counts_[0] = 1.0;
  for (std::size_t rank = 1; rank <= n; ++rank) {
    for (std::size_t v = max_v + 1; v-- > rank;) counts_[v] += counts_[v - rank];
  }
  cumulative_ = cumulate(counts_);
}

double SignedRankExact::cdf(double v) const noexcept { return table_cdf(cumulative_, v); }
double SignedRankExact::upper_tail(double v) const noexcept { return table_upper(counts_, v); }

}  // namespace palprig::stats
