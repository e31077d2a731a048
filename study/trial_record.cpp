#include "study/trial_record.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace palprig {

double response_time_after_stimulus_s(double onset_s, double response_time_s, double stimulus_end_s) noexcept {
  if (!std::isfinite(onset_s) || !std::isfinite(response_time_s) || !std::isfinite(stimulus_end_s)) {
    return std::numeric_limits<double>::quiet_NaN();
  }
  // An answer during the stimulus ended it at the answer's time: 0, never a small negative.
  return std::max(0.0, onset_s + response_time_s - stimulus_end_s);
}

double response_time_after_stimulus_s(const TrialRecord& trial) noexcept {
  if (!trial.answered) return std::numeric_limits<double>::quiet_NaN();
  return response_time_after_stimulus_s(trial.onset_s, trial.response_time_s, trial.stimulus_end_s);
}

double response_time_from_reached_s(double onset_s, double response_time_s, double stimulus_reached_s) noexcept {
  if (!std::isfinite(onset_s) || !std::isfinite(response_time_s) || !std::isfinite(stimulus_reached_s)) {
    return std::numeric_limits<double>::quiet_NaN();
  }
  return onset_s + response_time_s - stimulus_reached_s;
}

double response_time_from_reached_s(const TrialRecord& trial) noexcept {
  if (!trial.answered) return std::numeric_limits<double>::quiet_NaN();
  return response_time_from_reached_s(trial.onset_s, trial.response_time_s, trial.stimulus_reached_s);
}

}  // namespace palprig
