#pragma once
// CLOCK_MONOTONIC in integer nanoseconds, and an absolute sleep on it: the time base of the
// loop, the bus and tablet threads and the Modbus simulator. Absolute deadlines (TIMER_ABSTIME)
// keep periodic threads drift-free; EINTR (a signal) resumes the same sleep.
#include <time.h>

#include <cerrno>
#include <cstdint>

namespace palprig {

inline std::int64_t mono_ns() noexcept {
  timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return std::int64_t(ts.tv_sec) * 1'000'000'000 + ts.tv_nsec;
}

inline void sleep_until_ns(std::int64_t deadline_ns) noexcept {
  const timespec ts{static_cast<time_t>(deadline_ns / 1'000'000'000), static_cast<long>(deadline_ns % 1'000'000'000)};
  while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts, nullptr) == EINTR) {}
}

}  // namespace palprig
