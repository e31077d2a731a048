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

}  // namespace palprig
