#include "statistics/learning_cusum.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <string>

#include "statistics/statistics_error.hpp"

namespace palprig::stats {

namespace {

void check_rates(const CusumRates& r) {
  if (!(r.acceptable_failure > 0 && r.acceptable_failure < r.unacceptable_failure && r.unacceptable_failure < 1)) {
    throw StatisticsError("CUSUM rates must satisfy 0 < acceptable < unacceptable < 1 (got " +
                          std::to_string(r.acceptable_failure) + " and " + std::to_string(r.unacceptable_failure) +
                          ")");
  }
}

// The failure rate at which a signal is wrong (a false signal) and right (a true one).
double false_signal_rate(CusumChart chart, const CusumRates& r) {
  return chart == CusumChart::learning ? r.unacceptable_failure : r.acceptable_failure;
}
double true_signal_rate(CusumChart chart, const CusumRates& r) {
  return chart == CusumChart::learning ? r.acceptable_failure : r.unacceptable_failure;
}

struct Mass {
  double value = 0;
  double probability = 0;
};

// The distribution of the chart's value over the cases that have not signalled yet, one case at
// a time. From a value v a success goes to max(0, v + success) and a failure to
// max(0, v + failure); both branches are the sorted states shifted, so they merge in linear time.
class RunLengthWalk {
 public:
  RunLengthWalk(const CusumWeights& w, double limit, double failure_rate)
      : w_(w), limit_(limit), q_(failure_rate), states_{{0.0, 1.0}} {}

  // One case; returns the probability that it is the one that signals.
  double step() {
    branch(up_, w_.success, 1.0 - q_);
    branch(down_, w_.failure, q_);
    double signalled = signalled_now_;
    signalled_now_ = 0;
    states_.clear();
    std::merge(up_.begin(), up_.end(), down_.begin(), down_.end(), std::back_inserter(states_),
               [](const Mass& a, const Mass& b) { return a.value < b.value; });
    // Two paths to the same value (i ups and j downs in another order) differ in the last bits.
    std::size_t out = 0;
    for (std::size_t i = 0; i < states_.size(); ++i) {
      if (out > 0 && states_[i].value - states_[out - 1].value <= 1e-9 * (1.0 + std::abs(states_[i].value))) {
        states_[out - 1].probability += states_[i].probability;
      } else {
        states_[out++] = states_[i];
      }
    }
    states_.resize(out);
    return signalled;
  }
  std::size_t state_count() const noexcept { return states_.size(); }
  double surviving() const noexcept {
    double sum = 0;
    for (const Mass& m : states_) sum += m.probability;
    return sum;
  }

 private:
  void branch(std::vector<Mass>& to, double weight, double probability) {
    to.clear();
    if (probability <= 0) return;
    for (const Mass& m : states_) {
      const double v = std::max(0.0, m.value + weight);
      if (v >= limit_)
        signalled_now_ += m.probability * probability;
      else
        to.push_back({v, m.probability * probability});
    }
    // max(0, .) keeps the order; the leading zeros collapse in the merge.
  }

  CusumWeights w_;
  double limit_, q_;
  std::vector<Mass> states_, up_, down_;
  double signalled_now_ = 0;
};

double signal_within(CusumChart chart, const CusumRates& rates, double limit, double failure_rate, int cases) {
  const std::vector<double> cdf = run_length_cdf(chart, rates, limit, failure_rate, cases);
  return cdf.empty() ? 0.0 : cdf.back();
}

}  // namespace

const char* to_string(CusumChart chart) noexcept { return chart == CusumChart::learning ? "LC-CUSUM" : "CUSUM"; }

CusumWeights cusum_weights(CusumChart chart, const CusumRates& r) {
  check_rates(r);
  const double p0 = r.acceptable_failure, p1 = r.unacceptable_failure;
  if (chart == CusumChart::learning) return {std::log((1 - p0) / (1 - p1)), std::log(p0 / p1)};
  return {std::log((1 - p1) / (1 - p0)), std::log(p1 / p0)};
}

std::vector<CusumPoint> cusum_series(CusumChart chart, const CusumRates& rates, double limit,
                                     const std::vector<bool>& failures) {
  const CusumWeights w = cusum_weights(chart, rates);
  std::vector<CusumPoint> points;
  points.reserve(failures.size());
  double value = 0;
  bool declared = false;
  for (std::size_t i = 0; i < failures.size(); ++i) {
    value = std::max(0.0, value + (failures[i] ? w.failure : w.success));
    CusumPoint p{static_cast<int>(i + 1), failures[i], value, false};
    if (value >= limit) {
      if (chart == CusumChart::monitoring) {
        p.signal = true;  // an alarm; the chart starts again
        value = 0;
      } else if (!declared) {
        p.signal = true;  // competence declared: the first crossing
        declared = true;
      }
    }
    points.push_back(p);
  }
  return points;
}

std::vector<double> run_length_cdf(CusumChart chart, const CusumRates& rates, double limit, double failure_rate,
                                   int cases) {
  const CusumWeights w = cusum_weights(chart, rates);
  if (!(failure_rate >= 0 && failure_rate <= 1)) throw StatisticsError("a failure rate between 0 and 1");
  RunLengthWalk walk(w, limit, failure_rate);
  std::vector<double> cdf;
  cdf.reserve(static_cast<std::size_t>(std::max(cases, 0)));
  double total = 0;
  for (int n = 1; n <= cases; ++n) {
    total += walk.step();
    cdf.push_back(std::min(total, 1.0));
  }
  return cdf;
}

std::optional<double> mean_run_length(CusumChart chart, const CusumRates& rates, double limit, double failure_rate,
                                      int max_cases) {
  const CusumWeights w = cusum_weights(chart, rates);
  RunLengthWalk walk(w, limit, failure_rate);
  double mean = 0, signalled = 0;
  for (int n = 1; n <= max_cases; ++n) {
    const double p = walk.step();
    mean += n * p;
    signalled += p;
    if (1.0 - signalled < 1e-12) return mean / signalled;
    if (walk.state_count() > 400000) break;  // rare signals: the walk spreads over too many values
  }
  if (1.0 - signalled < 1e-9) return mean / signalled;
  return std::nullopt;
}

CusumLimit cusum_limit(CusumChart chart, const CusumRates& rates, const CusumErrors& errors) {
  check_rates(rates);
  if (!(errors.alpha > 0 && errors.alpha < 1) || !(errors.beta > 0 && errors.beta < 1))
    throw StatisticsError("CUSUM error rates alpha and beta between 0 and 1");
  if (errors.horizon_cases < 1 || errors.horizon_cases > 100000)
    throw StatisticsError("a CUSUM horizon of 1 to 100000 cases");
  const int n = errors.horizon_cases;
  const double bad = false_signal_rate(chart, rates), good = true_signal_rate(chart, rates);
  const auto false_signal = [&](double h) { return signal_within(chart, rates, h, bad, n); };
  // The false-signal probability falls as the limit rises (a higher limit only delays a signal):
  // bracket the smallest limit that meets alpha, then bisect.
  const CusumWeights w = cusum_weights(chart, rates);
  double lo = 0, hi = std::max(std::abs(w.success), std::abs(w.failure));
  while (false_signal(hi) > errors.alpha) {
    lo = hi;
    hi *= 2;
    if (hi > 1e4) throw StatisticsError("no CUSUM limit below 10000 meets alpha (rates too close together?)");
  }
  for (int i = 0; i < 60 && hi - lo > 1e-7; ++i) {
    const double mid = 0.5 * (lo + hi);
    (false_signal(mid) > errors.alpha ? lo : hi) = mid;
  }
  CusumLimit out;
  out.chart = chart;
  out.rates = rates;
  out.errors = errors;
  out.limit = std::ceil(hi * 100.0 - 1e-9) / 100.0;  // two decimals, as the limit is quoted
  out.wald_limit = std::log((1 - errors.beta) / errors.alpha);
  out.false_signal_within = false_signal(out.limit);
  out.true_signal_within = signal_within(chart, rates, out.limit, good, n);
  out.mean_cases_to_true_signal = mean_run_length(chart, rates, out.limit, good);
  const int longest = std::max(20 * n, 2000);
  const std::vector<double> cdf = run_length_cdf(chart, rates, out.limit, good, longest);
  for (std::size_t i = 0; i < cdf.size(); ++i) {
    if (cdf[i] >= 1 - errors.beta) {
      out.cases_for_power = static_cast<int>(i + 1);
      break;
    }
  }
  return out;
}

}  // namespace palprig::stats
