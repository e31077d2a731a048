#pragma once
// Where the pen will be a moment from now, from its past samples only (causal): the lag
// compensation samples the scene where the fingers will be when the regulators have answered,
// so a tumor edge is asked for one regulator lag before the finger reaches it.
//
// The newest samples (a fixed ring; no allocation) give a velocity for the position and a rate
// for the force, each the least-squares slope over the samples of the last window_s; the pen is
// extrapolated along them from its newest sample. A held reading (a sample time already seen:
// a tablet reports at 100-200 Hz, the loop runs at 1 kHz) is not a new sample. The horizon is
// capped (max_horizon_s) and so is the speed (max_speed_mm_per_s, well above a hand's), so a
// pen that jumps (a lifted pen put down elsewhere, a glitch) is not flung across the pad.
// Tracked fingers (TouchSample::own_positions, per_finger_force) are extrapolated the
// same way, each from its own positions and force, over the samples since its tool was last
// vented (out of view), so a tool coming back into view is not read as a jump. A finger's
// position is fitted against the times its poses were taken (FingerTouch::pose_t_s), each pose
// once, and extrapolated from the newest pose's time: a tracker's pose arrives late and is
// carried by several samples, and timed by the samples a late pose, or a burst, reads as a
// finger that stopped and then jumped. Its force (a load cell read every tick) goes by the
// samples' times.
#include <array>
#include <cstddef>

#include "models/touch_sample.hpp"

namespace palprig {

struct PenPrediction {
  double window_s = 0.02;              // samples used for the slopes
  double max_horizon_s = 0.25;         // beyond the newest sample
  double max_speed_mm_per_s = 500;     // a hand palpates at 10-100 mm/s
  double max_force_rate_N_per_s = 50;  // a press rises over tens of ms at the fastest
};

// One finger's part of a prediction (what the tick's look ahead needs, without copying a whole
// TouchSample per sample ahead): the pen, and the finger's own position and force when tracked.
struct PredictedFinger {
  double pen_x_mm = 0, pen_y_mm = 0, pen_force_N = 0;
  bool in_contact = false;
  bool own_position = false, own_force = false;  // TouchSample::own_positions, per_finger_force
  double x_mm = 0, y_mm = 0, force_N = 0;        // the finger's own (when tracked)
  FingerVent vent = FingerVent::none;
};

class PenPredictor {
 public:
  static constexpr std::size_t kCapacity = 64;

  void reset() noexcept { clear(); }
  // Record the sample the tick got. Lifted samples clear the history (a new touch starts over).
  // The slopes are fitted here, once per new sample, so predict() costs a few operations.
  void observe(const TouchSample& sample, const PenPrediction& how = {}) noexcept;
  // The pen at t_s (its position, force and contact), from the newest sample; a lifted pen, or
  // no sample yet, stays as it is. in_contact is kept; the force is clamped at 0. `how` should
  // be the one given to observe() (the caps apply here; the window there).
  TouchSample predict(double t_s, const PenPrediction& how) const noexcept;
  // The same as predict(t_s, how) for finger i only.
  PredictedFinger predict_finger(double t_s, const PenPrediction& how, std::size_t i) const noexcept;
  std::size_t samples() const noexcept { return count_; }

 private:
  const TouchSample& at(std::size_t age) const noexcept {  // 0: newest
    return ring_[(head_ + kCapacity - age) % kCapacity];
  }
  void fit_slopes(const PenPrediction& how) noexcept;
  void clear() noexcept;
  std::array<TouchSample, kCapacity> ring_{};
  std::size_t head_ = 0, count_ = 0;
  double vx_ = 0, vy_ = 0, vf_ = 0;  // mm/s, mm/s, N/s as fitted at the newest sample, capped
  // The same per tracked finger (zero for the pen's triangle, or a finger vented now).
  std::array<double, kFingerCount> finger_vx_{}, finger_vy_{}, finger_vf_{};
};

}  // namespace palprig
