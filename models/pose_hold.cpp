#include "models/pose_hold.hpp"

namespace palprig {

bool PointHold::add(double t_s, const Vec3_mm& p) noexcept {
  if (n_ == 0 || distance_mm(p, anchor_) > radius_mm_ || t_s < last_t_s_) {
    anchor_ = p;
    sum_ = {};
    n_ = 0;
    start_t_s_ = t_s;
  }
  for (int i = 0; i < 3; ++i) sum_[i] += p[i];
  ++n_;
  last_t_s_ = t_s;
  return last_t_s_ - start_t_s_ >= hold_s_;
}

double HoldTime::at(double stamp_s, double arrival_s) noexcept {
  if (mode_ == Mode::undecided) {
    mode_ = stamp_s > 0 ? Mode::stamps : Mode::arrival;
  } else if (mode_ == Mode::stamps) {
    const double step_s = stamp_s - last_stamp_s_;
    if (!(step_s > 0 && step_s <= max_step_s_)) mode_ = Mode::arrival;
  }
  if (mode_ == Mode::arrival) return arrival_s;
  last_stamp_s_ = stamp_s;
  return stamp_s;
}

Vec3_mm PointHold::mean() const noexcept {
  if (n_ == 0) return {};
  return {sum_[0] / double(n_), sum_[1] / double(n_), sum_[2] / double(n_)};
}

}  // namespace palprig
