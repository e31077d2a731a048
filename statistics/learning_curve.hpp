#pragma once
// A trainee's learning curve for one measure: its value per session, in session order, with an
// interval, and where it first met a benchmark on the required run of consecutive sessions
// (proficiency-based progression: a level is passed after meeting the experts' benchmark on N
// consecutive attempts). Proportions (tumors found, normal cases called normal) carry Wilson
// intervals; means (false marks per case, seconds per case) Student t intervals.
#include <cstdint>
#include <optional>
#include <utility>
#include <vector>

namespace palprig::stats {

struct LearningPoint {
  int session = 0;       // 1-based, the trainee's session number
  bool defined = false;  // the session had cases for this measure
  double value = 0, lower = 0, upper = 0;
  std::int64_t n = 0;  // cases (or targets) behind the value
};

// k of n per session (n = 0: undefined).
std::vector<LearningPoint> proportion_curve(const std::vector<std::pair<std::int64_t, std::int64_t>>& k_of_n,
                                            double confidence = 0.95);
// The mean of each session's values (none: undefined; one value: no interval, lower = upper).
std::vector<LearningPoint> mean_curve(const std::vector<std::vector<double>>& values, double confidence = 0.95);

enum class Better { higher, lower };
// The first session of the first run of `consecutive` defined sessions whose value meets the
// benchmark (>= for higher, <= for lower); none when no run reaches that length.
std::optional<int> first_run_meeting(const std::vector<LearningPoint>& curve, double benchmark, Better better,
                                     int consecutive);

}  // namespace palprig::stats
