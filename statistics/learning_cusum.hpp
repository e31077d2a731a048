#pragma once
// Cumulative-sum charts of case outcomes (success / failure), as surgical education reads a
// learning curve. Two charts on the same two rates, p0 the acceptable failure rate and p1 > p0
// the unacceptable one:
//
//   Bernoulli CUSUM (Page 1954; in surgery as reviewed by Biau, Resche-Rigon, Godiris-Petit,
//   Nizard and Porcher 2007, "Quality control of surgical and interventional procedures: a review
//   of the CUSUM"): watches performance for a failure rate that has risen to p1. Each case adds
//   the log likelihood ratio of p1 against p0,
//       failure  W = ln(p1 / p0)              (> 0)
//       success  W = ln((1 - p1) / (1 - p0))  (< 0),
//   C_0 = 0, C_t = max(0, C_{t-1} + W_t); an alarm when C_t >= h, after which the chart starts
//   again from 0.
//
//   LC-CUSUM (Biau, Williams, Schlup, Nizard and Porcher 2008, "Quantitative and individualized
//   assessment of the learning curve using LC-CUSUM", Br J Surg 95: 925-929): tests the null
//   hypothesis that the trainee is not yet competent (failure rate p1) against competence (p0).
//   Each case adds the log likelihood ratio of p0 against p1,
//       success  W = ln((1 - p0) / (1 - p1))  (> 0)
//       failure  W = ln(p0 / p1)              (< 0),
//   S_0 = 0, S_t = max(0, S_{t-1} + W_t); competence is declared at the first t with S_t >= h
//   (the chart goes on being drawn after it; the signal is that first case).
//
// Decision limits from chosen error rates over a horizon of N cases (the course's length): h is
// the smallest limit, rounded up to 0.01, for which the chart gives a false signal within N cases
// with probability at most alpha (LC-CUSUM: a trainee still failing at p1 declared competent;
// CUSUM: an alarm on a trainee performing at p0). The run lengths it gives are then reported: the
// probability of a true signal within N cases (power, 1 - beta achieved), the mean cases to a true
// signal, and the cases within which a true signal comes with probability 1 - beta. Beside it,
// Wald's SPRT approximation ln((1 - beta) / alpha), the limit much of the literature quotes.
//
// Run-length distributions are computed exactly: the chart's value after any sequence of cases
// is i * up - j * down for whole i, j (clipped at 0), so the distribution over the reachable
// values is propagated case by case (values a rounding apart merged) without discretising the
// weights. Boost has no CUSUM; this file is written by hand on the published formulas.
#include <optional>
#include <vector>

namespace palprig::stats {

enum class CusumChart { monitoring, learning };  // the Bernoulli CUSUM; the LC-CUSUM
const char* to_string(CusumChart chart) noexcept;

struct CusumRates {
  double acceptable_failure = 0.1;    // p0
  double unacceptable_failure = 0.2;  // p1
};

struct CusumErrors {
  double alpha = 0.05;      // a false signal within the horizon
  double beta = 0.2;        // no true signal within the horizon
  int horizon_cases = 100;  // N
};

// The two weights (failure < 0 < success for the LC-CUSUM; failure > 0 > success for the
// CUSUM). Throws StatisticsError unless 0 < p0 < p1 < 1.
struct CusumWeights {
  double success = 0, failure = 0;
};
CusumWeights cusum_weights(CusumChart chart, const CusumRates& rates);

// The chart over a sequence of cases (true: the case failed), case numbers from 1.
struct CusumPoint {
  int case_number = 0;
  bool failure = false;
  double value = 0;     // C_t or S_t after this case
  bool signal = false;  // an alarm (CUSUM), or the case competence was declared (LC-CUSUM, once)
};
std::vector<CusumPoint> cusum_series(CusumChart chart, const CusumRates& rates, double limit,
                                     const std::vector<bool>& failures);

// P(run length <= n) for n = 1..cases, for a trainee failing at `failure_rate` (exact).
std::vector<double> run_length_cdf(CusumChart chart, const CusumRates& rates, double limit, double failure_rate,
                                   int cases);
// The mean run length at `failure_rate`; none when the chart would not signal within
// `max_cases` with probability 1 - 1e-9 (the direction in which signals are rare).
std::optional<double> mean_run_length(CusumChart chart, const CusumRates& rates, double limit, double failure_rate,
                                      int max_cases = 20000);

struct CusumLimit {
  CusumChart chart = CusumChart::learning;
  CusumRates rates;
  CusumErrors errors;
  double limit = 0;                // h
  double wald_limit = 0;           // ln((1 - beta) / alpha), for comparison
  double false_signal_within = 0;  // P(false signal within N): <= alpha
  double true_signal_within = 0;   // P(true signal within N): the power, 1 - beta achieved
  std::optional<double> mean_cases_to_true_signal;
  std::optional<int> cases_for_power;  // a true signal within this many cases with probability 1 - beta
};
// Throws StatisticsError for rates outside 0 < p0 < p1 < 1, error rates outside (0, 1) or a
// horizon outside 1..100000.
CusumLimit cusum_limit(CusumChart chart, const CusumRates& rates, const CusumErrors& errors);

}  // namespace palprig::stats
