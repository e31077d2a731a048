#include "models/pen_predictor.hpp"

#include <algorithm>
#include <cmath>

namespace palprig {

void PenPredictor::observe(const TouchSample& s, const PenPrediction& how) noexcept {
  if (!s.in_contact || !std::isfinite(s.t_s) || !std::isfinite(s.x_mm) || !std::isfinite(s.y_mm) ||
      !std::isfinite(s.force_N)) {
    count_ = 0;
    vx_ = vy_ = vf_ = 0;
    return;
  }
  if (count_ > 0) {
    const TouchSample& newest = at(0);
    if (s.t_s <= newest.t_s) {
      // A held reading (same time) or a clock that went back: keep the history, refresh nothing.
      if (s.t_s < newest.t_s) count_ = 0, vx_ = vy_ = vf_ = 0;
      else return;
    }
  }
  head_ = (head_ + 1) % kCapacity;
  ring_[head_] = s;
  if (count_ < kCapacity) ++count_;
  fit_slopes(how);
}

void PenPredictor::fit_slopes(const PenPrediction& how) noexcept {
  vx_ = vy_ = vf_ = 0;
  if (count_ < 2) return;
  // Least-squares slopes over the samples of the window, times relative to the newest.
  const TouchSample& newest = at(0);
  double n = 0, st = 0, stt = 0, sx = 0, sy = 0, sf = 0, stx = 0, sty = 0, stf = 0;
  for (std::size_t age = 0; age < count_; ++age) {
    const TouchSample& s = at(age);
    const double t = s.t_s - newest.t_s;
    if (age >= 2 && t < -how.window_s) break;  // at least two samples, else the window's
    n += 1;
    st += t;
    stt += t * t;
    sx += s.x_mm;
    sy += s.y_mm;
    sf += s.force_N;
    stx += t * s.x_mm;
    sty += t * s.y_mm;
    stf += t * s.force_N;
  }
  const double d = n * stt - st * st;
  if (!(d > 0)) return;
  vx_ = (n * stx - st * sx) / d;
  vy_ = (n * sty - st * sy) / d;
  vf_ = std::clamp((n * stf - st * sf) / d, -how.max_force_rate_N_per_s, how.max_force_rate_N_per_s);
  const double speed = std::hypot(vx_, vy_);
  if (speed > how.max_speed_mm_per_s) {
    vx_ *= how.max_speed_mm_per_s / speed;
    vy_ *= how.max_speed_mm_per_s / speed;
  }
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
  return out;
}

}  // namespace palprig
