#pragma once
// RollingRms: the root mean square of an error over the last window_s seconds, for the live rig
// view's rendering error per finger (RMS of monitor - target while it runs), so an experimenter
// sees when a rig drifts from its calibration. Samples arrive at the view's refresh rate, not
// the loop's: a fixed ring of kCapacity samples (allocated with the object, nothing after) holds
// them, the oldest dropped when they age past the window or the ring is full. Running sums would
// drift over hours of a session; the RMS is summed over the ring when asked instead (at most
// kCapacity additions, at the refresh rate).
#include <array>
#include <cmath>
#include <cstddef>

namespace palprig {

class RollingRms {
 public:
  static constexpr std::size_t kCapacity = 512;  // 8.5 s at 60 Hz, 17 s at 30 Hz

  explicit RollingRms(double window_s = 5.0) noexcept : window_s_(window_s) {}

  // A sample of the error at time t_s. Non-finite errors (no monitor reading, a vented finger)
  // are left out; a time before the last one starts over (a new run).
  void push(double t_s, double error_kPa) noexcept {
    if (!std::isfinite(t_s)) return;
    if (count_ > 0 && t_s < time_[newest()]) clear();
    if (std::isfinite(error_kPa)) {
      if (count_ == kCapacity) drop_oldest();
      time_[(head_ + count_) % kCapacity] = t_s;
      error_[(head_ + count_) % kCapacity] = error_kPa;
      ++count_;
    }
    while (count_ > 0 && t_s - time_[head_] > window_s_) drop_oldest();
  }
  // NaN until a sample is in the window.
  double rms_kPa() const noexcept {
    if (count_ == 0) return std::nan("");
    double sum = 0;
    for (std::size_t k = 0; k < count_; ++k) sum += error_[(head_ + k) % kCapacity] * error_[(head_ + k) % kCapacity];
    return std::sqrt(sum / double(count_));
  }
  std::size_t samples() const noexcept { return count_; }
  double window_s() const noexcept { return window_s_; }
  void clear() noexcept { head_ = count_ = 0; }

 private:
  std::size_t newest() const noexcept { return (head_ + count_ - 1) % kCapacity; }
  void drop_oldest() noexcept {
    head_ = (head_ + 1) % kCapacity;
    --count_;
  }
  double window_s_;
  std::array<double, kCapacity> time_{}, error_{};
  std::size_t head_ = 0, count_ = 0;
};

}  // namespace palprig
