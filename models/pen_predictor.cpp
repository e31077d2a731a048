#include "models/pen_predictor.hpp"

#include <algorithm>
#include <cmath>

namespace palprig {

void PenPredictor::observe(const TouchSample& s, const PenPrediction& how) noexcept {
  if (!s.in_contact || !std::isfinite(s.t_s) || !std::isfinite(s.x_mm) || !std::isfinite(s.y_mm) ||
      !std::isfinite(s.force_N)) {
    clear();
    return;
  }
  if (count_ > 0) {
    const TouchSample& newest = at(0);
    if (s.t_s <= newest.t_s) {
      // A held reading (same time) or a clock that went back: keep the history, refresh nothing.
      if (s.t_s < newest.t_s)
        clear();
      else
        return;
    }
  }
  head_ = (head_ + 1) % kCapacity;
  ring_[head_] = s;
  if (count_ < kCapacity) ++count_;
  fit_slopes(how);
}

void PenPredictor::clear() noexcept {
  count_ = 0;
  vx_ = vy_ = vf_ = 0;
  finger_vx_ = finger_vy_ = finger_vf_ = {};
}

namespace {

// Least-squares slopes of x, y and force against time over samples given newest first.
struct Slopes {
  double n = 0, st = 0, stt = 0, sx = 0, sy = 0, sf = 0, stx = 0, sty = 0, stf = 0;
  void add(double t, double x, double y, double f) noexcept {
    n += 1;
    st += t;
    stt += t * t;
    sx += x;
    sy += y;
    sf += f;
    stx += t * x;
    sty += t * y;
    stf += t * f;
  }
  // False when the times do not spread (fewer than two distinct samples).
  bool fit(double& vx, double& vy, double& vf, const PenPrediction& how) const noexcept {
    vx = vy = vf = 0;
    const double d = n * stt - st * st;
    if (!(d > 0)) return false;
    vx = (n * stx - st * sx) / d;
    vy = (n * sty - st * sy) / d;
    vf = std::clamp((n * stf - st * sf) / d, -how.max_force_rate_N_per_s, how.max_force_rate_N_per_s);
    const double speed = std::hypot(vx, vy);
    if (speed > how.max_speed_mm_per_s) {
      vx *= how.max_speed_mm_per_s / speed;
      vy *= how.max_speed_mm_per_s / speed;
    }
    return true;
  }
};

}  // namespace

void PenPredictor::fit_slopes(const PenPrediction& how) noexcept {
  vx_ = vy_ = vf_ = 0;
  finger_vx_ = finger_vy_ = finger_vf_ = {};
  if (count_ < 2) return;
  const TouchSample& newest = at(0);
  if (newest.own_positions || newest.per_finger_force) {
    for (std::size_t i = 0; i < kFingerCount; ++i) {
      if (newest.fingers[i].vent != FingerVent::none) continue;
      // The force against the samples' times; the position against the times its poses were
      // taken, each pose once (a tracker's pose is carried by several samples, and arrives late).
      Slopes force, position;
      const double newest_pose_t = position_time_s(newest, i);
      double last_pose_t = 0;
      std::size_t poses = 0;
      bool force_done = false;
      for (std::size_t age = 0; age < count_; ++age) {
        const TouchSample& s = at(age);
        if (s.fingers[i].vent != FingerVent::none) break;  // back into view: only since then
        const double t = s.t_s - newest.t_s;
        force_done = force_done || (age >= 2 && t < -how.window_s);
        if (!force_done) force.add(t, 0, 0, s.fingers[i].force_N);
        const double pose_t = position_time_s(s, i) - newest_pose_t;
        if (poses > 0 && !(pose_t < last_pose_t)) {
          if (pose_t > last_pose_t) break;  // a pose time that went back: only since then
          continue;                         // the same pose again
        }
        if (poses >= 2 && pose_t < -how.window_s) {
          if (force_done) break;
          continue;
        }
        position.add(pose_t, s.fingers[i].x_mm, s.fingers[i].y_mm, 0);
        last_pose_t = pose_t;
        ++poses;
      }
      double unused_x = 0, unused_y = 0, unused_f = 0;
      force.fit(unused_x, unused_y, finger_vf_[i], how);
      position.fit(finger_vx_[i], finger_vy_[i], unused_f, how);
    }
  }
  // Least-squares slopes over the samples of the window, times relative to the newest.
  Slopes pen;
  for (std::size_t age = 0; age < count_; ++age) {
    const TouchSample& s = at(age);
    const double t = s.t_s - newest.t_s;
    if (age >= 2 && t < -how.window_s) break;  // at least two samples, else the window's
    pen.add(t, s.x_mm, s.y_mm, s.force_N);
  }
  pen.fit(vx_, vy_, vf_, how);
}

TouchSample PenPredictor::predict(double t_s, const PenPrediction& how) const noexcept {
  if (count_ == 0) return {};
  const TouchSample& newest = at(0);
  TouchSample out = newest;
  out.t_s = t_s;
  const double h = std::clamp(t_s - newest.t_s, 0.0, how.max_horizon_s);
  out.x_mm = newest.x_mm + vx_ * h;
  out.y_mm = newest.y_mm + vy_ * h;
  out.force_N = std::max(0.0, newest.force_N + vf_ * h);
  for (std::size_t i = 0; i < kFingerCount; ++i) {
    FingerTouch& f = out.fingers[i];
    const double h_pose = std::clamp(t_s - position_time_s(newest, i), 0.0, how.max_horizon_s);
    f.x_mm += finger_vx_[i] * h_pose;
    f.y_mm += finger_vy_[i] * h_pose;
    f.force_N = std::max(0.0, f.force_N + finger_vf_[i] * h);
  }
  return out;
}

PredictedFinger PenPredictor::predict_finger(double t_s, const PenPrediction& how, std::size_t i) const noexcept {
  PredictedFinger out;
  if (count_ == 0 || i >= kFingerCount) return out;
  const TouchSample& newest = at(0);
  const double h = std::clamp(t_s - newest.t_s, 0.0, how.max_horizon_s);
  out.pen_x_mm = newest.x_mm + vx_ * h;
  out.pen_y_mm = newest.y_mm + vy_ * h;
  out.pen_force_N = std::max(0.0, newest.force_N + vf_ * h);
  out.in_contact = newest.in_contact;
  out.own_position = newest.own_positions;
  out.own_force = newest.per_finger_force;
  const FingerTouch& f = newest.fingers[i];
  const double h_pose = std::clamp(t_s - position_time_s(newest, i), 0.0, how.max_horizon_s);
  out.x_mm = f.x_mm + finger_vx_[i] * h_pose;
  out.y_mm = f.y_mm + finger_vy_[i] * h_pose;
  out.force_N = std::max(0.0, f.force_N + finger_vf_[i] * h);
  out.vent = f.vent;
  return out;
}

}  // namespace palprig
