#pragma once
// Time base for calibration runs. On hardware the sweep and the evaluation must run in real
// time (the regulators take their time), with absolute deadlines on the monotonic clock so the
// period does not drift. On the simulated rig the plant advances by the time passed to
// write(), so the same code runs as fast as the machine goes on simulated time.
#include <cstdint>

namespace palprig {

class Pacer {
 public:
  Pacer(double rate_hz, bool realtime);
  // Time of tick k (k = 0, 1, ...) in seconds since the start; in real time, sleeps until it.
  double wait_for_tick(std::uint64_t k) noexcept;
  double period_s() const noexcept { return period_s_; }
  bool realtime() const noexcept { return realtime_; }

 private:
  double period_s_;
  std::int64_t period_ns_;
  bool realtime_;
  std::int64_t start_ns_ = 0;
};

}  // namespace palprig
