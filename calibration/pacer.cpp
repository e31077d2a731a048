#include "calibration/pacer.hpp"

#include <time.h>

#include <cerrno>
#include <cmath>
#include <stdexcept>

namespace palprig {

namespace {
std::int64_t monotonic_ns() noexcept {
  timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return std::int64_t(ts.tv_sec) * 1'000'000'000 + ts.tv_nsec;
}
}  // namespace

Pacer::Pacer(double rate_hz, bool realtime)
    : period_s_(1.0 / rate_hz), period_ns_(std::llround(1e9 / rate_hz)), realtime_(realtime) {
  if (!(rate_hz > 0) || rate_hz > 100000) throw std::invalid_argument("rate must be in (0, 100000] Hz");
  start_ns_ = monotonic_ns() + period_ns_;
}

double Pacer::wait_for_tick(std::uint64_t k) noexcept {
  if (realtime_) {
    const std::int64_t deadline = start_ns_ + std::int64_t(k) * period_ns_;
    timespec ts{static_cast<time_t>(deadline / 1'000'000'000), static_cast<long>(deadline % 1'000'000'000)};
    while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts, nullptr) == EINTR) {
    }
  }
  return double(k) * period_s_;
}

}  // namespace palprig
