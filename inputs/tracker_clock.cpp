#include "inputs/tracker_clock.hpp"

#include <algorithm>

namespace palprig {

double TrackerClock::taken_at(double stamp_s, double arrival_s) noexcept {
  const double waited_s = std::max(0.0, arrival_s - last_arrival_s_);
  if (mode_ == Mode::undecided) {
    mode_ = stamp_s > 0 ? Mode::stamps : Mode::arrival;
    offset_s_ = arrival_s - stamp_s;
  } else if (mode_ == Mode::stamps) {
    const double step_s = stamp_s - last_stamp_s_;
    if (!(step_s > 0 && step_s <= waited_s + kMaxLead_s)) mode_ = Mode::arrival;
  }
  last_arrival_s_ = arrival_s;
  if (mode_ == Mode::arrival) return arrival_s;
  last_stamp_s_ = stamp_s;
  offset_s_ = std::min(offset_s_ + kDriftAllowance * waited_s, arrival_s - stamp_s);
  return std::min(arrival_s, stamp_s + offset_s_);
}

}  // namespace palprig
