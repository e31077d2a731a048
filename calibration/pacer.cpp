#include "calibration/pacer.hpp"

#include <cmath>
#include <stdexcept>

#include "core/error.hpp"
#include "runtime/monotonic_clock.hpp"

namespace palprig {

Pacer::Pacer(double rate_hz, bool realtime)
    : period_s_(1.0 / rate_hz), period_ns_(std::llround(1e9 / rate_hz)), realtime_(realtime) {
  if (!(rate_hz > 0) || rate_hz > 100000) throw BadInput("rate must be in (0, 100000] Hz");
  start_ns_ = mono_ns() + period_ns_;
}

double Pacer::wait_for_tick(std::uint64_t k) noexcept {
  if (realtime_) {
    const std::int64_t deadline = start_ns_ + std::int64_t(k) * period_ns_;
    sleep_until_ns(deadline);
  }
  return double(k) * period_s_;
}

}  // namespace palprig
