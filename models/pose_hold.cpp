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

Vec3_mm PointHold::mean() const noexcept {
  if (n_ == 0) return {};
  return {sum_[0] / double(n_), sum_[1] / double(n_), sum_[2] / double(n_)};
}

}  // namespace palprig
