#pragma once
// Rank tests, two-sided, with the conventions of R's wilcox.test (stats package):
//   method auto    exact null distribution when every sample has fewer than 50 values and
//                  there are no ties (and, for the signed-rank test, no zero differences);
//                  otherwise the normal approximation
//   normal         z with the tie-corrected variance and, by default, a continuity correction
//                  of 0.5 towards the mean (R correct = TRUE). scipy's mannwhitneyu also
//                  corrects by default; scipy's wilcoxon and SPSS do not: pass
//                  continuity_correction = false to reproduce them.
//   ties           average ranks (R rank(), scipy rankdata "average")
//   zeros          signed-rank differences equal to 0 are dropped before ranking (Wilcoxon's
//                  method; R default, scipy zero_method = "wilcox")
// z is reported in every mode (from the normal approximation) so that the effect size
// r = z / sqrt(N) of papers 000 and 003 is always available.
#include <cstddef>
#include <span>
#include <vector>

namespace palprig::stats {

enum class RankMethod { automatic, exact, normal };

const char* to_string(RankMethod method) noexcept;

struct RankOptions {
  RankMethod method = RankMethod::automatic;
  bool continuity_correction = true;
};

// Average ranks (1-based) of the values, ties sharing the mean of their positions.
// Also returns sum(t^3 - t) over tie groups, the term of the tie-corrected variances.
struct Ranking {
  std::vector<double> ranks;
  double tie_term = 0;
  bool has_ties = false;
};
Ranking rank_average(std::span<const double> values);

struct MannWhitneyResult {
  std::size_t n1 = 0, n2 = 0;
  double u1 = 0;        // pairs where group 1 is larger (+0.5 per tie): R's W, scipy's U1
  double u2 = 0;        // n1 * n2 - u1
  double u = 0;         // min(u1, u2), the U that SPSS and paper 000 report
  double z = 0;         // (u1 - n1 n2 / 2 [-/+ 0.5]) / sigma: negative when group 1 ranks lower
  double p = 1;         // two-sided
  double effect_r = 0;  // z / sqrt(n1 + n2)
  bool exact = false;   // p from the exact distribution
  bool ties = false;
  bool continuity_correction = true;  // applied to z (and to p when not exact)
};

// Throws StatisticsError when a group is empty, a value is not finite, or an exact p is
// requested for tied data or samples too large to enumerate.
MannWhitneyResult mann_whitney(std::span<const double> group1, std::span<const double> group2,
                               const RankOptions& options = {});

struct SignedRankResult {
  std::size_t n = 0;       // values given
  std::size_t n_used = 0;  // non-zero differences that were ranked
  std::size_t zeros = 0;   // differences equal to zero, dropped
  double v = 0;            // sum of the ranks of the positive differences (R's V)
  double z = 0;
  double p = 1;                  // two-sided
  double effect_r = 0;           // z / sqrt(n_used)
  double median_difference = 0;  // median of the differences (zeros included)
  bool exact = false;
  bool ties = false;
  bool continuity_correction = true;
};

// One sample against a hypothesised location mu (e.g. a Likert scale's neutral point).
SignedRankResult wilcoxon_signed_rank(std::span<const double> x, double mu, const RankOptions& options = {});
// Paired samples: the differences x - y against 0.
SignedRankResult wilcoxon_signed_rank_paired(std::span<const double> x, std::span<const double> y,
                                             const RankOptions& options = {});

}  // namespace palprig::stats
