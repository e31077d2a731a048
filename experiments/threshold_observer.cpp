#include "experiments/threshold_observer.hpp"

#include <boost/math/distributions/normal.hpp>
#include <cmath>

namespace palprig {

nlohmann::json to_json(const ThresholdObserverModel& m) {
  return {{"model", "threshold observer"},        {"seed", m.seed},         {"noise_kPa", m.noise_kPa},
          {"criterion_kPa", m.criterion_kPa},     {"settle_s", m.settle_s}, {"response_time_mean_s", m.response.mean_s},
          {"response_time_sd_s", m.response.sd_s}};
}

double analytic_threshold_kPa(const ThresholdObserverModel& m, ThresholdMethod method, FingerSet fingers,
                              double p_correct) {
  const double n = fingers == FingerSet::three ? 3.0 : 1.0;
  const double s = m.noise_kPa * std::sqrt(2.0 / n);
  const double z = boost::math::quantile(boost::math::normal_distribution<>(), p_correct);
  return (method == ThresholdMethod::yes_no ? m.criterion_kPa : 0.0) + s * z;
}

void SimulatedThresholdObserver::trial_started(const ThresholdTrialInfo& trial, double) {
  trial_ = trial;
  for (auto& s : sum_) s.fill(0.0);
  for (auto& c : count_) c.fill(0);
  answer_at_s_ = -1;
}

void SimulatedThresholdObserver::interval_started(int interval, double t_s) {
  start_s_[static_cast<std::size_t>(interval)] = t_s;
}

void SimulatedThresholdObserver::feel(int interval, const FeltSample& sample) {
  const auto i = static_cast<std::size_t>(interval);
  if (sample.t_s - start_s_[i] < model_.settle_s) return;
  for (std::size_t f = 0; f < kFingerCount; ++f) {
    if (trial_.active[f]) {
      sum_[i][f] += sample.felt_kPa[f];
      ++count_[i][f];
    }
  }
}

std::optional<int> SimulatedThresholdObserver::answer(double t_s) {
  if (answer_at_s_ < 0) {
    answer_at_s_ = t_s + random_.lognormal_with_mean_sd(model_.response.mean_s, model_.response.sd_s);
    return std::nullopt;
  }
  if (t_s < answer_at_s_) return std::nullopt;
  std::array<double, 2> sensation{};
  for (std::size_t i = 0; i < 2; ++i) {
    double total = 0;
    int fingers = 0;
    for (std::size_t f = 0; f < kFingerCount; ++f) {
      if (!trial_.active[f]) continue;
      const double felt = count_[i][f] ? sum_[i][f] / count_[i][f] : 0.0;
      total += felt + model_.noise_kPa * random_.normal();
      ++fingers;
    }
    sensation[i] = fingers ? total / fingers : 0.0;
  }
  if (trial_.method == ThresholdMethod::two_afc) return sensation[1] > sensation[0] ? 1 : 0;
  return sensation[1] - sensation[0] > model_.criterion_kPa ? 1 : 0;
}

}  // namespace palprig
