#pragma once
// A tracked point held still: the tip resting on a fiducial (registration) or a finger under a
// digitizer (static digitization) is taken when it stays within radius_mm of where the hold
// began for hold_s; the point taken is the mean over the hold, which averages the tracker's
// jitter. Moving further restarts the hold there.
#include <cstddef>

#include "models/rigid_transform.hpp"

namespace palprig {

class PointHold {
 public:
  PointHold(double radius_mm, double hold_s) noexcept : radius_mm_(radius_mm), hold_s_(hold_s) {}
  // One point at time t_s; true when the hold is complete (mean() is then the point taken).
  bool add(double t_s, const Vec3_mm& p) noexcept;
  void reset() noexcept { n_ = 0; }
  Vec3_mm mean() const noexcept;
  std::size_t samples() const noexcept { return n_; }
  double held_s() const noexcept { return n_ ? last_t_s_ - start_t_s_ : 0.0; }

 private:
  double radius_mm_, hold_s_;
  Vec3_mm anchor_{}, sum_{};
  double start_t_s_ = 0, last_t_s_ = 0;
  std::size_t n_ = 0;
};

// The time to count a hold in: the tracker's own stamps (OpenIGTLink's header timestamp, the time
// a pose was acquired) while they behave like a clock, else the time each pose arrived. Counted
// in arrival time, a rest whose poses arrive late and then in one burst (a loaded machine, a
// reader that stalled) looks shorter than it was. Stamps are trusted from a first stamp above 0
// while each one is after the last by at most max_step_s: a sender that sets none (0), or leaves
// them unset (Debian's libopenigtlink 1.11 does not initialise them: a constant or random value),
// falls back to arrival time for the rest of the hold. The one switch makes the time go back,
// which restarts a PointHold; it never completes one early.
class HoldTime {
 public:
  explicit HoldTime(double max_step_s = 1.0) noexcept : max_step_s_(max_step_s) {}
  double at(double stamp_s, double arrival_s) noexcept;
  bool stamped() const noexcept { return mode_ == Mode::stamps; }

 private:
  enum class Mode { undecided, stamps, arrival };
  double max_step_s_;
  Mode mode_ = Mode::undecided;
  double last_stamp_s_ = 0;
};

}  // namespace palprig
