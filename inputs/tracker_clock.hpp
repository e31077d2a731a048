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
// the pose that travelled fastest fixing the clocks' offset (plus the shortest transport time,
// which every pose pays). So a taken time is never after its arrival. The offset may grow by
// kDriftAllowance seconds per second of arrival time, so a tracker clock running slower than ours
// (crystals: well below 1e-4) is followed rather than pushing taken times ever further back.
//
// Stamps are trusted only while they behave like a clock: a first stamp above 0, then each after
// the last and ahead of it by at most the time that passed here plus kMaxLead_s (a tool out of
// view for a minute comes back with a stamp a minute on, and that is a clock). A sender that sets
// none (0), or leaves them unset (Debian's libopenigtlink 1.11 does not initialise them: a
// constant or random value), gets arrival times, as before, for the rest of the connection.
//
// Written by hand: neither libopenigtlink nor PLUS's client side offers a stamp-to-local mapping
// (PLUS synchronises its own devices' clocks, on the server).

namespace palprig {

class TrackerClock {
 public:
  static constexpr double kDriftAllowance = 1e-3;  // s of offset growth per s (1000 ppm)
  static constexpr double kMaxLead_s = 1.0;        // a stamp may run ahead of our clock's step by this

  // A pose stamped stamp_s (the tracker's clock) that arrived at arrival_s (ours): its time on ours.
  double taken_at(double stamp_s, double arrival_s) noexcept;
  bool stamped() const noexcept { return mode_ == Mode::stamps; }

 private:
  enum class Mode { undecided, stamps, arrival };
  Mode mode_ = Mode::undecided;
  double offset_s_ = 0, last_stamp_s_ = 0, last_arrival_s_ = 0;
};

}  // namespace palprig
