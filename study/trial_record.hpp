#pragma once
// TrialRecord: everything one completed trial leaves behind. The runner fills it, the store
// commits it in one transaction, stats and export read it back.
#include <array>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "study/protocol.hpp"
#include "study/scoring.hpp"
#include "study/session_plan.hpp"

namespace palprig {

struct TrialRecord {
  PlannedTrial planned;
  std::string condition;
  PresentationMode mode = PresentationMode::simultaneous;
  std::string combination_label;                    // discrimination: e.g. "0/30/0"
  std::array<double, kFingerCount> stimulus_kPa{};  // discrimination: the commanded levels
  FingerFlags truth{};                              // discrimination: tumor under each finger
  bool answered = false;                            // false: the response timed out
  FingerFlags answer{};                             // discrimination: fingers answered
  std::vector<Mark> marks;                          // localisation
  double onset_s = 0;                               // stimulus onset on the runner's monotonic clock
  double response_time_s = 0;  // from onset to the answer (paper 002's measure); NaN when not answered
  // When the stimulus ended on the same clock: the runner left `present` (the sequence or
  // max_present_s ran out, or an answer during the presentation ended it at the answer's time).
  double stimulus_end_s = std::numeric_limits<double>::quiet_NaN();  // NaN: unknown (stored NULL)
  // When the stimulus reached the fingers on the same clock: the first moment the monitor of a
  // finger carrying a non-zero commanded level crossed half of that level (interpolated between
  // the session loop's samples), the onset as the finger met it rather than as it was
  // commanded (onset_s). NaN (stored NULL) when no finger carried a level above 0 kPa (a 0/0/0
  // combination), for a scene (localisation: the level follows the pen), and when it had not
  // happened by the answer or the stimulus end.
  double stimulus_reached_s = std::numeric_limits<double>::quiet_NaN();
  std::optional<int> confidence;                        // 1..levels when the protocol asks and it was answered
  std::array<double, kFingerCount> felt_kPa{};          // mean actuator pressure while the stimulus was on
  std::array<Outcome, kFingerCount> finger_outcomes{};  // discrimination, when answered
  LocalisationScore localisation;                       // localisation, when answered
  // Localisation: the case palpated (study/localisation_case.hpp). A normal case (no tumor)
  // answered without a mark is a true negative; every mark on it a false mark.
  std::string case_name;
  std::optional<std::uint64_t> case_seed;         // a generated case's seed
  std::optional<CaseDifficulty> case_difficulty;  // a generated case's difficulty
  int case_tumors = 0;                            // tumors in the case; 0: a normal case
};

// The response time measured from the end of the stimulus (what the experimenter's console
// shows): answer time - stimulus_end_s; 0 when answered during the stimulus; NaN when not
// answered. response_time_s stays paper 002's onset measure (its t-test).
double response_time_after_stimulus_s(const TrialRecord& trial) noexcept;
// The same from the stored columns (onset, onset RT, stimulus end); NaN when any is missing.
double response_time_after_stimulus_s(double onset_s, double response_time_s, double stimulus_end_s) noexcept;

// The response time measured from when the stimulus reached the fingers (stimulus_reached_s)
// rather than from its command (onset_s): answer time - stimulus_reached_s; NaN when not
// answered or the stimulus never reached a finger.
double response_time_from_reached_s(const TrialRecord& trial) noexcept;
// The same from the stored columns (onset, onset RT, reached); NaN when any is missing.
double response_time_from_reached_s(double onset_s, double response_time_s, double stimulus_reached_s) noexcept;

}  // namespace palprig
