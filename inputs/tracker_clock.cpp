#include "inputs/tracker_clock.hpp"

#include <algorithm>

namespace palprig {

double TrackerClock::taken_at(double stamp_s, double arrival_s) noexcept {
  const double t = clock_.at(stamp_s, arrival_s);
  if (!clock_.stamped()) return arrival_s;
  const double delay_s = arrival_s - t;
  if (!have_offset_) {
    offset_s_ = delay_s;
    have_offset_ = true;
  } else {
    const double grown_s = offset_s_ + kDriftAllowance * std::max(0.0, arrival_s - last_arrival_s_);
    offset_s_ = std::min(grown_s, delay_s);
  }
  last_arrival_s_ = arrival_s;
  return std::min(arrival_s, t + offset_s_);
}

}  // namespace palprig
