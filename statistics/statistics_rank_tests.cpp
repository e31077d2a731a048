#include "statistics/statistics_rank_tests.hpp"

#include <algorithm>
#include <boost/math/distributions/normal.hpp>
#include <cmath>
#include <numeric>

#include "statistics/rank_distributions.hpp"
#include "statistics/statistics_describe.hpp"
#include "statistics/statistics_error.hpp"

namespace palprig::stats {

namespace {

// R's wilcox.test switches to the normal approximation at 50 values per sample.
constexpr std::size_t kExactLimit = 50;
// Forced exact p: the counting tables grow as m * m * n (rank sum) and n^3 (signed rank).
constexpr double kMaxExactTableCells = 5e7;

double sign(double x) noexcept { return x > 0 ? 1.0 : (x < 0 ? -1.0 : 0.0); }

double two_sided_normal_p(double z) {
  const boost::math::normal_distribution<double> standard;
  return 2.0 * boost::math::cdf(boost::math::complement(standard, std::fabs(z)));
}

bool use_exact(const RankOptions& options, bool small_enough, bool untied) {
  switch (options.method) {
    case RankMethod::automatic: return small_enough && untied;
    case RankMethod::exact:
      if (!untied)
        throw StatisticsError("an exact p needs untied data without zero differences; use the normal method");
      return true;
    case RankMethod::normal: return false;
  }
  return false;
}

}  // namespace

const char* to_string(RankMethod method) noexcept {
  switch (method) {
    case RankMethod::automatic: return "auto";
    case RankMethod::exact: return "exact";
    case RankMethod::normal: return "normal";
  }
  return "auto";
}

Ranking rank_average(std::span<const double> values) {
  Ranking r;
  const std::size_t n = values.size();
  r.ranks.assign(n, 0.0);
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return values[a] < values[b]; });
  for (std::size_t start = 0; start < n;) {
    std::size_t end = start + 1;
    while (end < n && values[order[end]] == values[order[start]]) ++end;
    // Positions start..end-1 (0-based) share the mean of the ranks start+1..end.
    const double mean_rank = (static_cast<double>(start + 1) + static_cast<double>(end)) / 2.0;
    for (std::size_t i = start; i < end; ++i) r.ranks[order[i]] = mean_rank;
    const double t = static_cast<double>(end - start);
    if (end - start > 1) {
      r.has_ties = true;
      r.tie_term += t * t * t - t;
    }
    start = end;
  }
  return r;
}

MannWhitneyResult mann_whitney(std::span<const double> group1, std::span<const double> group2,
                               const RankOptions& options) {
  require_finite(group1);
  require_finite(group2);
  if (group1.empty() || group2.empty()) throw StatisticsError("the Mann-Whitney U test needs two non-empty groups");

  std::vector<double> combined(group1.begin(), group1.end());
  combined.insert(combined.end(), group2.begin(), group2.end());
  const Ranking ranking = rank_average(combined);

  MannWhitneyResult r;
  r.n1 = group1.size();
  r.n2 = group2.size();
  const double n1 = static_cast<double>(r.n1), n2 = static_cast<double>(r.n2), n = n1 + n2;
  const double rank_sum1 =
      std::accumulate(ranking.ranks.begin(), ranking.ranks.begin() + static_cast<std::ptrdiff_t>(r.n1), 0.0);
  r.u1 = rank_sum1 - n1 * (n1 + 1.0) / 2.0;
  r.u2 = n1 * n2 - r.u1;
  r.u = std::min(r.u1, r.u2);
  r.ties = ranking.has_ties;
  r.continuity_correction = options.continuity_correction;

  const double centre = n1 * n2 / 2.0;
  const double variance = n1 * n2 / 12.0 * ((n + 1.0) - ranking.tie_term / (n * (n - 1.0)));
  if (!(variance > 0.0)) throw StatisticsError("all values are tied: the rank test is undefined");
  const double deviation = r.u1 - centre;
  const double correction = options.continuity_correction ? sign(deviation) * 0.5 : 0.0;
  r.z = (deviation - correction) / std::sqrt(variance);
  r.effect_r = r.z / std::sqrt(n);

  r.exact = use_exact(options, r.n1 < kExactLimit && r.n2 < kExactLimit, !r.ties);
  if (r.exact) {
    if (std::min(n1, n2) * n1 * n2 > kMaxExactTableCells) {
      throw StatisticsError("samples too large for an exact p; use the normal method");
    }
    r.p = exact_two_sided_p(MannWhitneyExact(r.n1, r.n2), r.u1, centre);
  } else {
    r.p = std::min(1.0, two_sided_normal_p(r.z));
  }
  return r;
}

namespace {

SignedRankResult signed_rank_of_differences(std::vector<double> differences, const RankOptions& options) {
  require_finite(differences);
  if (differences.empty()) throw StatisticsError("the signed-rank test needs at least one value");

  SignedRankResult r;
  r.n = differences.size();
  r.continuity_correction = options.continuity_correction;
  {
    std::vector<double> sorted = differences;
    std::sort(sorted.begin(), sorted.end());
    r.median_difference = quantile_sorted(sorted, 0.5);
  }

  std::vector<double> nonzero;
  nonzero.reserve(differences.size());
  for (double d : differences) {
    if (d != 0.0) nonzero.push_back(d);
  }
  r.zeros = r.n - nonzero.size();
  r.n_used = nonzero.size();
  if (nonzero.empty()) throw StatisticsError("every difference is zero: the signed-rank test is undefined");

  std::vector<double> magnitudes(nonzero.size());
  for (std::size_t i = 0; i < nonzero.size(); ++i) magnitudes[i] = std::fabs(nonzero[i]);
  const Ranking ranking = rank_average(magnitudes);
  for (std::size_t i = 0; i < nonzero.size(); ++i) {
    if (nonzero[i] > 0) r.v += ranking.ranks[i];
  }
  r.ties = ranking.has_ties;

  const double n = static_cast<double>(r.n_used);
  const double centre = n * (n + 1.0) / 4.0;
  const double variance = n * (n + 1.0) * (2.0 * n + 1.0) / 24.0 - ranking.tie_term / 48.0;
  const double deviation = r.v - centre;
  const double correction = options.continuity_correction ? sign(deviation) * 0.5 : 0.0;
  r.z = variance > 0.0 ? (deviation - correction) / std::sqrt(variance) : 0.0;
  r.effect_r = r.z / std::sqrt(n);

  r.exact = use_exact(options, r.n_used < kExactLimit, !r.ties && r.zeros == 0);
  if (r.exact) {
    if (n * n * n > kMaxExactTableCells)
      throw StatisticsError("sample too large for an exact p; use the normal method");
    r.p = exact_two_sided_p(SignedRankExact(r.n_used), r.v, centre);
  } else {
    if (!(variance > 0.0)) throw StatisticsError("all differences are tied: the normal approximation is undefined");
    r.p = std::min(1.0, two_sided_normal_p(r.z));
  }
  return r;
}

}  // namespace

SignedRankResult wilcoxon_signed_rank(std::span<const double> x, double mu, const RankOptions& options) {
  if (!std::isfinite(mu)) throw StatisticsError("the hypothesised value must be a finite number");
  std::vector<double> differences(x.size());
  for (std::size_t i = 0; i < x.size(); ++i) differences[i] = x[i] - mu;
  return signed_rank_of_differences(std::move(differences), options);
}

SignedRankResult wilcoxon_signed_rank_paired(std::span<const double> x, std::span<const double> y,
                                             const RankOptions& options) {
  if (x.size() != y.size()) throw StatisticsError("a paired signed-rank test needs two columns of equal length");
  std::vector<double> differences(x.size());
  for (std::size_t i = 0; i < x.size(); ++i) differences[i] = x[i] - y[i];
  return signed_rank_of_differences(std::move(differences), options);
}

}  // namespace palprig::stats
