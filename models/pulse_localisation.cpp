#include "models/pulse_localisation.hpp"

#include <cmath>

namespace palprig {

PulseMarkScore score_pulse_mark(const PulseField& arteries, const Point2_mm& mark, double tolerance_mm,
                                const std::string& artery_name) {
  PulseMarkScore s;
  if (!std::isfinite(mark.x_mm) || !std::isfinite(mark.y_mm)) return s;  // no mark: a miss
  for (std::size_t i = 0; i < arteries.size(); ++i) {
    if (!artery_name.empty() && arteries.artery(i).spec().name != artery_name) continue;
    const double d = arteries.artery(i).centreline_distance_mm(mark);
    if (d < s.distance_mm) {
      s.distance_mm = d;
      s.artery = static_cast<int>(i);
    }
  }
  s.hit = s.artery >= 0 && s.distance_mm <= tolerance_mm;
  return s;
}

}  // namespace palprig
