#pragma once
// When a tracked pose was taken, on this machine's CLOCK_MONOTONIC (seconds).
//
// The lag compensation extrapolates each tracked finger from its own past poses
// (models/pen_predictor.hpp). Timed by arrival, a pose that comes late, or several that come in
// one burst (a loaded rig PC, a network hiccup, a reader that stalled), look like a finger that
// stopped and then jumped, and the extrapolation amplifies that into a pressure spike. A tracker
// stamps each pose with its acquisition time (OpenIGTLink's header timestamp; PlusServer sets it)
// on its own clock; this maps those stamps onto ours:
//
//   taken = stamp + offset,  offset = the smallest (arrival - stamp) seen so far,
//
// the pose that travelled fastest fixing the clocks' offset (plus the shortest transport time, which
// every pose pays). So a taken time is never after its arrival. The offset may grow by
// kDriftAllowance seconds per second of arrival time, so a tracker clock running slower than ours
// (crystals: well below 1e-4) is followed rather than pushing taken times ever further back.
//
// Stamps are trusted only while they behave like a clock (models/pose_hold.hpp's HoldTime: a
// first stamp above 0, each after the last by at most 1 s). A sender that sets none, or leaves
// them unset (Debian's libopenigtlink 1.11 does not initialise them), gives arrival times, as
// before, for the rest of the connection.
//
// Written by hand: neither libopenigtlink nor PLUS's client side offers a stamp-to-local mapping
// (PLUS synchronises its own devices' clocks, on the server).
#include "models/pose_hold.hpp"

namespace palprig {

class TrackerClock {
 public:
  static constexpr double kDriftAllowance = 1e-3;  // s of offset growth per s (1000 ppm)

  // A pose stamped stamp_s (the tracker's clock) that arrived at arrival_s (ours): its time on ours.
  double taken_at(double stamp_s, double arrival_s) noexcept;
  bool stamped() const noexcept { return clock_.stamped(); }

 private:
  HoldTime clock_;
  bool have_offset_ = false;
  double offset_s_ = 0, last_arrival_s_ = 0;
};

}  // namespace palprig
