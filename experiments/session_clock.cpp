#include "experiments/session_clock.hpp"

#include <thread>

namespace palprig {

SteadyClock::SteadyClock(double speed) : start_(std::chrono::steady_clock::now()), speed_(speed > 0 ? speed : 1.0) {}

double SteadyClock::now_s() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count() * speed_;
}

void SteadyClock::wait_until(double t_s) {
  // Absolute deadlines, so the loop's period does not drift with the work done in it.
  const auto deadline = start_ + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                     std::chrono::duration<double>(t_s / speed_));
  std::this_thread::sleep_until(deadline);
}

}  // namespace palprig
