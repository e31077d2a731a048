#pragma once
// Session clocks: the monotonic time the runner is fed, in seconds since the session started.
//   SteadyClock     real time (std::chrono::steady_clock), for people
//   SimulatedClock  time jumps to whatever the loop waits for: a simulated participant's
//                   session runs as fast as the machine goes, with the same timing logic
//   scaled          SteadyClock(speed): real sleeps, time running `speed` times faster
#include <chrono>
#include <optional>

namespace palprig {

class SessionClock {
 public:
  virtual ~SessionClock() = default;
  virtual double now_s() = 0;
  virtual void wait_until(double t_s) = 0;
  // False when time only moves as the loop waits for it: nothing has a deadline, so a consumer
  // (the telemetry writer) may be waited for instead of dropping.
  virtual bool real_time() const { return true; }
  // The session time of a moment on std::chrono::steady_clock (CLOCK_MONOTONIC), such as an
  // input event's own timestamp: so a front end times an answer by when it was given, not by
  // when the loop took it. None for a clock not tied to it (simulated time).
  virtual std::optional<double> at_steady(std::chrono::steady_clock::time_point) const { return std::nullopt; }
  // The steady_clock moment of session time 0 when session time is steady_clock time (real
  // time at speed 1); none otherwise.
  virtual std::optional<std::chrono::steady_clock::time_point> steady_origin() const { return std::nullopt; }
};

class SteadyClock final : public SessionClock {
 public:
  explicit SteadyClock(double speed = 1.0);
  double now_s() override;
  void wait_until(double t_s) override;
  std::optional<double> at_steady(std::chrono::steady_clock::time_point t) const override {
    return std::chrono::duration<double>(t - start_).count() * speed_;
  }
  std::optional<std::chrono::steady_clock::time_point> steady_origin() const override {
    if (speed_ != 1.0) return std::nullopt;
    return start_;
  }

 private:
  std::chrono::steady_clock::time_point start_;
  double speed_;
};

class SimulatedClock final : public SessionClock {
 public:
  double now_s() override { return t_s_; }
  void wait_until(double t_s) override {
    if (t_s > t_s_) t_s_ = t_s;
  }
  bool real_time() const override { return false; }

 private:
  double t_s_ = 0;
};

}  // namespace palprig
