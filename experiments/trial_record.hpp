#pragma once
// TrialRecord: everything one completed trial leaves behind. The runner fills it, the store
// commits it in one transaction, stats and export read it back.
#include <array>
#include <string>
#include <vector>

#include "experiments/protocol.hpp"
#include "experiments/scoring.hpp"
#include "experiments/session_plan.hpp"

namespace palprig {

struct TrialRecord {
  PlannedTrial planned;
  std::string condition;
  PresentationMode mode = PresentationMode::simultaneous;
  std::string combination_label;                  // discrimination: e.g. "0/30/0"
  std::array<double, kFingerCount> stimulus_kPa{};  // discrimination: the commanded levels
  FingerFlags truth{};                              // discrimination: tumor under each finger
  bool answered = false;                            // false: the response timed out
  FingerFlags answer{};                             // discrimination: fingers answered
  std::vector<Mark> marks;                          // localisation
  double onset_s = 0;                 // stimulus onset on the runner's monotonic clock
  double response_time_s = 0;         // from onset to the answer; meaningless when not answered
  std::array<double, kFingerCount> felt_kPa{};  // mean actuator pressure while the stimulus was on
  std::array<Outcome, kFingerCount> finger_outcomes{};  // discrimination, when answered
  LocalisationScore localisation;                        // localisation, when answered
};

}  // namespace palprig
