#pragma once
// SimulatedThresholdObserver: the model observer of threshold sessions, with a threshold known
// in closed form. In each interval every active finger's pressure (the mean monitor reading
// after settle_s, i.e. what the rig delivered once the rise is over) is perceived with
// independent Gaussian noise of sd noise_kPa; the interval's sensation is the mean over the
// active fingers (sd noise / sqrt(n)). The difference of the two intervals therefore has sd
// s = noise * sqrt(2 / n), and
//   2afc    P(correct) = Phi(level / s)                 threshold(p) = s * Phi^-1(p)
//   yes-no  P(yes)     = Phi((level - criterion) / s)   threshold(p) = criterion + s * Phi^-1(p)
// with level the increment the rig actually delivered. Three fingers lower the threshold by
// sqrt(3) (averaging independent noise), doubling the noise doubles the 2afc threshold.
#include <cstdint>

#include <nlohmann/json.hpp>

#include "study/random_source.hpp"
#include "experiments/simulated_participant.hpp"
#include "experiments/threshold_session.hpp"

namespace palprig {

struct ThresholdObserverModel {
  std::uint64_t seed = 1;
  double noise_kPa = 0.8;
  double criterion_kPa = 0.5;  // yes-no only
  double settle_s = 0.4;
  ResponseTimeModel response{1.2, 0.4};
};

nlohmann::json to_json(const ThresholdObserverModel& m);

double analytic_threshold_kPa(const ThresholdObserverModel& m, ThresholdMethod method, FingerSet fingers,
                              double p_correct);

class SimulatedThresholdObserver final : public ThresholdParticipant {
 public:
  explicit SimulatedThresholdObserver(const ThresholdObserverModel& model) : model_(model), random_(model.seed) {}

  bool ready(double) override { return true; }
  void trial_started(const ThresholdTrialInfo& trial, double t_s) override;
  void interval_started(int interval, double t_s) override;
  void feel(int interval, const FeltSample& sample) override;
  std::optional<int> answer(double t_s) override;

 private:
  ThresholdObserverModel model_;
  RandomSource random_;
  ThresholdTrialInfo trial_;
  std::array<double, 2> start_s_{};
  std::array<std::array<double, kFingerCount>, 2> sum_{};
  std::array<std::array<int, kFingerCount>, 2> count_{};
  double answer_at_s_ = -1;
};

}  // namespace palprig
