#pragma once
// What one pulse-localisation trial leaves behind: the mark, the artery it was scored against,
// its distance to the centreline and the hit (the store commits it; stats and export read it).
#include <cstdint>
#include <optional>
#include <string>

namespace palprig {

struct PulseTrialRecord {
  int position = 0;
  std::string condition;
  std::optional<std::uint64_t> scene_seed;  // generated conditions: the case's seed
  bool answered = false;
  double mark_x_mm = 0, mark_y_mm = 0;
  std::string artery;      // the artery scored against
  double distance_mm = 0;  // to its centreline; NaN when not answered
  bool hit = false;
  double onset_s = 0, response_time_s = 0;
};

}  // namespace palprig
